//! The GOAL-level tokens of `.goal` and `.mod2g` files, recognised with `logos`.
//! KR-content tokens (`KrBraces`, `KrParens`, ...) are produced by the wrapper in `mod.rs`.

use logos::Logos;

/// A GOAL-level token. Tokens carry no text: the `(start, end)` byte span of the triple does.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tok {
    #[token("module")]
    Module,
    #[token("init")]
    Init,
    #[token("main")]
    Main,
    #[token("event")]
    Event,
    #[token("focus")]
    Focus,
    #[token("none")]
    None,
    #[token("new")]
    New,
    #[token("filter")]
    Filter,
    #[token("select")]
    Select,
    #[token("exit")]
    Exit,
    #[token("always")]
    Always,
    #[token("never")]
    Never,
    #[token("nogoals")]
    NoGoals,
    #[token("noaction")]
    NoAction,
    #[token("knowledge")]
    Knowledge,
    #[token("beliefs")]
    Beliefs,
    #[token("goals")]
    Goals,
    #[token("program")]
    Program,
    #[token("order")]
    Order,
    #[token("linear")]
    Linear,
    #[token("linearall")]
    LinearAll,
    #[token("random")]
    Random,
    #[token("randomall")]
    RandomAll,
    #[token("adaptive")]
    Adaptive,
    #[token("actionspec")]
    ActionSpec,
    #[token("pre")]
    Pre,
    #[token("post")]
    Post,
    #[token("if")]
    If,
    #[token("then")]
    Then,
    #[token("forall")]
    Forall,
    #[token("do")]
    Do,
    #[token("listall")]
    Listall,
    #[token("not")]
    Not,
    #[token("true")]
    True,
    #[token("bel")]
    Bel,
    #[token("goal")]
    Goal,
    #[token("a-goal")]
    AGoal,
    #[token("goal-a")]
    GoalA,
    #[token("adopt")]
    Adopt,
    #[token("drop")]
    Drop,
    #[token("insert")]
    Insert,
    #[token("delete")]
    Delete,
    #[token("send")]
    Send,
    #[token("sendonce")]
    SendOnce,
    #[token("print")]
    Print,
    #[token("log")]
    Log,
    #[token("exit-module")]
    ExitModule,
    #[token("all")]
    All,
    #[token("allother")]
    AllOther,
    #[token("some")]
    Some,
    #[token("someother")]
    SomeOther,
    #[token("self")]
    SelfKw,
    #[token("this")]
    This,
    #[token("#import")]
    Import,
    #[token("#define")]
    Define,
    #[token("@int")]
    AtInt,
    #[token("@env")]
    AtEnv,
    #[token("<-")]
    LArrow,
    #[token("->")]
    RArrow,
    #[token("=")]
    Eq,
    #[token("-")]
    Minus,
    #[token("+")]
    Plus,
    #[token(".")]
    Dot,
    #[token(",")]
    Comma,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token(":")]
    Colon,
    /// A name: `[A-Za-z_][A-Za-z0-9_]*`.
    #[regex("[A-Za-z_][A-Za-z0-9_]*")]
    Ident,
    /// `"..."` or `'...'` with backslash escapes (the span includes the quotes).
    #[regex(r#""([^"\\]|\\.)*""#)]
    #[regex(r#"'([^'\\]|\\.)*'"#)]
    Str,
    #[regex("[0-9]+")]
    Int,
    #[regex(r"[0-9]+\.[0-9]+([eE][+-]?[0-9]+)?")]
    Float,
    /// `{ ... }` after `knowledge`, `beliefs`, `goals`, `pre` or `post`: raw KR text.
    KrBraces,
    /// `( ... )` after a mental operator, a built-in action or a name: raw KR text.
    KrParens,
    /// A standalone `( ... )` (a selector, followed by `.`).
    SelParens,
    /// A name directly followed by `.` and a letter: a bare agent-name selector (`bob.send(...)`).
    SelName,
    /// The variable after `listall`, up to `<-`.
    ListallVar,
}

impl Tok {
    /// How the token is described in messages ("found `then`", "expected a name").
    pub fn describe(self) -> &'static str {
        match self {
            Tok::Ident => "a name",
            Tok::Str => "a string",
            Tok::Int => "an integer",
            Tok::Float => "a number",
            Tok::KrBraces => "a `{ ... }` block",
            Tok::KrParens => "a `( ... )` argument list",
            Tok::SelParens => "a `( ... )` selector",
            Tok::SelName => "an agent-name selector",
            Tok::ListallVar => "a listall variable",
            _ => "a keyword or symbol",
        }
    }

    /// True for tokens after which a `(` starts KR arguments.
    pub(crate) fn takes_kr_parens(self) -> bool {
        matches!(
            self,
            Tok::Bel
                | Tok::Goal
                | Tok::AGoal
                | Tok::GoalA
                | Tok::Adopt
                | Tok::Drop
                | Tok::Insert
                | Tok::Delete
                | Tok::Send
                | Tok::SendOnce
                | Tok::Print
                | Tok::Log
                | Tok::Ident
        )
    }

    /// True for tokens after which a `{` starts a KR block.
    pub(crate) fn takes_kr_braces(self) -> bool {
        matches!(
            self,
            Tok::Knowledge | Tok::Beliefs | Tok::Goals | Tok::Pre | Tok::Post
        )
    }
}
