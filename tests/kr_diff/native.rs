//! The native engine behind the same interface as `scryer::Scryer`: load clauses, run a query,
//! return the answers in the canonical form of `scryer::Outcome`.

use crate::scryer::{canonical, Outcome};
use goal::kr::{Engine, FactBase, Knowledge, NativeEngine, View};
use goal::term::Term;
use std::sync::Arc;

/// Where a program's ground facts live on the native side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facts {
    /// Knowledge clauses, like the rules.
    Knowledge,
    /// An indexed belief base (`FactBase`), queried through the belief view.
    Beliefs,
    /// The facts of one goal (a scanned slice), queried through the goal view.
    Goal,
}

/// The native engine with one loaded program: knowledge clauses and, optionally, facts in a
/// belief base or a goal.
pub struct Native {
    knowledge: Arc<Knowledge>,
    facts: FactBase,
    goal_facts: Vec<Term>,
    engine: NativeEngine,
}

impl Native {
    /// A fresh engine with empty knowledge.
    pub fn new() -> Native {
        Native {
            knowledge: Knowledge::empty(),
            facts: FactBase::new(),
            goal_facts: Vec::new(),
            engine: NativeEngine::new(1),
        }
    }

    /// Loads clauses as knowledge.
    pub fn load(&mut self, clauses: &[Term]) -> Result<(), String> {
        self.knowledge = Knowledge::load(clauses).map_err(|e| e.to_string())?;
        Ok(())
    }

    /// Loads rules as knowledge and ground facts into a belief base or a goal.
    pub fn load_split(&mut self, rules: &[Term], facts: &[Term], at: Facts) -> Result<(), String> {
        self.load(rules)?;
        match at {
            Facts::Goal => self.goal_facts = facts.to_vec(),
            _ => {
                for f in facts {
                    self.facts.insert(f.clone());
                }
            }
        }
        Ok(())
    }

    /// Runs `goal` on the belief view and returns the instances of `template`, or the error.
    pub fn query(&mut self, template: &Term, goal: &Term) -> Outcome {
        let bases = [&self.facts];
        let view = if self.goal_facts.is_empty() {
            View::beliefs(&self.knowledge, &bases)
        } else {
            View::goal(&self.knowledge, &self.goal_facts)
        };
        match self.engine.query(&view, goal) {
            Ok(answers) => Outcome::Answers(
                answers
                    .iter()
                    .map(|s| canonical(&s.apply(template)))
                    .collect(),
            ),
            Err(e) => Outcome::Error(canonical(&e.to_term())),
        }
    }
}
