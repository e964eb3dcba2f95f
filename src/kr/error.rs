//! Errors of the KR layer (values, never panics) and the resource limits of a query.

use crate::term::{Sym, Term};
use std::fmt;

/// Resource limits of one query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Maximum number of predicate calls (inferences) per query.
    pub max_inferences: u64,
    /// Maximum proof depth (nesting of predicate calls).
    pub max_depth: u32,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_inferences: 10_000_000,
            max_depth: 100_000,
        }
    }
}

/// Why a query (or loading knowledge) failed with an error rather than an answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum KrError {
    /// The inference budget ran out while calling `predicate` (`name/arity`).
    Budget { predicate: String, limit: u64 },
    /// The proof became deeper than the depth bound while calling `predicate`.
    Depth { predicate: String, limit: u32 },
    /// An ISO error term `error(Formal, Context)`, e.g. `error(instantiation_error, is/2)`.
    Iso(Term),
    /// Knowledge could not be loaded: one message per rejected clause.
    Load(Vec<LoadError>),
}

/// One rejected knowledge clause.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// Index of the clause in the list given to the loader.
    pub clause: usize,
    /// The offending predicate (`name/arity`), if the problem is a predicate.
    pub predicate: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl KrError {
    /// `error(Formal, Context)` with a `name/arity` context.
    pub fn iso(formal: Term, context: Option<(Sym, usize)>) -> KrError {
        let ctx = match context {
            Some((s, n)) => Term::compound("/", vec![Term::Atom(s), Term::Int(n as i64)]),
            None => Term::var("_"),
        };
        KrError::Iso(Term::compound("error", vec![formal, ctx]))
    }

    /// The error as a Prolog term (`error(...)`, or a descriptive term for budget and depth).
    pub fn to_term(&self) -> Term {
        match self {
            KrError::Iso(t) => t.clone(),
            KrError::Budget { predicate, limit } => Term::compound(
                "error",
                vec![
                    Term::compound(
                        "resource_error",
                        vec![Term::compound("inferences", vec![Term::Int(*limit as i64)])],
                    ),
                    Term::atom(predicate),
                ],
            ),
            KrError::Depth { predicate, limit } => Term::compound(
                "error",
                vec![
                    Term::compound(
                        "resource_error",
                        vec![Term::compound("depth", vec![Term::Int(*limit as i64)])],
                    ),
                    Term::atom(predicate),
                ],
            ),
            KrError::Load(errs) => Term::list(
                errs.iter()
                    .map(|e| Term::string(&e.message))
                    .collect::<Vec<_>>(),
            ),
        }
    }
}

impl fmt::Display for KrError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KrError::Budget { predicate, limit } => write!(
                f,
                "inference budget of {limit} exceeded (while calling {predicate})"
            ),
            KrError::Depth { predicate, limit } => {
                write!(
                    f,
                    "proof depth limit of {limit} exceeded (while calling {predicate})"
                )
            }
            KrError::Iso(t) => f.write_str(&t.to_text_limited(crate::term::print::MESSAGE_DEPTH)),
            KrError::Load(errs) => {
                for (i, e) in errs.iter().enumerate() {
                    if i > 0 {
                        writeln!(f)?;
                    }
                    write!(f, "clause {}: {}", e.clause + 1, e.message)?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for KrError {}

/// Result of the KR layer.
pub type KrResult<T> = Result<T, KrError>;
