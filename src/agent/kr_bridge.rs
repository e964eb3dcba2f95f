//! Adapter between the agent and the KR layer: re-exports the KR types the agent uses and
//! loads knowledge with errors the compiler can report.

pub use crate::kr::{Engine, FactBase, Knowledge, KrError, Limits, NativeEngine, View};
use crate::term::Term;
use std::sync::Arc;

/// Loads knowledge clauses (shared by every agent of a program).
pub fn load_knowledge(clauses: &[Term]) -> Result<Arc<Knowledge>, KrError> {
    Knowledge::load(clauses)
}
