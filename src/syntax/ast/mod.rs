//! The AST of `.goal` agent programs and `.mod2g` module files, with byte spans on every node.
//!
//! KR (Prolog) content is held as [`Located`] terms (term plus spans), so an interpreter can run
//! the tree directly. `dump` prints a compact text form for snapshots.

pub mod dump;

use crate::diag::Span;
pub use crate::syntax::prolog::{Located, TermSpans};
use crate::term::Sym;

/// A name written in the program (module, action, macro, option word) with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub name: Sym,
    pub span: Span,
}

/// A value with the span it was written at.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    pub value: T,
    pub span: Span,
}

/// A whole `.goal` file: its modules and its top-level `#import "x.mod2g".` lines.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentProgram {
    /// The file name as given by the user (used in diagnostics).
    pub file: String,
    pub modules: Vec<Module>,
    /// Top-level imports of `.mod2g` module files.
    pub imports: Vec<Import>,
    pub span: Span,
}

/// What an `#import` brings in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImportKind {
    /// A `.mod2g` module file (top level of a `.goal` file).
    Module,
    /// A Prolog file appended to the knowledge (inside a module, or the legacy form inside `knowledge{}`).
    Prolog,
}

/// `#import "path".`
#[derive(Clone, Debug, PartialEq)]
pub struct Import {
    pub kind: ImportKind,
    /// The path as written (without quotes), relative to the importing file.
    pub path: String,
    /// Span of the whole `#import ... .`.
    pub span: Span,
}

/// Which module a [`Module`] is.
#[derive(Clone, Debug, PartialEq)]
pub enum ModuleKind {
    Init,
    Main,
    Event,
    /// Modular GOAL's shutdown module: one pass when the agent stops.
    Shutdown,
    /// `module name(P1, ..., Pn)`; parameters should be variables (the validator checks).
    User {
        name: Ident,
        params: Vec<Located>,
    },
}

/// The section kinds of a module (for section bookkeeping and diagnostics).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SectionKind {
    Knowledge,
    Beliefs,
    Goals,
    Program,
    ActionSpec,
}

/// A section header as written, in source order (including duplicates, which are ignored).
#[derive(Clone, Debug, PartialEq)]
pub struct SectionHeader {
    pub kind: SectionKind,
    /// Span of the whole section.
    pub span: Span,
    /// False for a duplicate section (a warning was given and its content dropped).
    pub used: bool,
}

/// `exit=` option values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExitCondition {
    Always,
    Never,
    NoGoals,
    NoAction,
}

/// `focus=` option values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Focus {
    None,
    New,
    Select,
    Filter,
}

/// `program[order=...]` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    Linear,
    LinearAll,
    Random,
    RandomAll,
    Adaptive,
}

/// One `key=value` written in a module's `[...]` option list.
#[derive(Clone, Debug, PartialEq)]
pub struct ModuleOption {
    pub key: Ident,
    pub value: Ident,
    pub span: Span,
}

/// The options of a module: the recognised `exit`/`focus` values (first occurrence) and
/// everything written, in order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ModuleOptions {
    pub exit: Option<Spanned<ExitCondition>>,
    pub focus: Option<Spanned<Focus>>,
    /// Every option as written (including unknown and duplicate ones).
    pub written: Vec<ModuleOption>,
}

/// A module: `init`, `main`, `event` or a user module (also the content of a `.mod2g` file).
#[derive(Clone, Debug, PartialEq)]
pub struct Module {
    pub kind: ModuleKind,
    pub options: ModuleOptions,
    /// Knowledge clauses (global and static).
    pub knowledge: Vec<Located>,
    /// Belief facts inserted on every entry.
    pub beliefs: Vec<Located>,
    /// Goals adopted on every entry; each entry is one goal (possibly a conjunction).
    pub goals: Vec<Located>,
    pub program: Option<ProgramSection>,
    pub action_specs: Vec<ActionSpec>,
    /// `#import "x.pl".` inside the module or inside its `knowledge` block.
    pub imports: Vec<Import>,
    /// The sections as written, in order.
    pub sections: Vec<SectionHeader>,
    /// Span of the module head (`main module`, `module foo(X)`).
    pub head_span: Span,
    pub span: Span,
}

/// `program [order=...] { macros rules }`.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramSection {
    pub order: Option<Spanned<Order>>,
    /// Order of nested `{ }` rule blocks; `None` is `linearall` (modular files inherit the
    /// file's explicit `order`).
    pub nested_order: Option<Order>,
    pub macros: Vec<Macro>,
    pub rules: Vec<Rule>,
    pub span: Span,
}

/// `#define name(P1, ..., Pn) condition.`
#[derive(Clone, Debug, PartialEq)]
pub struct Macro {
    pub name: Ident,
    pub params: Vec<Located>,
    pub body: Vec<Literal>,
    pub span: Span,
}

/// The kind of a rule.
#[derive(Clone, Debug, PartialEq)]
pub enum RuleKind {
    /// `if C then B`
    If,
    /// `forall C do B`
    Forall,
    /// `listall V <- C do B` or `listall C -> V do B`.
    Listall { var: Located },
}

/// A rule: a mental-state condition and a body.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    pub kind: RuleKind,
    /// The literals of the condition, in order (`true` is a literal too).
    pub condition: Vec<Literal>,
    pub body: RuleBody,
    pub span: Span,
}

/// What a rule does.
#[derive(Clone, Debug, PartialEq)]
pub enum RuleBody {
    /// `a1 + a2 + ... + an .`
    Combo(Vec<Action>),
    /// `{ rule ... }`: an anonymous nested module.
    Block(Vec<Rule>),
}

/// The mental operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MentalOp {
    Bel,
    Goal,
    /// `a-goal`
    AGoal,
    /// `goal-a`
    GoalA,
}

impl MentalOp {
    /// The operator as written in a program.
    pub fn keyword(self) -> &'static str {
        match self {
            MentalOp::Bel => "bel",
            MentalOp::Goal => "goal",
            MentalOp::AGoal => "a-goal",
            MentalOp::GoalA => "goal-a",
        }
    }
}

/// A literal of a mental-state condition.
#[derive(Clone, Debug, PartialEq)]
pub struct Literal {
    pub kind: LiteralKind,
    pub span: Span,
}

/// The forms of a literal.
#[derive(Clone, Debug, PartialEq)]
pub enum LiteralKind {
    /// `true`
    True,
    /// `[not(] [selector.] op(query) [)]`
    Mental {
        negated: bool,
        selector: Selector,
        op: MentalOp,
        query: Located,
    },
    /// `name(args)`: the use of a `#define` macro.
    MacroUse { name: Ident, args: Vec<Located> },
}

/// Who a literal or action is about.
#[derive(Clone, Debug, PartialEq)]
pub enum SelectorKind {
    /// `this` (the default)
    This,
    /// `self`
    SelfAgent,
    All,
    AllOther,
    Some,
    SomeOther,
    /// `(a, B, ...)` or a bare agent name `bob.`: terms naming agents (atoms or variables).
    Agents(Vec<Located>),
}

/// A selector with its span (`None` when not written, meaning `this`).
#[derive(Clone, Debug, PartialEq)]
pub struct Selector {
    pub kind: SelectorKind,
    pub span: Option<Span>,
}

impl Selector {
    /// The implicit selector `this`.
    pub fn default_this() -> Selector {
        Selector {
            kind: SelectorKind::This,
            span: None,
        }
    }
}

/// The mood of a message: the marker at the start of the send content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mood {
    /// `:` or no marker; stored as plain `Content`.
    Declarative,
    /// `!`; stored as `imp(Content)`.
    Imperative,
    /// `?`; stored as `int(Content)`.
    Interrogative,
}

/// The built-in modules that can be called as actions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuiltinModule {
    Init,
    Main,
    Event,
}

/// An action in a rule body.
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub kind: ActionKind,
    pub span: Span,
}

/// The forms of an action.
#[derive(Clone, Debug, PartialEq)]
pub enum ActionKind {
    Adopt {
        selector: Selector,
        content: Located,
    },
    Drop {
        selector: Selector,
        content: Located,
    },
    Insert {
        selector: Selector,
        content: Located,
    },
    Delete {
        selector: Selector,
        content: Located,
    },
    /// The content is without the mood marker. The selector of a legacy `send(bob, p)` is the
    /// agent term `bob`.
    Send {
        selector: Selector,
        mood: Mood,
        content: Located,
    },
    SendOnce {
        selector: Selector,
        mood: Mood,
        content: Located,
    },
    Print(Located),
    Log(Located),
    ExitModule,
    /// `name(args)`: a user action or a user module call (resolved later by name/arity).
    Call {
        name: Ident,
        args: Vec<Located>,
    },
    /// `init`, `main` or `event` used as an action.
    BuiltinModule(BuiltinModule),
    /// Modular GOAL's `sleep`, timers and channels.
    Timing {
        op: TimingOp,
        args: Vec<Located>,
    },
}

/// The built-in actions of modular GOAL about time and channels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingOp {
    /// `sleep(Ms)`.
    Sleep,
    /// `starttimer(Name, IntervalMs, DurationMs)`.
    StartTimer,
    /// `canceltimer(Name)`.
    CancelTimer,
    /// `subscribe(Channel, ...)`.
    Subscribe,
    /// `unsubscribe(Channel, ...)`.
    Unsubscribe,
}

impl TimingOp {
    /// The action's name as written.
    pub fn name(self) -> &'static str {
        match self {
            TimingOp::Sleep => "sleep",
            TimingOp::StartTimer => "starttimer",
            TimingOp::CancelTimer => "canceltimer",
            TimingOp::Subscribe => "subscribe",
            TimingOp::Unsubscribe => "unsubscribe",
        }
    }
}

/// `@int` or `@env`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ActionSpecKind {
    /// Sent to the environment (the default).
    Env,
    /// Internal: only changes the mental state.
    Int,
}

/// A `pre{...}` or `post{...}` block: one term (`true` when the block is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct SpecCondition {
    pub term: Located,
    /// The block was empty (`pre{}`); the term is then `true`.
    pub empty: bool,
    /// Span of the whole `pre{...}` / `post{...}`.
    pub span: Span,
}

/// `name(P1, ..., Pn) [@int|@env] { pre{...} post{...} }`.
#[derive(Clone, Debug, PartialEq)]
pub struct ActionSpec {
    pub name: Ident,
    pub params: Vec<Located>,
    pub kind: ActionSpecKind,
    /// Span of the `@int`/`@env` annotation, if written.
    pub kind_span: Option<Span>,
    pub pre: SpecCondition,
    pub post: SpecCondition,
    pub span: Span,
}

impl Module {
    /// The module's name as used in calls and messages (`init`, `main`, `event` or the user name).
    pub fn name(&self) -> &'static str {
        match &self.kind {
            ModuleKind::Init => "init",
            ModuleKind::Main => "main",
            ModuleKind::Event => "event",
            ModuleKind::Shutdown => "shutdown",
            ModuleKind::User { name, .. } => name.name.name(),
        }
    }
}
