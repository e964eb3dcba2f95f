//! Turns the full current truth of an entity's percepts into per-tick batches by percept type.

use super::{PerceptDecl, PerceptType};
use crate::term::{well_known, Sym, Term};

/// Per-entity memory of what was sent, producing batches according to the declared types.
#[derive(Clone, Debug)]
pub struct PerceptFilter {
    decls: Vec<(Sym, usize, PerceptType)>,
    prev: Vec<Vec<Term>>,
    first: bool,
}

impl PerceptFilter {
    /// A filter for the given declarations that has sent nothing yet.
    pub fn new(decls: &[PerceptDecl]) -> PerceptFilter {
        PerceptFilter {
            decls: decls
                .iter()
                .map(|d| (Sym::intern(&d.name), d.arity, d.kind))
                .collect(),
            prev: vec![Vec::new(); decls.len()],
            first: true,
        }
    }

    /// True until the first batch has been produced (once-percepts are only needed then).
    pub fn is_first(&self) -> bool {
        self.first
    }

    /// The index of the declaration of `term`'s predicate, if declared.
    pub fn index_of(&self, term: &Term) -> Option<usize> {
        let (name, arity) = term.functor()?;
        self.decls
            .iter()
            .position(|(n, a, _)| *n == name && *a == arity)
    }

    /// The batch for the current truth `current` (any order; undeclared percepts count as always).
    pub fn batch(&mut self, current: Vec<Term>) -> Vec<Term> {
        let mut groups = vec![Vec::new(); self.decls.len()];
        let mut undeclared = Vec::new();
        for t in current {
            match self.index_of(&t) {
                Some(i) => groups[i].push(t),
                None => undeclared.push(t),
            }
        }
        let mut out = self.batch_grouped(groups);
        out.extend(undeclared);
        out
    }

    /// The batch for the current truth given per declaration (`groups[i]` holds the current
    /// instances of declaration `i`); the output follows declaration order.
    pub fn batch_grouped(&mut self, mut groups: Vec<Vec<Term>>) -> Vec<Term> {
        groups.resize(self.decls.len(), Vec::new());
        let first = self.first;
        self.first = false;
        let mut out = Vec::new();
        for (i, now) in groups.into_iter().enumerate() {
            let prev = &mut self.prev[i];
            match self.decls[i].2 {
                PerceptType::Once => {
                    if first {
                        out.extend(now);
                    }
                }
                PerceptType::Always => out.extend(now),
                PerceptType::OnChange => {
                    // Instances come in a stable order, so plain equality is the fast path.
                    if first || (*prev != now && !same_set(prev, &now)) {
                        out.extend(now.iter().cloned());
                        *prev = now;
                    }
                }
                PerceptType::OnChangeWithNegation => {
                    if *prev == now {
                        continue;
                    }
                    for p in prev.iter() {
                        if !now.contains(p) {
                            out.push(Term::compound(well_known::NOT, vec![p.clone()]));
                        }
                    }
                    for n in &now {
                        if !prev.contains(n) {
                            out.push(n.clone());
                        }
                    }
                    *prev = now;
                }
            }
        }
        out
    }
}

/// True when `a` and `b` hold the same terms (as sets; both are small).
fn same_set(a: &[Term], b: &[Term]) -> bool {
    a.len() == b.len() && a.iter().all(|x| b.contains(x)) && b.iter().all(|x| a.contains(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decls() -> Vec<PerceptDecl> {
        vec![
            PerceptDecl::new("place", 1, PerceptType::Once),
            PerceptDecl::new("at", 1, PerceptType::OnChange),
            PerceptDecl::new("in", 1, PerceptType::OnChangeWithNegation),
            PerceptDecl::new("color", 2, PerceptType::Always),
        ]
    }

    fn t(name: &str, arg: &str) -> Term {
        Term::compound(name, vec![Term::atom(arg)])
    }

    fn show(batch: &[Term]) -> Vec<String> {
        batch.iter().map(|t| t.to_string()).collect()
    }

    #[test]
    fn each_type_is_delivered_as_declared() {
        let mut f = PerceptFilter::new(&decls());
        let color = Term::compound("color", vec![Term::Int(1), Term::atom("Red")]);
        let b1 = f.batch(vec![t("place", "A"), t("at", "A"), color.clone()]);
        assert_eq!(show(&b1), ["place('A')", "at('A')", "color(1,'Red')"]);
        let b2 = f.batch(vec![
            t("place", "A"),
            t("at", "A"),
            t("in", "R"),
            color.clone(),
        ]);
        assert_eq!(show(&b2), ["in('R')", "color(1,'Red')"]);
        let b3 = f.batch(vec![t("place", "A"), t("at", "B")]);
        assert_eq!(show(&b3), ["at('B')", "not(in('R'))"]);
        let b4 = f.batch(vec![t("place", "A"), t("at", "B")]);
        assert!(b4.is_empty());
    }
}
