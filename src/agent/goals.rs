//! Goals: single goals (conjunctions of ground facts), goal bases and the attention stack.

use crate::term::Term;
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

/// A set of single goals in adoption order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GoalBase {
    goals: Vec<Goal>,
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
    /// Adds a goal unless present; true when added.
    pub fn add(&mut self, g: Goal) -> bool {
        if self.contains(&g.term) {
            return false;
        }
        self.goals.push(g);
        true
    }
    /// Removes the goals for which `pred` holds, returning them in order.
    pub fn remove_where(&mut self, mut pred: impl FnMut(&Goal) -> bool) -> Vec<Goal> {
        let mut removed = Vec::new();
        self.goals.retain(|g| {
            if pred(g) {
                removed.push(g.clone());
                false
            } else {
                true
            }
        });
        removed
    }
}

/// The attention stack: the bottom is the top-level goal base, the top the current
/// attention set.
#[derive(Clone, Debug)]
pub struct AttentionStack {
    bases: Vec<GoalBase>,
}

impl Default for AttentionStack {
    fn default() -> Self {
        AttentionStack {
            bases: vec![GoalBase::default()],
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
        self.bases.push(base);
    }
    /// Pops the current attention set (the top-level base is never popped).
    pub fn pop(&mut self) {
        if self.bases.len() > 1 {
            self.bases.pop();
        }
    }
    /// Number of bases on the stack.
    pub fn depth(&self) -> usize {
        self.bases.len()
    }
}
