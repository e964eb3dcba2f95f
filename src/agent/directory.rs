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
    /// (symbol id, position) sorted by symbol id: finding an agent by its symbol is a search
    /// over integers, not over names (sending a message does it).
    by_sym: Vec<(u32, u32)>,
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
            by_sym: sym_table(&syms),
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
    pub fn knows(&self, name: Sym) -> bool {
        position(&self.by_sym, name).is_some()
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
        assert_eq!(d.syms(), [Sym::intern("a"), Sym::intern("b")]);
        assert_eq!(d.facts().len(), 2);
        assert!(d
            .facts()
            .contains(&Term::compound(wk::AGENT, vec![Term::atom("a")])));
    }
}
