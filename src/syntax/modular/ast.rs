//! The AST of modular files (generations (A) and (B)): use clauses, and the module or action
//! specifications of a file, held in the 2014 AST types ([`crate::syntax::ast`]) so that every
//! later stage (validator, compiler, interpreter) reads one representation.

use crate::diag::Span;
use crate::syntax::ast::{ActionSpec, Module, Spanned};
use std::fmt::Write;

/// Which generation a file or a MAS belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Generation {
    /// 2014-16: single `.goal` files, `environment { }` MAS files.
    Classic,
    /// (A) modular GOAL, 2016+.
    Modular,
    /// (B) MARBEL, the VU course language.
    Marbel,
}

impl Generation {
    /// How the generation is named in messages.
    pub fn label(self) -> &'static str {
        match self {
            Generation::Classic => "2014 GOAL",
            Generation::Modular => "modular GOAL (2016+)",
            Generation::Marbel => "MARBEL",
        }
    }
}

/// What a `use` clause says a file is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UseCase {
    Knowledge,
    Beliefs,
    Goals,
    Module,
    ActionSpec,
    Mas,
    Planner,
}

impl UseCase {
    /// The keyword as written after `as`.
    pub fn keyword(self) -> &'static str {
        match self {
            UseCase::Knowledge => "knowledge",
            UseCase::Beliefs => "beliefs",
            UseCase::Goals => "goals",
            UseCase::Module => "module",
            UseCase::ActionSpec => "actionspec",
            UseCase::Mas => "mas",
            UseCase::Planner => "planner",
        }
    }
}

/// `use ref, ref as case.`
#[derive(Clone, Debug, PartialEq)]
pub struct UseClause {
    /// The references as written (dots of unquoted references already turned into `/`).
    pub refs: Vec<Spanned<String>>,
    pub case: Option<Spanned<UseCase>>,
    pub span: Span,
}

/// A `.mod2g` file of generation (A) or (B).
#[derive(Clone, Debug, PartialEq)]
pub struct ModFile {
    pub file: String,
    pub uses: Vec<UseClause>,
    /// The module; its kind is `User` with the declared name until a MAS gives it a role.
    pub module: Module,
}

/// An `.act2g` file.
#[derive(Clone, Debug, PartialEq)]
pub struct ActFile {
    pub file: String,
    pub uses: Vec<UseClause>,
    pub specs: Vec<ActionSpec>,
}

/// Writes use clauses for snapshots.
pub fn dump_uses(uses: &[UseClause]) -> String {
    let mut o = String::new();
    for u in uses {
        let refs: Vec<&str> = u.refs.iter().map(|r| r.value.as_str()).collect();
        let case = u.case.as_ref().map_or("", |c| c.value.keyword());
        let _ = writeln!(o, "use {} as {case} @{:?}", refs.join(", "), u.span);
    }
    o
}
