//! Answers of goal literals kept while the mental state provably does not change: the module
//! loop evaluating rule after rule that finds no answer (in linear order, rules that each start
//! with `a-goal(fib(N))` ask the goal base the same question in one pass).
//!
//! Exactness: the memo is *live* only inside `rule_answers` called by the module loop (and not
//! while `goal why` records), and its entries are dropped at every loop iteration that is not
//! "evaluate one rule, which found no answers" (see `module.rs`). Between two rule evaluations
//! in a row that found no answers the loop ran nothing but condition evaluation, which only
//! reads the mental state (`&MentalState`): no action, module entry or exit, percept, mail or
//! cycle boundary came between, so every belief, goal and attention set is the one the entry
//! was made from. Only answers read from goal facts and belief lookups are kept
//! (`goal_fact_answers`: no engine, so no random draw, no output and no error to repeat), and
//! only for a positive literal about this agent's own goals with no single-goal restriction
//! (`focus=select`), as a condition's first literal under the empty substitution.

use super::super::condition::Found;
use crate::syntax::ast::MentalOp;
use crate::term::Term;
use std::sync::Arc;

/// Kept answers of goal literals (see the module doc for when they are valid).
#[derive(Clone, Debug, Default)]
pub struct GoalMemo {
    /// Whether evaluation may read and fill the memo now (set by the module loop only).
    pub live: bool,
    entries: Vec<Entry>,
}

/// The answers of one goal query from one goal base.
#[derive(Clone, Debug)]
struct Entry {
    op: MentalOp,
    top_level: bool,
    query: Term,
    answers: Arc<Found>,
}

/// Most entries kept: a pass asks a few distinct goal questions; the bound keeps memory and
/// the search small.
const MAX_ENTRIES: usize = 8;

impl GoalMemo {
    /// Forgets every entry (the state may change next).
    #[inline]
    pub fn clear(&mut self) {
        // Mostly nothing was kept: a length check instead of a clear each loop step.
        if !self.entries.is_empty() {
            self.entries.clear();
        }
    }

    /// The kept answers of `op` `query` on the top-level (`top_level`) or current goal base.
    pub fn get(&self, op: MentalOp, top_level: bool, query: &Term) -> Option<Arc<Found>> {
        self.entries
            .iter()
            .find(|e| e.op == op && e.top_level == top_level && e.query == *query)
            .map(|e| e.answers.clone())
    }

    /// Keeps the answers of `op` `query` (while there is room).
    pub fn put(&mut self, op: MentalOp, top_level: bool, query: &Term, answers: Arc<Found>) {
        if self.entries.len() < MAX_ENTRIES {
            self.entries.push(Entry {
                op,
                top_level,
                query: query.clone(),
                answers,
            });
        }
    }
}
