//! The native engine's figures for `benches/kr.rs` (placeholder until `kr` exposes its API).

use super::Queries;
use goal::term::Term;

/// The native figures in table order (`None` = not measured).
pub fn figures(_clauses: &[Term], _q: &Queries, _pairs: usize) -> [Option<f64>; 7] {
    [None; 7]
}
