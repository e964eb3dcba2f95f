//! The initial towers of a blocks world from init parameters.
//!
//! * `start = [2, 3, 0, ...]` (GOAL's examples): the i-th number says what block i stands on,
//!   `0` for the table; the blocks are named by their positions `1..n`.
//! * `blocks = [on(a, b), on(b, table), ...]` (this project's form): named blocks.
//!
//! Every block stands on the table or on one other block, no block carries two, and no tower
//! loops back on itself.

use crate::diag::Diagnostic;
use crate::env::InitParams;
use crate::term::Term;

/// Most blocks a world may have (keeps a typo from building a huge world).
pub const MAX_BLOCKS: usize = 10_000;

/// The parameter keys the blocks world reads (`gui` is accepted and ignored: there is no GUI).
pub const PARAMS: &[&str] = &["start", "blocks", "gui"];

fn bad(msg: String) -> Vec<Diagnostic> {
    vec![Diagnostic::error("M0040", msg, "init", 0..0).with_hint(
        "write `init = [start = [2, 0, 0]]`: block i stands on the i-th number, 0 = table",
    )]
}

/// The `(block, support)` pairs described by `params`; the table is the atom `table`.
pub fn towers(params: &InitParams) -> Result<Vec<(Term, Term)>, Vec<Diagnostic>> {
    let pairs = match (params.get("start"), params.get("blocks")) {
        (Some(_), Some(_)) => {
            return Err(bad("give either `start` or `blocks`, not both".into()));
        }
        (Some(s), None) => from_start(s)?,
        (None, Some(b)) => from_blocks(b)?,
        (None, None) => Vec::new(),
    };
    check(&pairs)?;
    Ok(pairs)
}

/// A start list item as a number (`2` or `"2"`).
fn number(t: &Term) -> Option<i64> {
    match t {
        Term::Int(i) => Some(*i),
        Term::Str(s) => s.trim().parse().ok(),
        Term::Atom(a) => a.name().trim().parse().ok(),
        _ => None,
    }
}

/// The items of the list parameter `key`, at most [`MAX_BLOCKS`] of them.
fn items(list: &Term, key: &str, of_what: &str) -> Result<Vec<Term>, Vec<Diagnostic>> {
    let Some(items) = list.list_items() else {
        return Err(bad(format!(
            "`{key}` must be a list of {of_what}, got `{list}`"
        )));
    };
    if items.len() > MAX_BLOCKS {
        return Err(bad(format!(
            "`{key}` lists {} blocks; at most {MAX_BLOCKS} are allowed",
            items.len()
        )));
    }
    Ok(items)
}

fn from_start(list: &Term) -> Result<Vec<(Term, Term)>, Vec<Diagnostic>> {
    let items = items(list, "start", "numbers")?;
    let n = items.len() as i64;
    let mut out = Vec::with_capacity(items.len());
    for (i, it) in items.iter().enumerate() {
        let below = match number(it) {
            Some(0) => Term::atom("table"),
            Some(k) if (1..=n).contains(&k) => Term::Int(k),
            _ => {
                return Err(bad(format!(
                    "`start` item {} is `{it}`; it must be 0 (the table) or a block 1..{n}",
                    i + 1
                )))
            }
        };
        out.push((Term::Int(i as i64 + 1), below));
    }
    Ok(out)
}

fn from_blocks(list: &Term) -> Result<Vec<(Term, Term)>, Vec<Diagnostic>> {
    let items = items(list, "blocks", "on(X, Y)")?;
    let mut out = Vec::with_capacity(items.len());
    for it in items.iter() {
        let simple = |t: &Term| matches!(t, Term::Atom(_) | Term::Int(_));
        match it.functor() {
            Some((f, 2)) if f.name() == "on" && it.args().iter().all(simple) => {
                out.push((it.args()[0].clone(), it.args()[1].clone()))
            }
            _ => {
                return Err(bad(format!(
                    "`blocks` items must be on(Block, Below) with names, got `{it}`"
                )))
            }
        }
    }
    let is_table = |t: &Term| matches!(t, Term::Atom(s) if s.name() == "table");
    // A block named only as a support stands on the table.
    let mut extra = Vec::new();
    for (_, y) in &out {
        if !is_table(y) && !out.iter().any(|(x, _)| x == y) && !extra.contains(y) {
            extra.push(y.clone());
        }
    }
    out.extend(extra.into_iter().map(|b| (b, Term::atom("table"))));
    Ok(out)
}

/// Every block once, each carrying at most one block, and no loops.
fn check(pairs: &[(Term, Term)]) -> Result<(), Vec<Diagnostic>> {
    use std::collections::HashMap;
    let index: HashMap<&Term, usize> = pairs.iter().enumerate().map(|(i, (x, _))| (x, i)).collect();
    if index.len() != pairs.len() {
        return Err(bad("a block is placed twice".into()));
    }
    let mut carried_by: HashMap<&Term, &Term> = HashMap::new();
    for (x, y) in pairs {
        if x == y {
            return Err(bad(format!("block {x} stands on itself")));
        }
        if matches!(x, Term::Atom(s) if s.name() == "table") {
            return Err(bad("`table` cannot be a block".into()));
        }
        if index.contains_key(y) {
            if let Some(other) = carried_by.insert(y, x) {
                return Err(bad(format!(
                    "blocks {other} and {x} both stand on block {y}"
                )));
            }
        }
    }
    // Walk down from every block until the table or a block known to stand on it; meeting a
    // block of the current walk again means a loop. Each block is walked over once.
    let mut state = vec![0u8; pairs.len()]; // 0 unseen, 1 on the current walk, 2 grounded
    for (start, (name, _)) in pairs.iter().enumerate() {
        let mut path = Vec::new();
        let mut at = Some(start);
        while let Some(i) = at.filter(|&i| state[i] != 2) {
            if state[i] == 1 {
                return Err(bad(format!(
                    "the tower under block {name} loops back on itself"
                )));
            }
            state[i] = 1;
            path.push(i);
            at = index.get(&pairs[i].1).copied();
        }
        for i in path {
            state[i] = 2;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn start(items: &[i64]) -> InitParams {
        let l = Term::list(items.iter().map(|i| Term::Int(*i)).collect::<Vec<_>>());
        InitParams::from([("start".to_string(), l)])
    }

    #[test]
    fn start_list_names_blocks_by_position() {
        let t = towers(&start(&[2, 0, 0])).unwrap();
        assert_eq!(t[0], (Term::Int(1), Term::Int(2)));
        assert_eq!(t[1], (Term::Int(2), Term::atom("table")));
    }

    #[test]
    fn a_tower_of_the_largest_size_is_checked_quickly() {
        let n = MAX_BLOCKS as i64;
        let tall: Vec<i64> = (1..=n).map(|i| if i == n { 0 } else { i + 1 }).collect();
        assert_eq!(towers(&start(&tall)).unwrap().len(), MAX_BLOCKS);
    }

    #[test]
    fn bad_start_lists_are_refused() {
        for bad in [&[1][..], &[2, 2, 0], &[2, 1], &[5, 0], &[2, 3, 1]] {
            assert!(towers(&start(bad)).is_err(), "{bad:?}");
        }
    }
}
