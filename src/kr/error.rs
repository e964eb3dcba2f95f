//! Errors of the KR layer (values, never panics) and the resource limits of a query.

use crate::term::{Sym, Term};
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Resource limits of one query: work (inferences, depth), memory (heap cells, answers,
/// output) and an optional way to interrupt it from outside (deadline or cancel flag).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Maximum number of predicate calls (inferences) per query; built-ins that walk lists
    /// or text count their steps too.
    pub max_inferences: u64,
    /// Maximum proof depth (nesting of predicate calls).
    pub max_depth: u32,
    /// Maximum working memory of a query in heap cells (16 bytes each): terms built, the goal
    /// stack, choicepoints and collected `findall` answers together.
    pub max_heap_cells: u64,
    /// Maximum number of answers one query may produce for a caller that takes them all.
    pub max_answers: u64,
    /// Maximum bytes of text written by output built-ins within one query.
    pub max_output: u64,
    /// Maximum length in bytes of an atom or string built at run time.
    pub max_text: u64,
    /// Maximum number of distinct atoms an engine's queries may make at run time, over the
    /// engine's whole life: atoms are never freed.
    pub max_new_atoms: u64,
    /// The query stops with [`KrError::Interrupted`] once this instant has passed.
    pub deadline: Option<Instant>,
    /// The query stops with [`KrError::Interrupted`] once this flag is set.
    pub cancel: Interrupt,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_inferences: 10_000_000,
            max_depth: 100_000,
            max_heap_cells: 16 << 20,
            max_answers: 100_000,
            max_output: 1 << 20,
            max_text: 16 << 20,
            max_new_atoms: 1_000_000,
            deadline: None,
            cancel: Interrupt::default(),
        }
    }
}

/// A shared cancel flag: whoever holds a copy can stop the queries that check it. The flag
/// lives for the rest of the process (one byte per [`Interrupt::new`]; a run makes one), which
/// keeps [`Limits`] `Copy`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Interrupt(Option<&'static AtomicBool>);

impl Interrupt {
    /// A fresh flag, not yet set.
    pub fn new() -> Interrupt {
        Interrupt(Some(Box::leak(Box::new(AtomicBool::new(false)))))
    }

    /// Sets the flag: every query checking it stops soon (within a few thousand inferences).
    pub fn set(&self) {
        if let Some(f) = self.0 {
            f.store(true, Ordering::Relaxed);
        }
    }

    /// True once the flag has been set.
    pub fn is_set(&self) -> bool {
        self.0.is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

impl PartialEq for Interrupt {
    fn eq(&self, other: &Interrupt) -> bool {
        match (self.0, other.0) {
            (Some(a), Some(b)) => std::ptr::eq(a, b),
            (None, None) => true,
            _ => false,
        }
    }
}

impl Eq for Interrupt {}

/// Why a query (or loading knowledge) failed with an error rather than an answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum KrError {
    /// The inference budget ran out while calling `predicate` (`name/arity`).
    Budget { predicate: String, limit: u64 },
    /// The proof became deeper than the depth bound while calling `predicate`.
    Depth { predicate: String, limit: u32 },
    /// A memory budget ran out (`resource` is `memory`, `answers`, `output` or `text`)
    /// while calling `predicate`.
    Resource {
        resource: &'static str,
        predicate: String,
        limit: u64,
    },
    /// The query was stopped from outside (deadline passed or cancel flag set).
    Interrupted { predicate: String },
    /// An ISO error term `error(Formal, Context)`, e.g. `error(instantiation_error, is/2)`.
    Iso(Term),
    /// A term thrown by `throw/1` that no `catch/3` caught (not an `error(_, _)` term).
    Uncaught(Term),
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

    /// The error as a Prolog term (`error(...)`, or a descriptive term for budget and depth),
    /// for showing: a culprit nested deeper than 1,000 or larger than 10,000 sub-terms is cut
    /// (`...`), so that writing it is cheap and safe.
    pub fn to_term(&self) -> Term {
        match self {
            KrError::Iso(t) | KrError::Uncaught(t) => t.truncated(1_000, 10_000),
            KrError::Resource {
                resource,
                predicate,
                ..
            } => Term::compound(
                "error",
                vec![
                    Term::compound("resource_error", vec![Term::atom(resource)]),
                    Term::atom(predicate),
                ],
            ),
            KrError::Interrupted { predicate } => Term::compound(
                "error",
                vec![Term::atom("interrupted"), Term::atom(predicate)],
            ),
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
            KrError::Resource {
                resource,
                predicate,
                limit,
            } => write!(
                f,
                "{} budget of {limit} exceeded (while calling {predicate})",
                resource_name(resource)
            ),
            KrError::Interrupted { predicate } => write!(
                f,
                "query interrupted: the cycle's time quota (--cycle-time) or the run's time limit ran out (while calling {predicate})"
            ),
            KrError::Iso(t) => write!(f, "{}", bounded_text(t)),
            KrError::Uncaught(t) => write!(f, "unhandled exception: {}", bounded_text(t)),
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

/// What a resource budget measures, for messages.
fn resource_name(resource: &str) -> &'static str {
    match resource {
        "memory" => "memory (heap cells)",
        "answers" => "answer",
        "output" => "output (bytes)",
        "text" => "text length (bytes)",
        "atoms" => "new atoms (never freed)",
        _ => "resource",
    }
}

/// Longest error text shown: a culprit can be a huge term.
pub const MAX_ERROR_TEXT: usize = 2_000;

/// `t` as text, cut to [`MAX_ERROR_TEXT`] bytes (with `...` marking the cut).
pub fn bounded_text(t: &Term) -> String {
    let mut text = t.truncated(40, 400).to_string();
    if text.len() > MAX_ERROR_TEXT {
        let mut cut = MAX_ERROR_TEXT;
        while !text.is_char_boundary(cut) {
            cut -= 1;
        }
        text.truncate(cut);
        text.push_str("...");
    }
    text
}

/// Result of the KR layer.
pub type KrResult<T> = Result<T, KrError>;
