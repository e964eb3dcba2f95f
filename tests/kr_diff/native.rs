//! The native engine behind the same interface as `scryer::Scryer` (placeholder until `kr` lands).

use crate::scryer::Outcome;
use goal::term::Term;

/// False until the native engine exposes its query API (then the comparisons run).
pub const AVAILABLE: bool = false;

/// The native engine with one loaded program.
pub struct Native;

impl Native {
    /// A fresh engine.
    pub fn new() -> Native {
        Native
    }

    /// Loads clauses.
    pub fn load(&mut self, _clauses: &[Term]) -> Result<(), String> {
        Err("the native engine is not built yet".into())
    }

    /// Runs a query.
    pub fn query(&mut self, _template: &Term, _goal: &Term) -> Outcome {
        Outcome::Error("the native engine is not built yet".into())
    }
}
