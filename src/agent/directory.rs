//! The agents of a system as every agent sees them: sorted names and the `agent(A)` facts,
//! built once and shared by all agents (so a system of N agents holds them once, not N times).

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Sym, Term};
use std::sync::Arc;

/// Known agent names (sorted, unique) and their `agent/1` facts.
#[derive(Debug, Default)]
pub struct Directory {
    names: Vec<String>,
    /// The names interned, in the same order.
    syms: Vec<Sym>,
    /// One bit per symbol id, set for the known agents: [`Directory::knows`] (asked once per
    /// message sent) is a load and a mask, not a search.
    known: Vec<u64>,
    facts: FactBase,
}

/// The positions of `syms`, sorted by symbol id for [`position`].
pub fn sym_table(syms: &[Sym]) -> Vec<(u32, u32)> {
    let mut t: Vec<(u32, u32)> = syms
        .iter()
        .enumerate()
        .map(|(i, s)| (s.0, i as u32))
        .collect();
    // The first of equal names wins, as a lookup by name would find it.
    t.sort_by_key(|&(id, i)| (id, i));
    t.dedup_by_key(|&mut (id, _)| id);
    t
}

/// The position of `s` in a table made by [`sym_table`].
pub fn position(table: &[(u32, u32)], s: Sym) -> Option<usize> {
    table
        .binary_search_by_key(&s.0, |&(id, _)| id)
        .ok()
        .map(|k| table[k].1 as usize)
}

/// A bit set over symbol ids with the bits of `syms` set (as long as the largest id needs).
fn sym_bits(syms: &[Sym]) -> Vec<u64> {
    let words = syms
        .iter()
        .map(|s| s.0 as usize / 64 + 1)
        .max()
        .unwrap_or(0);
    let mut bits = vec![0u64; words];
    for s in syms {
        bits[s.0 as usize / 64] |= 1 << (s.0 % 64);
    }
    bits
}

impl Directory {
    /// A shared directory of `names` (any order, duplicates ignored).
    pub fn new(names: &[String]) -> Arc<Directory> {
        let mut names = names.to_vec();
        names.sort();
        names.dedup();
        let syms: Vec<Sym> = names.iter().map(|n| Sym::intern(n)).collect();
        let mut facts = FactBase::new();
        for &n in &syms {
            facts.insert(Term::compound(wk::AGENT, vec![Term::Atom(n)]));
        }
        Arc::new(Directory {
            known: sym_bits(&syms),
            names,
            syms,
            facts,
        })
    }

    /// The names interned, sorted by name.
    pub fn syms(&self) -> &[Sym] {
        &self.syms
    }

    /// True when the agent named `name` is known.
    #[inline]
    pub fn knows(&self, name: Sym) -> bool {
        // Exactly the names of `syms`: the bit of each was set, and no other (see `sym_bits`).
        let id = name.0 as usize;
        self.known
            .get(id / 64)
            .is_some_and(|w| w & (1 << (id % 64)) != 0)
    }

    /// The names, sorted.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// True when `name` is known.
    pub fn contains(&self, name: &str) -> bool {
        self.names
            .binary_search_by(|n| n.as_str().cmp(name))
            .is_ok()
    }

    /// `agent(A)` for every known agent.
    pub fn facts(&self) -> &FactBase {
        &self.facts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorted_unique_names_and_facts() {
        let d = Directory::new(&["b".into(), "a".into(), "b".into()]);
        assert_eq!(d.names(), ["a", "b"]);
        assert!(d.contains("a") && d.contains("b") && !d.contains("c"));
        assert!(d.knows(Sym::intern("a")) && !d.knows(Sym::intern("c")));
        // Every symbol is asked: exactly the agents' names are known, ids past the set's end
        // included.
        let far = Sym::intern("directory_test_a_name_interned_last");
        for id in 0..=far.0 + 70 {
            assert_eq!(d.knows(Sym(id)), d.syms().contains(&Sym(id)), "symbol {id}");
        }
        assert_eq!(d.syms(), [Sym::intern("a"), Sym::intern("b")]);
        assert_eq!(d.facts().len(), 2);
        assert!(d
            .facts()
            .contains(&Term::compound(wk::AGENT, vec![Term::atom("a")])));
    }
}
