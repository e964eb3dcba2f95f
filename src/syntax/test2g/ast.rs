//! The AST of a 2014 `.test2g` file (`masTest`), with byte spans.
//! Conditions and actions reuse the `.goal` AST ([`Literal`], [`Action`]).

use crate::diag::Span;
use crate::syntax::ast::{Action, Ident, Literal, Spanned};

/// `masTest { mas = "x.mas2g". timeout = N. agentTest* }`.
#[derive(Clone, Debug, PartialEq)]
pub struct MasTest {
    pub file: String,
    /// The MAS file, relative to the test file.
    pub mas: Spanned<String>,
    /// Seconds; `None` or 0 means no timeout.
    pub timeout: Option<Spanned<u64>>,
    pub agents: Vec<AgentTest>,
    pub span: Span,
}

/// `name1, name2 { namedTest* }`: tests run by the agents with these names.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentTest {
    pub agents: Vec<Ident>,
    pub tests: Vec<NamedTest>,
    pub span: Span,
}

/// `testName { section. ... }`.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedTest {
    pub name: Ident,
    pub sections: Vec<TestSection>,
    pub span: Span,
}

/// One step of a named test.
#[allow(clippy::large_enum_variant)] // few per file; boxing would only add noise
#[derive(Clone, Debug, PartialEq)]
pub enum TestSection {
    /// `do combo.`
    Do { combo: Vec<Action>, span: Span },
    /// `assert msc [: "message"].`
    Assert {
        condition: Vec<Literal>,
        message: Option<Spanned<String>>,
        span: Span,
    },
    /// `evaluate { conds } in do combo [until|while cond].`
    Evaluate {
        conditions: Vec<TemporalCondition>,
        combo: Vec<Action>,
        boundary: Option<Boundary>,
        span: Span,
    },
}

/// A condition of a test: mental literals plus at most one `do(Action)` test.
#[derive(Clone, Debug, PartialEq)]
pub struct TestCondition {
    pub literals: Vec<Literal>,
    pub done: Option<DoTest>,
    pub span: Span,
}

/// `do(Action)` or `not(do(Action))`: matches the last executed action.
#[derive(Clone, Debug, PartialEq)]
pub struct DoTest {
    pub negated: bool,
    pub action: Action,
    pub span: Span,
}

/// The temporal operators of `evaluate` conditions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TemporalOp {
    Always,
    Never,
    Eventually,
    AtEnd,
    Watch,
    /// Parsed for compatibility; not used by the runtime.
    AtStart,
}

/// `op condition`.
#[derive(Clone, Debug, PartialEq)]
pub struct TemporalPart {
    pub op: TemporalOp,
    pub condition: TestCondition,
    pub span: Span,
}

/// A condition of an `evaluate` block.
#[allow(clippy::large_enum_variant)] // few per file; boxing would only add noise
#[derive(Clone, Debug, PartialEq)]
pub enum TemporalCondition {
    /// `P -> Q -> ...`: each answer of a part starts an instance of the next.
    Chain {
        parts: Vec<TemporalPart>,
        span: Span,
    },
    /// `reactTo(P, Q)`: the first element is the trigger, the rest the reaction.
    ReactTo {
        trigger: TestCondition,
        reaction: TestCondition,
        span: Span,
    },
}

/// `until C` or `while C` after `in do ...`.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary {
    /// True for `until` (stop when C holds), false for `while` (stop when C stops holding).
    pub until: bool,
    pub condition: TestCondition,
    pub span: Span,
}

/// An element of a test condition as parsed (a literal or a `do` test).
#[derive(Clone, Debug, PartialEq)]
pub enum CondItem {
    Literal(Literal),
    Done(DoTest),
}
