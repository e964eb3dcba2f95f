//! Goals: single goals (conjunctions of ground facts), goal bases and the attention stack.

use crate::kr::fxhash::FxHashMap;
use crate::kr::native::code::Key;
use crate::term::{Sym, Term};
use std::sync::Arc;

/// One goal: a conjunction of ground facts, queried as its own database plus knowledge.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Goal {
    /// The conjunction as written (goals are equal when these are syntactically equal).
    pub term: Term,
    /// The conjuncts (facts of the goal's database).
    pub facts: Arc<[Term]>,
}

impl Goal {
    /// A goal from a conjunction.
    pub fn new(term: Term) -> Goal {
        let facts: Vec<Term> = term.conjuncts().into_iter().cloned().collect();
        Goal {
            term,
            facts: facts.into(),
        }
    }
}

/// A set of single goals in adoption order, indexed by the predicates of their facts and by
/// predicate and first argument.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GoalBase {
    goals: Vec<Goal>,
    /// For each predicate `name/arity`, the positions (ascending) of the goals with a fact of
    /// it: a goal condition on a predicate only knowledge-free facts answer looks at these
    /// goals alone instead of querying every goal.
    preds: FxHashMap<(Sym, u32), Vec<u32>>,
    /// The same by predicate and the key of the first argument (goal facts are ground, so
    /// every fact with arguments has one): `goal(fib(N1))` with `N1` bound looks at the goals
    /// with a `fib(N1)` fact alone, not at every `fib/1` goal.
    keys: FxHashMap<(Sym, u32, Key), Vec<u32>>,
    /// True when a goal was added without the caller having checked that it is not believed
    /// (see [`GoalBase::add_unbelieved`]): the next goal check looks at every goal.
    unchecked: bool,
    /// True once a goal had a fact without a predicate (not in the indexes) or with variables
    /// (which the first-argument index cannot place): goal checks then look at every goal.
    odd: bool,
    /// The number of times a predicate new to `preds` was indexed: tells a goal check whether
    /// the predicates it noted are still all of them.
    new_predicates: u64,
}

impl GoalBase {
    /// The goals in order.
    pub fn goals(&self) -> &[Goal] {
        &self.goals
    }
    /// True when there are no goals.
    pub fn is_empty(&self) -> bool {
        self.goals.is_empty()
    }
    /// Number of goals.
    pub fn len(&self) -> usize {
        self.goals.len()
    }
    /// True when a syntactically equal goal is present.
    pub fn contains(&self, t: &Term) -> bool {
        self.goals.iter().any(|g| &g.term == t)
    }
    /// The goals with a fact of predicate `name/arity`, in adoption order.
    pub fn with_predicate(&self, name: Sym, arity: usize) -> impl Iterator<Item = &Goal> + '_ {
        self.preds
            .get(&(name, arity as u32))
            .map_or(&[][..], |v| &v[..])
            .iter()
            .map(|&i| &self.goals[i as usize])
    }
    /// The goals with a fact of predicate `name/arity` whose first argument has key `key`, in
    /// adoption order (a superset of the goals with a fact unifying a query of that key).
    pub(crate) fn with_first_arg(
        &self,
        name: Sym,
        arity: usize,
        key: Key,
    ) -> impl Iterator<Item = &Goal> + '_ {
        self.keys
            .get(&(name, arity as u32, key))
            .map_or(&[][..], |v| &v[..])
            .iter()
            .map(|&i| &self.goals[i as usize])
    }
    /// Adds a goal unless present; true when added.
    pub fn add(&mut self, g: Goal) -> bool {
        let added = self.add_unbelieved(g);
        self.unchecked |= added;
        added
    }
    /// [`GoalBase::add`] of a goal the caller found not believed in the current mental state
    /// (as `adopt` does), so that a goal check after later updates need not look at it
    /// unless they concern its facts.
    pub fn add_unbelieved(&mut self, g: Goal) -> bool {
        if self.contains(&g.term) {
            return false;
        }
        self.index(self.goals.len(), &g);
        self.goals.push(g);
        true
    }
    /// True when a goal check must look at every goal: a goal was added by
    /// [`GoalBase::add`] since the last [`GoalBase::checked`], or a goal has a fact the
    /// indexes do not hold.
    pub fn unchecked(&self) -> bool {
        self.unchecked || self.odd
    }
    /// True when the indexes place every goal exactly: each fact is ground and has a
    /// predicate.
    pub fn exactly_indexed(&self) -> bool {
        !self.odd
    }
    /// Notes that every goal was found not believed.
    pub fn checked(&mut self) {
        self.unchecked = false;
    }
    /// The positions (ascending) of the goals with a fact of predicate `name/arity`.
    pub(crate) fn positions(&self, name: Sym, arity: u32) -> &[u32] {
        self.preds.get(&(name, arity)).map_or(&[][..], |v| &v[..])
    }
    /// The positions (ascending) of the goals with a fact of predicate `name/arity` whose
    /// first argument has key `key`.
    pub(crate) fn positions_with_key(&self, name: Sym, arity: u32, key: Key) -> &[u32] {
        self.keys
            .get(&(name, arity, key))
            .map_or(&[][..], |v| &v[..])
    }
    /// How many times a predicate no goal had before was indexed (never decreases).
    pub(crate) fn new_predicates(&self) -> u64 {
        self.new_predicates
    }
    /// The predicates the goals' facts have (in no particular order).
    pub(crate) fn predicates(&self) -> impl Iterator<Item = (Sym, u32)> + '_ {
        self.preds.keys().copied()
    }
    fn index(&mut self, pos: usize, g: &Goal) {
        for f in g.facts.iter() {
            self.odd |= f.functor().is_none() || !f.is_ground();
            if let Some((name, arity)) = f.functor() {
                let at = self.preds.entry((name, arity as u32)).or_insert_with(|| {
                    self.new_predicates += 1;
                    Vec::new()
                });
                if at.last() != Some(&(pos as u32)) {
                    at.push(pos as u32);
                }
                if let Some(key) = f.args().first().and_then(Key::of_term) {
                    let at = self.keys.entry((name, arity as u32, key)).or_default();
                    if at.last() != Some(&(pos as u32)) {
                        at.push(pos as u32);
                    }
                }
            }
        }
    }
    /// Removes the goals for which `pred` holds, returning them in order.
    pub fn remove_where(&mut self, mut pred: impl FnMut(&Goal) -> bool) -> Vec<Goal> {
        let mut gone: Vec<u32> = Vec::new();
        for (i, g) in self.goals.iter().enumerate() {
            if pred(g) {
                gone.push(i as u32);
            }
        }
        self.remove_at(&gone)
    }
    /// Removes the goals at the ascending positions `gone`, returning them in order. The
    /// indexes are mended in place: positions after a removed goal move down.
    pub fn remove_at(&mut self, gone: &[u32]) -> Vec<Goal> {
        if gone.is_empty() {
            return Vec::new();
        }
        let mut removed = Vec::with_capacity(gone.len());
        let mut next = 0;
        let mut i = 0u32;
        self.goals.retain_mut(|g| {
            let drop = gone.get(next) == Some(&i);
            i += 1;
            if drop {
                next += 1;
                removed.push(g.clone());
            }
            !drop
        });
        // A position's new value: itself less the removed positions before it.
        let shift = |p: &mut u32| -> bool {
            match gone.binary_search(p) {
                Ok(_) => false,
                Err(before) => {
                    *p -= before as u32;
                    true
                }
            }
        };
        self.preds.retain(|_, at| {
            at.retain_mut(|p| shift(p));
            !at.is_empty()
        });
        self.keys.retain(|_, at| {
            at.retain_mut(|p| shift(p));
            !at.is_empty()
        });
        removed
    }
}

/// The attention stack: the bottom is the top-level goal base, the top the current
/// attention set.
#[derive(Clone, Debug)]
pub struct AttentionStack {
    bases: Vec<GoalBase>,
    /// Pushes and pops so far: tells a goal check whether the current set is the one it
    /// looked at last.
    moves: u64,
}

impl Default for AttentionStack {
    fn default() -> Self {
        AttentionStack {
            bases: vec![GoalBase::default()],
            moves: 0,
        }
    }
}

impl AttentionStack {
    /// The current attention set.
    pub fn current(&self) -> &GoalBase {
        self.bases.last().unwrap_or(&self.bases[0])
    }
    /// The current attention set, mutably.
    pub fn current_mut(&mut self) -> &mut GoalBase {
        let n = self.bases.len() - 1;
        &mut self.bases[n]
    }
    /// The top-level goal base.
    pub fn top_level(&self) -> &GoalBase {
        &self.bases[0]
    }
    /// The top-level goal base, mutably.
    pub fn top_level_mut(&mut self) -> &mut GoalBase {
        &mut self.bases[0]
    }
    /// Every goal base, bottom first.
    pub fn all_mut(&mut self) -> &mut [GoalBase] {
        &mut self.bases
    }
    /// Pushes a new attention set.
    pub fn push(&mut self, base: GoalBase) {
        self.moves += 1;
        self.bases.push(base);
    }
    /// Pops the current attention set (the top-level base is never popped).
    pub fn pop(&mut self) {
        if self.bases.len() > 1 {
            self.moves += 1;
            self.bases.pop();
        }
    }
    /// The number of pushes and pops so far.
    pub fn moves(&self) -> u64 {
        self.moves
    }
    /// Number of bases on the stack.
    pub fn depth(&self) -> usize {
        self.bases.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn goal(text: &str) -> Goal {
        let mut r = crate::syntax::prolog::Reader::new("test");
        Goal::new(r.term(text, 0).expect("term").term)
    }

    fn names(it: impl Iterator<Item = Goal>) -> Vec<String> {
        it.map(|g| g.term.to_string()).collect()
    }

    #[test]
    fn goals_are_found_by_predicate_in_adoption_order_after_removals() {
        let mut b = GoalBase::default();
        for t in ["fib(3)", "round(2)", "(fib(2), fib(1))", "fib(0)", "done"] {
            assert!(b.add(goal(t)));
        }
        assert!(!b.add(goal("fib(3)")));
        let fib = Sym::intern("fib");
        let by = |b: &GoalBase| names(b.with_predicate(fib, 1).cloned());
        assert_eq!(by(&b), ["fib(3)", "fib(2),fib(1)", "fib(0)"]);
        assert_eq!(
            names(b.with_predicate(Sym::intern("done"), 0).cloned()),
            ["done"]
        );
        assert_eq!(b.with_predicate(fib, 2).count(), 0);
        let gone = b.remove_where(|g| g.term.to_string() == "fib(3)");
        assert_eq!(gone.len(), 1);
        assert_eq!(by(&b), ["fib(2),fib(1)", "fib(0)"]);
        assert!(b.add(goal("fib(5)")));
        assert_eq!(by(&b), ["fib(2),fib(1)", "fib(0)", "fib(5)"]);
        let first = |b: &GoalBase, n: i64| names(b.with_first_arg(fib, 1, Key::Int(n)).cloned());
        assert_eq!(first(&b, 1), ["fib(2),fib(1)"]);
        assert_eq!(first(&b, 5), ["fib(5)"]);
        assert!(first(&b, 3).is_empty());
        assert!(b.add(goal("(fib(1), fib(4))")));
        assert_eq!(first(&b, 1), ["fib(2),fib(1)", "fib(1),fib(4)"]);
        // Several goals at once, down to the last: the indexes follow.
        assert!(b.add(goal("round(3)")));
        let gone = b.remove_at(&[1, 3, 6]);
        assert_eq!(
            names(gone.into_iter()),
            ["fib(2),fib(1)", "done", "round(3)"]
        );
        assert_eq!(by(&b), ["fib(0)", "fib(5)", "fib(1),fib(4)"]);
        assert_eq!(first(&b, 1), ["fib(1),fib(4)"]);
        assert_eq!(first(&b, 5), ["fib(5)"]);
        assert_eq!(b.positions(Sym::intern("round"), 1), [0]);
        assert_eq!(b.positions_with_key(fib, 1, Key::Int(4)), [3]);
        assert!(b.positions(Sym::intern("done"), 0).is_empty());
    }
}
