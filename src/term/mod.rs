//! The one term type: interned atoms, terms, substitutions and unification, and printing as
//! Prolog text. Everything else (parser, KR engines, percepts, messages, traces) uses it.

pub mod instance;
pub mod ops;
pub mod print;
pub mod subst;
pub mod sym;
#[allow(clippy::module_inception)]
mod term;

pub use print::Style;
pub use subst::Subst;
pub use sym::{well_known, Sym};
pub use term::{Compound, Float, Term};
