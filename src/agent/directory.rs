//! The agents of a system as every agent sees them: sorted names and the `agent(A)` facts,
//! built once and shared by all agents (so a system of N agents holds them once, not N times).

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Term};
use std::sync::Arc;

/// Known agent names (sorted, unique) and their `agent/1` facts.
#[derive(Debug, Default)]
pub struct Directory {
    names: Vec<String>,
    facts: FactBase,
}

impl Directory {
    /// A shared directory of `names` (any order, duplicates ignored).
    pub fn new(names: &[String]) -> Arc<Directory> {
        let mut names = names.to_vec();
        names.sort();
        names.dedup();
        let mut facts = FactBase::new();
        for n in &names {
            facts.insert(Term::compound(wk::AGENT, vec![Term::atom(n)]));
        }
        Arc::new(Directory { names, facts })
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
        assert_eq!(d.facts().len(), 2);
        assert!(d
            .facts()
            .contains(&Term::compound(wk::AGENT, vec![Term::atom("a")])));
    }
}
