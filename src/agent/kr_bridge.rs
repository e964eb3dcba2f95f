//! Adapter between the agent and the KR layer: re-exports the KR types the agent uses and
//! loads knowledge with errors the compiler can report.

pub use crate::kr::{
    AgentEngine, Engine, FactBase, Knowledge, KrError, KrKind, Limits, NativeEngine, View,
};
use crate::term::Term;
use std::sync::Arc;

/// Loads knowledge clauses (shared by every agent of a program).
/// Knowledge that only the scryer engine runs (DCG rules, `catch/3`) is compiled from native
/// stand-ins and kept as written for scryer; agents on the native engine refuse it at launch.
pub fn load_knowledge(clauses: &[Term]) -> Result<Arc<Knowledge>, KrError> {
    if crate::kr::choice::needs_scryer(clauses).is_some() {
        return Knowledge::load_as(clauses, &crate::kr::choice::native_stand_ins(clauses));
    }
    Knowledge::load(clauses)
}
