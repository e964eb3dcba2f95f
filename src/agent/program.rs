//! A compiled agent program: modules, rule blocks, action specs and knowledge, built once from
//! the AST and shared (via `Arc`) by every agent that runs it.

use super::conjunction::PlanCell;
use super::kr_bridge::Knowledge;
use crate::diag::{line_col, Diagnostic};
use crate::syntax::ast::{self, ExitCondition, Focus, MentalOp, Mood, Order};
use crate::syntax::goal::imports::Imports;
use crate::term::{Sym, Term};
use std::sync::Arc;

/// Which kind of module.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModuleKind {
    Init,
    Main,
    Event,
    Shutdown,
    User,
}

/// A module ready to run.
#[derive(Clone, Debug)]
pub struct ModuleDef {
    pub name: String,
    pub kind: ModuleKind,
    /// Parameter variables.
    pub params: Vec<Term>,
    pub exit: ExitCondition,
    pub focus: Focus,
    /// Beliefs inserted on entry.
    pub beliefs: Vec<Term>,
    /// Goals adopted on entry (parameters substituted).
    pub goals: Vec<Term>,
    /// The module's rules (index into `Program::blocks`).
    pub block: usize,
    pub line: usize,
}

/// A list of rules with their evaluation order.
#[derive(Clone, Debug)]
pub struct Block {
    pub rules: Vec<RuleDef>,
    pub order: Order,
}

/// The kind of a rule.
#[derive(Clone, Debug, PartialEq)]
pub enum RuleKind {
    If,
    Forall,
    /// `listall V <- C do B` with the variable `V`.
    Listall(Sym),
}

/// One literal of a condition after macro expansion.
#[derive(Clone, Debug, PartialEq)]
pub enum Lit {
    True,
    Mental {
        negated: bool,
        /// `self.` (top-level goal base) rather than `this.` (current attention set).
        top_level: bool,
        /// Other agents' mental models to query instead of this agent's own state.
        about: Option<About>,
        op: MentalOp,
        query: Term,
        /// `query` analysed for answering without the engine (made on first use).
        plan: PlanCell,
    },
}

/// Whose mental models a condition literal queries (selectors other than `this`/`self`).
#[derive(Clone, Debug, PartialEq)]
pub enum About {
    /// Every known agent, this one included: the same answer in all.
    All,
    /// Every other agent: the same answer in all.
    AllOther,
    /// Any known agent, this one included.
    Some,
    /// Any other agent.
    SomeOther,
    /// The named agents (terms, possibly variables bound earlier): the same answer in all.
    Agents(Vec<Term>),
}

/// A rule ready to run.
#[derive(Clone, Debug)]
pub struct RuleDef {
    pub kind: RuleKind,
    pub cond: Vec<Lit>,
    pub body: Body,
    /// `module:line`, used in traces and errors.
    pub label: Arc<str>,
    pub line: usize,
    /// The file the rule is written in, and its source text on one line (comments left out,
    /// a nested block's rules elided), as `goal why` shows it.
    pub file: Arc<str>,
    pub text: Arc<str>,
    /// The body calls a `focus=select` module (evaluate the condition per goal).
    pub per_goal: bool,
}

/// A rule body.
#[derive(Clone, Debug)]
pub enum Body {
    Combo(Vec<ActionDef>),
    /// A nested rule block (index into `Program::blocks`).
    Block(usize),
}

/// Receivers of a send.
#[derive(Clone, Debug, PartialEq)]
pub enum Receivers {
    All,
    AllOther,
    SelfAgent,
    Agents(Vec<Term>),
}

/// An action of a combo.
#[derive(Clone, Debug)]
pub struct ActionDef {
    pub kind: Act,
    pub line: usize,
}

/// The forms of an action.
#[derive(Clone, Debug)]
pub enum Act {
    Adopt {
        top_level: bool,
        content: Term,
    },
    Drop(Term),
    Insert(Term),
    Delete(Deletion),
    Send {
        to: Receivers,
        mood: Mood,
        content: Term,
        once: bool,
    },
    Print(Term),
    Log(Term),
    ExitModule,
    /// Call of a module (index into `Program::modules`).
    Module {
        module: usize,
        args: Vec<Term>,
    },
    /// A user action (index into `Program::specs`).
    Spec {
        spec: usize,
        args: Vec<Term>,
    },
    /// `sleep`, timers and channels (modular GOAL).
    Timing {
        op: ast::TimingOp,
        args: Vec<Term>,
    },
}

/// A `delete` action.
#[derive(Clone, Debug)]
pub struct Deletion {
    /// The fact pattern.
    pub fact: Term,
    /// True when the pattern is, by its form, the `sent/2` fact of the nearest earlier send of
    /// its combo (see `message::link_sent_deletes`): the mailbox may then find it by the
    /// identity the send left.
    pub of_send: bool,
}

impl Deletion {
    /// A delete of `fact`, not linked to a send.
    pub fn new(fact: Term) -> Deletion {
        Deletion {
            fact,
            of_send: false,
        }
    }
}

/// A user action specification.
#[derive(Clone, Debug)]
pub struct SpecDef {
    pub name: Sym,
    /// Parameters (variables renamed apart from rule variables).
    pub params: Vec<Term>,
    pub env: bool,
    pub pre: Term,
    pub post: Term,
}

/// A compiled program.
#[derive(Debug)]
pub struct Program {
    pub file: String,
    pub source: Arc<str>,
    pub knowledge: Arc<Knowledge>,
    pub modules: Vec<ModuleDef>,
    pub blocks: Vec<Block>,
    pub specs: Vec<SpecDef>,
    pub init: Option<usize>,
    pub main: usize,
    pub event: Option<usize>,
    /// Modular GOAL's shutdown module, run once when the agent stops.
    pub shutdown: Option<usize>,
    /// Warnings found while compiling.
    pub warnings: Vec<Diagnostic>,
    /// Some query mentions `newpercept` (so the raw batch must be kept as facts).
    pub uses_newpercept: bool,
    /// Some condition queries other agents' mental models (so messages must update them).
    pub uses_models: bool,
    /// Something in the program can see `session/4` facts (so the agent follows its own
    /// conversations; see `mentions.rs`).
    pub uses_sessions: bool,
    /// A modular program: a send to a name that is no agent goes to that channel's subscribers
    /// (a 2014 program drops it with a warning).
    pub channels: bool,
    /// Macros and callable names, kept to compile code from outside the program
    /// ([`Program::extend`]).
    pub(crate) names: super::compile::Names,
}

/// Code from outside a program (a test file) compiled against it by [`Program::extend`].
#[derive(Debug)]
pub struct Extension {
    /// A copy of the program with one extra rule block per action sequence.
    pub program: Arc<Program>,
    /// The extra blocks, in the order of the action sequences: one `if true then A` rule per
    /// action, run in order (`linearall`), so a disabled action is skipped.
    pub blocks: Vec<usize>,
    /// The conditions, with the program's macros expanded.
    pub conditions: Vec<Vec<Lit>>,
}

impl Program {
    /// 1-based line of a byte offset in the program source.
    pub fn line(&self, offset: usize) -> usize {
        line_col(&self.source, offset).0
    }

    /// Parses and compiles `.goal` text; syntax or compile errors are returned as diagnostics.
    pub fn from_source(file: &str, source: &str) -> Result<Arc<Program>, Vec<Diagnostic>> {
        let (ast, diags) = crate::syntax::goal::parse_goal(file, source);
        if diags.iter().any(Diagnostic::is_error) {
            return Err(diags);
        }
        let mut p = Program::compile(&ast, source)?;
        if let Some(prog) = Arc::get_mut(&mut p) {
            prog.warnings.splice(0..0, diags);
        }
        Ok(p)
    }

    /// Compiles a parsed program (its imports are not read: see [`Program::compile_with`]).
    pub fn compile(ast: &ast::AgentProgram, source: &str) -> Result<Arc<Program>, Vec<Diagnostic>> {
        Program::compile_with(ast, source, &Imports::default())
    }

    /// Compiles a parsed program with what its imports bring in: the modules of `.mod2g` files
    /// and the clauses of `.pl` files (which join the knowledge). The caller reads the imports
    /// (`syntax::goal::imports::read_imports`): the agent layer does no I/O.
    pub fn compile_with(
        ast: &ast::AgentProgram,
        source: &str,
        imports: &Imports,
    ) -> Result<Arc<Program>, Vec<Diagnostic>> {
        let units: Vec<super::compile::Unit<'_>> = imports
            .modules
            .iter()
            .map(|m| super::compile::Unit {
                file: &m.file,
                source: &m.source,
                module: &m.module,
            })
            .collect();
        let knowledge: Vec<Term> = imports.knowledge.iter().map(|l| l.term.clone()).collect();
        super::compile::compile(ast, source, &units, &knowledge)
    }

    /// Compiles action sequences and conditions written in `file` (e.g. a `.test2g` file, text
    /// `source`) against this program: actions may call its modules and action specs,
    /// conditions may use its macros. Unknown names are errors.
    pub fn extend(
        &self,
        file: &str,
        source: &str,
        combos: &[Vec<ast::Action>],
        conditions: &[Vec<ast::Literal>],
    ) -> Result<Extension, Vec<Diagnostic>> {
        super::compile::extend(self, file, source, combos, conditions)
    }
}
