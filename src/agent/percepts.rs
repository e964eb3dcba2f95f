//! The typed percept base: percepts are kept according to the type the environment declares
//! for their predicate, and `bel(percept(X))` reads this base. A negated percept `not(p)` of
//! the current batch removes `p` from the base; the cycle's raw batch also answers
//! `percept(not(p))` for that one cycle (programs for BW4T clients up to 3.8 delete beliefs with
//! `forall bel(percept(not(in(R)))) do delete(in(R))`).

use super::kr_bridge::FactBase;
use crate::kr::fxhash::{FxHashMap, FxHashSet};
use crate::term::{well_known as wk, Sym, Term};
use serde::Serialize;
use std::sync::OnceLock;

/// How the environment sends a percept (and so how long the agent keeps it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PerceptType {
    /// Sent once; kept until a `not(p)` percept deletes it.
    Once,
    /// Sent when its value changes; a batch with this predicate replaces all its old facts.
    OnChange,
    /// Sent on change, with `not(p)` when `p` stops holding; facts are added and deleted.
    OnChangeNeg,
    /// Sent every tick; each batch replaces the predicate's facts (absent means no longer true).
    Always,
}

/// Percept types by `(name, arity)`; unknown percepts are `Always`.
#[derive(Clone, Debug, Default)]
pub struct PerceptTypes {
    /// Keyed by interned name: looked up for every percept fact of every cycle (membership
    /// only, so the ids' order never shows).
    map: FxHashMap<(Sym, usize), PerceptType>,
}

impl PerceptTypes {
    /// Builds the map from declarations.
    pub fn new(decls: impl IntoIterator<Item = ((String, usize), PerceptType)>) -> PerceptTypes {
        PerceptTypes {
            map: decls
                .into_iter()
                .map(|((name, arity), t)| ((Sym::intern(&name), arity), t))
                .collect(),
        }
    }

    /// The type of a percept term.
    pub fn of(&self, t: &Term) -> PerceptType {
        match t.functor() {
            Some(key) if !self.map.is_empty() => {
                self.map.get(&key).copied().unwrap_or(PerceptType::Always)
            }
            _ => PerceptType::Always,
        }
    }
}

/// Changes made to the percept base by one batch.
#[derive(Debug, Default)]
pub struct PerceptChanges {
    /// Percepts that became visible.
    pub added: Vec<Term>,
    /// Percepts that stopped being visible.
    pub removed: Vec<Term>,
}

/// The percept base: facts `percept(P)`.
#[derive(Clone, Debug, Default)]
pub struct PerceptBase {
    facts: FactBase,
    /// The raw batch of the current cycle: `newpercept(P)` facts (for edge-triggered rules,
    /// when the program asks for them) and `percept(not(p))` for its negations.
    batch: FactBase,
}

fn wrap(p: &Term) -> Term {
    Term::compound(wk::PERCEPT, vec![p.clone()])
}

impl PerceptBase {
    /// The facts (`percept(P)`) for queries.
    pub fn facts(&self) -> &FactBase {
        &self.facts
    }

    /// The current cycle's raw batch: `newpercept(P)` and `percept(not(p))` facts.
    pub fn batch(&self) -> &FactBase {
        &self.batch
    }

    /// True when `p` is currently perceived.
    pub fn contains(&self, p: &Term) -> bool {
        self.facts.contains(&wrap(p))
    }

    /// Applies one batch according to the types; the changes are listed only when `record`
    /// asks for them (the trace records them).
    pub fn apply(
        &mut self,
        batch: &[Term],
        types: &PerceptTypes,
        keep_batch: bool,
        record: bool,
    ) -> PerceptChanges {
        let mut ch = PerceptChanges::default();
        if !self.batch.is_empty() {
            self.batch.clear();
        }
        static NEWPERCEPT: OnceLock<Sym> = OnceLock::new();
        let newpercept = *NEWPERCEPT.get_or_init(|| Sym::intern("newpercept"));
        for p in batch.iter().filter(|_| keep_batch) {
            self.batch
                .insert(Term::compound(newpercept, vec![p.clone()]));
        }
        let mut positive: Vec<Term> = Vec::with_capacity(batch.len());
        let mut negative: Vec<&Term> = Vec::new();
        for p in batch {
            if p.is_functor(wk::NOT, 1) {
                negative.push(&p.args()[0]);
            } else if p.functor().is_some() {
                // Wrapped once: the same term is looked up and then stored.
                positive.push(wrap(p));
            }
        }
        if self.replaced_whole(&positive, types) {
            // The common case of an environment that resends everything: no stored fact
            // survives, so empty the base at once instead of finding and deleting each.
            if record {
                ch.removed
                    .extend(self.facts.iter().map(|f| f.args()[0].clone()));
            }
            self.facts.delete_all();
        } else if !self.facts.is_empty() {
            self.remove_stale(&positive, types, record.then_some(&mut ch));
        }
        for n in negative {
            if self.facts.delete(&wrap(n)) && record {
                ch.removed.push(n.clone());
            }
        }
        for p in batch.iter().filter(|p| p.is_functor(wk::NOT, 1)) {
            self.batch.insert(wrap(p));
        }
        for w in positive {
            let p = record.then(|| w.args()[0].clone());
            if self.facts.insert(w) {
                ch.added.extend(p);
            }
        }
        ch
    }

    /// True when the batch (wrapped positive percepts) replaces every stored fact: all are
    /// `Always` percepts and none of them is sent again.
    fn replaced_whole(&self, positive: &[Term], types: &PerceptTypes) -> bool {
        !self.facts.is_empty()
            && positive.iter().all(|w| !self.facts.contains(w))
            && self
                .facts
                .iter()
                .all(|f| types.of(&f.args()[0]) == PerceptType::Always)
    }

    /// Removes the facts the batch replaces: all `Always` ones and the `OnChange` ones whose
    /// predicate the batch mentions, unless the batch sends them again.
    fn remove_stale(
        &mut self,
        positive: &[Term],
        types: &PerceptTypes,
        mut ch: Option<&mut PerceptChanges>,
    ) {
        let in_batch: FxHashSet<&Term> = positive.iter().collect();
        // Membership only (never reaches output), so ordering by id is harmless here.
        let mut mentioned: Vec<(Sym, usize)> = positive
            .iter()
            .filter_map(|w| w.args()[0].functor())
            .collect();
        mentioned.sort_unstable();
        mentioned.dedup();
        let stale: Vec<Term> = self
            .facts
            .iter()
            .filter(|f| {
                let p = &f.args()[0];
                match types.of(p) {
                    PerceptType::Always => true,
                    PerceptType::OnChange => p.functor().is_some_and(|k| mentioned.contains(&k)),
                    _ => false,
                }
            })
            .filter(|f| !in_batch.contains(f))
            .cloned()
            .collect();
        for f in stale {
            self.facts.delete(&f);
            if let Some(ch) = ch.as_deref_mut() {
                ch.removed.push(f.args()[0].clone());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(name: &str, arg: &str) -> Term {
        Term::compound(name, vec![Term::atom(arg)])
    }

    fn not(p: Term) -> Term {
        Term::compound(wk::NOT, vec![p])
    }

    fn shown(base: &PerceptBase) -> Vec<String> {
        base.facts().iter().map(|f| f.to_string()).collect()
    }

    #[test]
    fn an_always_batch_replaces_stale_facts_and_keeps_repeated_ones_in_place() {
        let types = PerceptTypes::default();
        let mut base = PerceptBase::default();
        base.apply(&[t("at", "r1"), t("seen", "a")], &types, false, true);
        let edits = base.facts().edits();
        // Nothing repeated: the whole base goes, removals in stored order.
        let ch = base.apply(&[t("seen", "b"), t("at", "r2")], &types, false, true);
        assert_eq!(ch.removed, vec![t("at", "r1"), t("seen", "a")]);
        assert_eq!(ch.added, vec![t("seen", "b"), t("at", "r2")]);
        assert_eq!(shown(&base), ["percept(seen(b))", "percept(at(r2))"]);
        assert_eq!(base.facts().edits(), edits + 4, "one edit per change");
        // One fact repeated: it stays where it was, the new one goes after it.
        let ch = base.apply(&[t("seen", "c"), t("at", "r2")], &types, false, true);
        assert_eq!(ch.removed, vec![t("seen", "b")]);
        assert_eq!(ch.added, vec![t("seen", "c")]);
        assert_eq!(shown(&base), ["percept(at(r2))", "percept(seen(c))"]);
    }

    #[test]
    fn changes_are_listed_only_when_recorded_and_the_base_is_the_same() {
        let types = PerceptTypes::new([(("in".to_string(), 1), PerceptType::OnChangeNeg)]);
        let batches = [
            vec![t("at", "r1"), t("in", "a")],
            vec![t("at", "r2"), t("in", "a")],
            vec![t("at", "r3"), not(t("in", "a"))],
        ];
        let (mut quiet, mut loud) = (PerceptBase::default(), PerceptBase::default());
        for b in &batches {
            let ch = quiet.apply(b, &types, false, false);
            assert!(ch.added.is_empty() && ch.removed.is_empty());
            let ch = loud.apply(b, &types, false, true);
            assert!(!ch.added.is_empty() || !ch.removed.is_empty());
            assert_eq!(shown(&quiet), shown(&loud));
        }
    }

    #[test]
    fn a_batch_keeps_once_percepts_it_does_not_repeat() {
        let types = PerceptTypes::new([(("color".to_string(), 1), PerceptType::Once)]);
        let mut base = PerceptBase::default();
        base.apply(&[t("color", "red"), t("at", "r1")], &types, false, true);
        let ch = base.apply(&[t("at", "r2")], &types, false, true);
        assert_eq!(ch.removed, vec![t("at", "r1")]);
        assert_eq!(shown(&base), ["percept(color(red))", "percept(at(r2))"]);
    }

    #[test]
    fn a_negated_percept_is_visible_for_its_cycle_only() {
        let types = PerceptTypes::new([(("in".to_string(), 1), PerceptType::OnChangeNeg)]);
        let mut base = PerceptBase::default();
        base.apply(&[t("in", "room1")], &types, false, true);
        assert!(base.contains(&t("in", "room1")));
        let ch = base.apply(&[not(t("in", "room1"))], &types, false, true);
        assert_eq!(ch.removed, vec![t("in", "room1")]);
        assert!(!base.contains(&t("in", "room1")));
        let negated = wrap(&not(t("in", "room1")));
        assert!(
            !base.facts().contains(&negated),
            "the typed base keeps no negations"
        );
        assert!(
            base.batch().contains(&negated),
            "percept(not(in(room1))) this cycle"
        );
        base.apply(&[], &types, false, true);
        assert!(!base.batch().contains(&negated), "gone in the next cycle");
    }
}
