//! The knowledge-representation boundary (a trait) and its engines.
//!
//! # Overview
//!
//! GOAL agents keep their mental state in Prolog: *knowledge* (clauses shared by every agent
//! running the same program), *beliefs*, typed *percepts* (`percept(P)`), a *mailbox*
//! (`received/2`, `sent/2`) and `agent/1`/`me/1` facts, and *goals* (each goal a small set of
//! ground facts queried together with the knowledge). This module offers exactly that:
//!
//! * [`Knowledge`]: compiled clauses, loaded once with [`Knowledge::load`] and shared through
//!   `Arc` (per-agent state never copies it). Loading rejects protected predicates (`assert`,
//!   `retract`, `:`, `catch`, directives, ... see docs/prolog.md), redefinitions of
//!   built-ins, and clauses whose head is not callable, with a [`KrError::Load`] listing every
//!   offending clause and naming the predicate. [`Knowledge::check_query`] applies the same
//!   check to a query or condition.
//! * [`FactBase`]: an indexed set of ground facts (by predicate and by the first two
//!   arguments; a compound argument is keyed by its functor). [`FactBase::insert`] and
//!   [`FactBase::delete`] are O(1) expected, return whether anything changed, and free memory
//!   (no tombstones), so a million insert/delete pairs leave the base where it started.
//!   Iteration is in insertion order, which makes answers deterministic.
//! * [`View`]: what one query sees. [`View::beliefs`] is knowledge + a list of fact bases (the
//!   agent passes beliefs, percepts, mailbox and its `agent/1`/`me/1` base);
//!   [`View::goal`] is knowledge + the facts of one goal (a slice of ground terms, scanned, not
//!   indexed). Knowledge clauses are tried first; a predicate defined by knowledge clauses is
//!   answered from those clauses only (GOAL forbids defining a predicate in both knowledge and
//!   beliefs). Predicates with neither clauses nor facts simply fail (GOAL semantics); calling
//!   an unbound variable is an instantiation error.
//! * [`Engine`]: the query interface, implemented by [`NativeEngine`] (the default; a
//!   scryer-backed engine can implement the same trait; [`Knowledge::source`] keeps the clauses
//!   as loaded for such an engine).
//!   [`NativeEngine::solve`] streams answers to a callback instead of collecting them. `query` returns every answer as a
//!   [`Subst`] over the query's variables, in Prolog solution order; `query_first` stops at the
//!   first; `holds` is the cheap yes/no check for conditions such as `bel(on(a,b))`.
//!   Variables left unbound by an answer are not in the substitution; variables bound to each
//!   other are bound to the first query variable; other unbound variables inside answers are
//!   named `_R0`, `_R1`, ...
//! * [`Update`]: a GOAL update (a conjunction of literals, `not(L)` marking deletions) split into
//!   its delete and add lists and applied to a base (delete first, then add).
//! * Budgets ([`Limits`]): besides inferences and depth, a query has a memory budget (heap
//!   cells, counting the goal stack, choicepoints and `findall` bags), an answer budget (number
//!   and total size of the answers a caller collects), an output budget and a maximum text
//!   length for atoms and strings built at run time. Resuming a choicepoint counts as an
//!   inference, so pure backtracking loops meet the budget too. Every 1,024 inferences the
//!   solver also checks an optional deadline and an [`Interrupt`] flag that another thread can
//!   set, so `--time-limit` and test timeouts always stop a query. Built-ins that allocate or
//!   walk in proportion to their input check first (`native/budget.rs`), and cyclic input to
//!   them is `representation_error(cyclic_term)`.
//! * Exceptions: `catch/3` and `throw/1` follow ISO; errors raised by built-ins are catchable
//!   `error(Formal, Context)` terms. Budget, depth, memory and interruption errors are not
//!   catchable. Protected predicates called at run time (`assert/1`, ...) raise
//!   `permission_error(access, private_procedure, PI)` with a hint that agents change beliefs
//!   with `insert`/`delete`.
//! * Errors are values ([`KrError`]): an exceeded inference budget or depth bound (naming the
//!   predicate being called) or an ISO error term such as `error(instantiation_error, is/2)`,
//!   `error(type_error(evaluable, foo/0), _)`, `error(evaluation_error(zero_divisor), _)`.
//!   [`KrError::to_term`] gives a printable term. No query can panic, hang (see [`Limits`]) or
//!   overflow the Rust stack: the solver, unification, comparison, copying and arithmetic are
//!   iterative. The depth bound counts the length of the continuation (pending goals), so
//!   deterministic tail recursion over a long list is fine while `p :- p, q.` or a
//!   left-recursive rule stops with [`KrError::Depth`]; `p :- p.` runs in constant space and
//!   stops at the inference budget. Cyclic terms (possible without the occurs check, e.g.
//!   `X = f(X)`) give `error(representation_error(cyclic_term), _)` instead of endless loops,
//!   and terms nested deeper than 10,000 cannot be written (`resource_error(print_depth)`),
//!   since the term printer recurses.
//!
//! ```
//! use goal::kr::{Engine, FactBase, Knowledge, NativeEngine, View};
//! use goal::syntax::prolog::Reader;
//! let mut r = Reader::new("example");
//! let (clauses, _) = r.clauses("clear(X) :- block(X), \\+ on(_, X).", 0);
//! let kn = Knowledge::load(&clauses.into_iter().map(|c| c.term).collect::<Vec<_>>()).unwrap();
//! let mut beliefs = FactBase::new();
//! for f in ["block(a)", "block(b)", "on(a, b)"] {
//!     beliefs.insert(r.term(f, 0).unwrap().term);
//! }
//! let mut engine = NativeEngine::new(42);
//! let q = r.term("clear(X)", 0).unwrap().term;
//! let answers = engine.query(&View::beliefs(&kn, &[&beliefs]), &q).unwrap();
//! assert_eq!(answers.len(), 1);
//! assert_eq!(answers[0].iter().next().unwrap().1.to_string(), "a");
//! ```
//!
//! # The native engine
//!
//! `native/` holds a Prolog engine written for GOAL's needs: terms are copied onto a heap of
//! cells (`store.rs`) with a trail; knowledge clauses are compiled to flat cells with numbered
//! variable slots (`code.rs`), so a head is unified directly against the goal and only the body
//! is built; `machine.rs` (with `control.rs` and `facts.rs`) runs SLD resolution with an explicit goal-frame arena and choicepoint
//! stack (cut barriers per clause, opaque `call/N`, `\+`, `->`, `*->`, `findall/3` collecting
//! off-heap). Clauses are indexed on the first argument when a predicate has four or more (and on
//! the second, used when the first argument of the goal is unbound).
//! Built-ins are native Rust (`builtins.rs`, `arith.rs`, `text.rs`, `lists.rs`, `output.rs`)
//! or standard Prolog definitions compiled once per process (`prelude.rs`: `append/3`,
//! `select/3`, `maplist/2..5`, `foldl/4..6`, `bagof/3`, `setof/3`, `aggregate_all/3,4`, ...).
//! A program may redefine library predicates (`append/3`, ...) but not ISO built-ins; the
//! library's own clauses keep calling the library definitions (as SWI-Prolog modules do).
//! Body goals are resolved to their predicate when knowledge is loaded, so a call costs no
//! table lookup.
//! Output built-ins write to a buffer taken with [`Engine::take_output`]; `random/1` and friends
//! use the engine's seeded ChaCha8 RNG. The solver's buffers are per thread and reused by every
//! query, so an agent only holds its [`NativeEngine`] (limits, RNG, output buffer, and the
//! queries of its rule conditions as placed on the heap: [`NativeEngine::query_upto_in`] places
//! a query once and copies its cells on later calls, with the bindings' values in cells of
//! their own).

pub mod choice;
pub mod error;
pub mod factbase;
pub(crate) mod fxhash;
pub mod knowledge;
pub mod native;
#[cfg(feature = "scryer")]
pub mod scryer;
pub mod update;

pub use choice::{AgentEngine, KrKind};
pub use error::{Interrupt, KrError, KrResult, Limits, LoadError};
pub use factbase::FactBase;
pub use knowledge::Knowledge;
pub use native::NativeEngine;
pub use update::Update;

use crate::term::{Subst, Term};

/// What a query sees: knowledge plus fact bases (belief view) or plus one goal's facts.
#[derive(Clone, Copy)]
pub struct View<'a> {
    /// The program's knowledge (and the library).
    pub knowledge: &'a Knowledge,
    /// Indexed fact bases, searched in order.
    pub bases: &'a [&'a FactBase],
    /// The facts of one goal (scanned in order after the bases).
    pub goal_facts: &'a [Term],
}

impl<'a> View<'a> {
    /// The belief view: knowledge + beliefs, percepts, mailbox, ... (in the given order).
    pub fn beliefs(knowledge: &'a Knowledge, bases: &'a [&'a FactBase]) -> View<'a> {
        View {
            knowledge,
            bases,
            goal_facts: &[],
        }
    }

    /// The view of one goal: knowledge + the goal's facts.
    pub fn goal(knowledge: &'a Knowledge, facts: &'a [Term]) -> View<'a> {
        View {
            knowledge,
            bases: &[],
            goal_facts: facts,
        }
    }
}

/// A Prolog engine behind the KR boundary.
pub trait Engine {
    /// Every answer of `query` in Prolog solution order.
    fn query(&mut self, view: &View, query: &Term) -> KrResult<Vec<Subst>>;
    /// The first answer of `query`, if any.
    fn query_first(&mut self, view: &View, query: &Term) -> KrResult<Option<Subst>>;
    /// True when `query` has an answer.
    fn holds(&mut self, view: &View, query: &Term) -> KrResult<bool>;
    /// Takes the text written by output built-ins (`write/1`, `format/2`, ...) so far.
    fn take_output(&mut self) -> String;
}
