//! Parser output for `.mas2g` before checking: sections as written, with generic `key = value`
//! parameters (the builder in `mod.rs` turns them into the AST and reports misuse).

use super::ast::{AgentName, InitParam, Spanned};
use crate::diag::Span;

/// A section as written (duplicates are merged by the builder).
#[derive(Clone, Debug, PartialEq)]
pub enum Section {
    Environment {
        items: Vec<EnvItem>,
        span: Span,
    },
    AgentFiles {
        files: Vec<RawAgentFile>,
        span: Span,
    },
    LaunchPolicy {
        rules: Vec<RawLaunchRule>,
        span: Span,
    },
}

/// `env = "..."` or `init = [...]` inside `environment`.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvItem {
    Env(Spanned<String>, Span),
    Init(Vec<InitParam>, Span),
}

/// `key = value` in an agent file's options or an entity constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct RawParam {
    pub key: Spanned<String>,
    pub value: RawValue,
    pub span: Span,
}

/// The value of a [`RawParam`].
#[derive(Clone, Debug, PartialEq)]
pub enum RawValue {
    Ident(Spanned<String>),
    Int(Spanned<i64>),
    Str(Spanned<String>),
}

/// An agent file entry as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawAgentFile {
    pub path: Spanned<String>,
    pub params: Vec<RawParam>,
    pub span: Span,
}

/// The entity part of a conditional launch rule as written.
#[derive(Clone, Debug, PartialEq)]
pub enum RawEntitySpec {
    Any(Span),
    Constraints(Vec<RawParam>, Span),
}

/// A launch instruction as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawInstruction {
    pub name: Option<AgentName>,
    pub reference: Spanned<String>,
    pub count: Option<Spanned<i64>>,
    pub span: Span,
}

/// A launch rule as written.
#[derive(Clone, Debug, PartialEq)]
pub struct RawLaunchRule {
    pub condition: Option<RawEntitySpec>,
    pub instructions: Vec<RawInstruction>,
    pub span: Span,
}
