//! The tokens of modular module (`.mod2g`) and action-specification (`.act2g`) files, generations
//! (A) and (B), recognised with `logos`. KR spans are produced by the wrapper in `lexer.rs`.

use logos::Logos;

/// A token of a modular `.mod2g`/`.act2g` file; the span of the triple carries the text.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MTok {
    #[token("use")]
    Use,
    #[token("as")]
    As,
    #[token("module")]
    Module,
    #[token("actionspec")]
    ActionSpec,
    #[token("knowledge")]
    Knowledge,
    #[token("beliefs")]
    Beliefs,
    #[token("goals")]
    Goals,
    #[token("mas")]
    Mas,
    #[token("planner")]
    Planner,
    #[token("learnbel")]
    LearnBel,
    #[token("learngoal")]
    LearnGoal,
    #[token("exit")]
    Exit,
    #[token("focus")]
    Focus,
    #[token("order")]
    Order,
    #[token("timeout")]
    Timeout,
    #[token("define")]
    Define,
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
    #[token("bel")]
    Bel,
    #[token("goal")]
    Goal,
    #[token("a-goal")]
    AGoal,
    #[token("goal-a")]
    GoalA,
    #[token("percept")]
    Percept,
    #[token("sent")]
    #[token("sent:")]
    Sent,
    #[token("sent?")]
    SentInt,
    #[token("sent!")]
    SentImp,
    #[token("not")]
    Not,
    #[token("true")]
    True,
    #[token("adopt")]
    Adopt,
    #[token("drop")]
    Drop,
    #[token("insert")]
    Insert,
    #[token("delete")]
    Delete,
    #[token("send")]
    #[token("send:")]
    Send,
    #[token("send?")]
    SendInt,
    #[token("send!")]
    SendImp,
    #[token("sendonce")]
    SendOnce,
    #[token("log")]
    Log,
    #[token("print")]
    Print,
    #[token("sleep")]
    Sleep,
    #[token("subscribe")]
    Subscribe,
    #[token("unsubscribe")]
    Unsubscribe,
    #[token("starttimer")]
    StartTimer,
    #[token("canceltimer")]
    CancelTimer,
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
    #[token("external")]
    External,
    #[token("internal")]
    Internal,
    #[token("with")]
    With,
    #[token("pre")]
    Pre,
    #[token("post")]
    Post,
    #[token("post+")]
    PostAdd,
    #[token("post-")]
    PostDel,
    #[token("<-")]
    LArrow,
    #[token("=")]
    Eq,
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
    /// A name: a letter or `_`, then letters, digits and `_` (Unicode letters too).
    #[regex(r"[\p{L}_][\p{L}\p{N}_]*")]
    Ident,
    /// `"..."` or `'...'` with backslash escapes (the span includes the quotes).
    #[regex(r#""([^"\\\n]|\\.)*""#)]
    #[regex(r#"'([^'\\\n]|\\.)*'"#)]
    Str,
    #[regex("-?[0-9]+")]
    Int,
    /// `{ ... }` after `pre`, `post`, `post+`, `post-`: raw KR text.
    KrBraces,
    /// `( ... )` after a mental operator, a built-in action or a name: raw KR text.
    KrParens,
    /// A standalone `( ... )`: a selector (followed by `.`).
    SelParens,
    /// A name followed directly by `.` and a letter: a path part of a reference (`dir.file`).
    PathName,
    /// The variable after `listall`, up to `<-`.
    ListallVar,
    /// (B) a condition taken raw: from after `if`/`forall`/`<-` up to `then`/`do`.
    KrCond,
    /// Keywords of (A) test files only (names elsewhere): `test`, `in`, `always`, `never`,
    /// `eventually`, `leadsto`, `done`, `until`.
    Test,
    In,
    Always,
    Never,
    Eventually,
    LeadsTo,
    Done,
    Until,
}

impl MTok {
    /// In a test file, the test keyword a name stands for.
    pub(crate) fn test_keyword(text: &str) -> Option<MTok> {
        Some(match text {
            "test" => MTok::Test,
            "in" => MTok::In,
            "always" => MTok::Always,
            "never" => MTok::Never,
            "eventually" => MTok::Eventually,
            "leadsto" => MTok::LeadsTo,
            "done" => MTok::Done,
            "until" => MTok::Until,
            _ => return None,
        })
    }
}

impl MTok {
    /// True for tokens after which a `(` starts KR arguments.
    pub(crate) fn takes_kr_parens(self) -> bool {
        use MTok::*;
        matches!(
            self,
            Bel | Goal
                | AGoal
                | GoalA
                | Percept
                | Sent
                | SentInt
                | SentImp
                | Adopt
                | Drop
                | Insert
                | Delete
                | Send
                | SendInt
                | SendImp
                | SendOnce
                | Log
                | Print
                | Sleep
                | Subscribe
                | Unsubscribe
                | StartTimer
                | CancelTimer
                | LearnBel
                | LearnGoal
                | Ident
        )
    }

    /// True for tokens after which a `{` starts a KR block.
    pub(crate) fn takes_kr_braces(self) -> bool {
        matches!(self, MTok::Pre | MTok::Post | MTok::PostAdd | MTok::PostDel)
    }

    /// True for tokens after which a (B) condition starts.
    pub(crate) fn starts_condition(self) -> bool {
        matches!(self, MTok::If | MTok::Forall | MTok::LArrow)
    }
}
