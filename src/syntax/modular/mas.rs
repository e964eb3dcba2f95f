//! The `.mas2g` forms of modular GOAL (A) and MARBEL (B): tokens, the builder used by
//! `grammar/mas2g_modular.lalrpop`, and the parsed system ([`ModMas`]). Launch rules and
//! environment parameters are built in the 2014 MAS types so that launching has one path.

use super::ast::Generation;
use crate::diag::{Diagnostic, Span};
use crate::syntax::mas2g::ast::{
    AgentName, EntitySpec, InitParam, InitValue, LaunchInstruction, LaunchRule, Spanned,
};
use lalrpop_util::{lalrpop_mod, ErrorRecovery};
use logos::Logos;

lalrpop_mod!(
    #[allow(clippy::all, unused, dead_code, missing_docs)]
    grammar,
    "/mas2g_modular.rs"
);

/// A token of a modular `.mas2g` file.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(skip r"[ \t\r\n\f]+")]
#[logos(skip r"%[^\n]*")]
pub enum MasTok {
    /// A block comment (skipped; unterminated is a lexical error).
    #[token("/*", block_comment)]
    Comment,
    #[token("use")]
    Use,
    #[token("as")]
    As,
    #[token("environment")]
    Environment,
    #[token("with")]
    With,
    #[token("define")]
    Define,
    #[token("agent")]
    Agent,
    #[token("module")]
    Module,
    #[token("for")]
    For,
    #[token("add")]
    Add,
    #[token("update")]
    Update,
    #[token("replace")]
    Replace,
    #[token("launchpolicy")]
    LaunchPolicy,
    #[token("when")]
    When,
    #[token("launch")]
    Launch,
    #[token("*")]
    Star,
    #[token("=")]
    Eq,
    #[token(".")]
    Dot,
    #[token(",")]
    Comma,
    #[token("/")]
    Slash,
    #[token("+")]
    Plus,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[regex(r"[\p{L}_][\p{L}\p{N}_]*")]
    Ident,
    /// A name directly followed by `.` and a letter: part of a dotted reference.
    PathName,
    #[regex(r#""([^"\\\n]|\\.)*""#)]
    #[regex(r#"'([^'\\\n]|\\.)*'"#)]
    Str,
    #[regex("-?[0-9]+")]
    Int,
    #[regex(r"-?[0-9]*\.[0-9]+([eE][+-]?[0-9]+)?")]
    Float,
}

fn block_comment(lex: &mut logos::Lexer<MasTok>) -> logos::FilterResult<(), ()> {
    match lex.remainder().find("*/") {
        Some(i) => {
            lex.bump(i + 2);
            logos::FilterResult::Skip
        }
        None => {
            lex.bump(lex.remainder().len());
            logos::FilterResult::Error(())
        }
    }
}

/// True for a byte that can start a name: an ASCII letter or `_`, or the first byte of a
/// non-ASCII character (Unicode letters).
pub fn starts_name(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_' || c >= 0x80
}

/// The text of one or more quoted strings joined by `+` (`"a" + "b"` is `ab`), without quotes
/// and escapes.
pub fn joined_strings(text: &str) -> String {
    let mut out = String::new();
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '"' && c != '\'' {
            continue;
        }
        let quote = c;
        while let Some(d) = chars.next() {
            match d {
                // `\"` and `\\` stand for the character; other backslashes stay (paths).
                '\\' => match chars.next() {
                    Some(e) if e == quote || e == '\\' => out.push(e),
                    Some(e) => {
                        out.push('\\');
                        out.push(e);
                    }
                    None => out.push('\\'),
                },
                d if d == quote => break,
                d => out.push(d),
            }
        }
    }
    out
}

/// Deepest nesting of `(`/`[` in parameter values.
const MAX_NESTING: usize = 32;

/// Tokens of `src` for the parser, with lexical errors as diagnostics.
fn tokens(src: &str, file: &str) -> (Vec<(usize, MasTok, usize)>, Vec<Diagnostic>) {
    let mut out = Vec::new();
    let mut diags = Vec::new();
    let mut depth = 0usize;
    let b = src.as_bytes();
    let mut lx = MasTok::lexer(src);
    while let Some(t) = lx.next() {
        let span = lx.span();
        match t {
            Ok(mut tok) => {
                if tok == MasTok::Ident
                    && b.get(span.end) == Some(&b'.')
                    && b.get(span.end + 1).is_some_and(|c| starts_name(*c))
                {
                    tok = MasTok::PathName;
                }
                match tok {
                    MasTok::LParen | MasTok::LBracket => depth += 1,
                    MasTok::RParen | MasTok::RBracket => depth = depth.saturating_sub(1),
                    _ => {}
                }
                if depth > MAX_NESTING {
                    diags.push(Diagnostic::error(
                        "E0201",
                        format!("values nested more than {MAX_NESTING} deep"),
                        file,
                        span,
                    ));
                    break;
                }
                out.push((span.start, tok, span.end));
            }
            Err(()) => {
                let text = &src[span.clone()];
                let (msg, hint) = if text.starts_with('"') || text.starts_with('\'') {
                    (
                        "unterminated string".to_string(),
                        "close the string on the same line",
                    )
                } else if text.starts_with("/*") {
                    (
                        "unterminated block comment".to_string(),
                        "close the comment with `*/`",
                    )
                } else {
                    (
                        format!("unexpected character `{}`", text.escape_debug()),
                        "remove it",
                    )
                };
                diags.push(Diagnostic::error("E0200", msg, file, span).with_hint(hint));
                if diags.len() > 50 {
                    break;
                }
            }
        }
    }
    (out, diags)
}

/// A parameter or constraint value as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Ident(Spanned<String>),
    Int(Spanned<i64>),
    Float(Spanned<f64>),
    Str(Spanned<String>),
    Function(Spanned<String>, Vec<Value>, Span),
    List(Vec<Value>, Span),
    Star(Span),
}

/// `use REF [as environment] [with k = v, ...].`
#[derive(Clone, Debug, PartialEq)]
pub struct EnvUse {
    pub reference: Spanned<String>,
    pub params: Vec<InitParam>,
    /// `as environment` was written (A); without it the form is (B).
    pub as_environment: bool,
    pub span: Span,
}

/// The role a module plays in an agent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Init,
    Event,
    Main,
    Shutdown,
}

impl Role {
    /// The (A) keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            Role::Init => "init",
            Role::Event => "event",
            Role::Main => "main",
            Role::Shutdown => "shutdown",
        }
    }
}

/// How a (B) agent stores percepts of one predicate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PerceptMode {
    Add,
    Update,
    Replace,
}

/// An item of an agent definition.
#[derive(Clone, Debug, PartialEq)]
pub enum AgentItem {
    /// `use m as main module.` (A) or `use m for decisions.` (B).
    Use {
        reference: Spanned<String>,
        role: Spanned<Role>,
        marbel: bool,
        span: Span,
    },
    /// (B) `add|update|replace p/n.`
    Percept {
        mode: PerceptMode,
        name: Spanned<String>,
        arity: usize,
        span: Span,
    },
}

/// `define name as agent { ... }` (A) or `define name { ... }` (B).
#[derive(Clone, Debug, PartialEq)]
pub struct AgentDef {
    pub name: Spanned<String>,
    /// Span of `as agent` when written (A).
    pub as_agent: Option<Span>,
    pub items: Vec<AgentItem>,
    pub span: Span,
}

/// An entity condition of a launch rule.
#[derive(Clone, Debug, PartialEq)]
pub enum Entity {
    Any(Span),
    Is(Spanned<String>, Spanned<String>),
}

/// One `key = value` of a launch instruction.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    pub key: Spanned<String>,
    pub value: Value,
}

/// A parsed modular `.mas2g` file.
#[derive(Clone, Debug, PartialEq)]
pub struct ModMas {
    pub file: String,
    pub generation: Generation,
    pub env: Option<EnvUse>,
    pub agents: Vec<AgentDef>,
    /// Launch rules in the 2014 form (`max` moved to the rule, `number` to the count).
    pub launch: Vec<LaunchRule>,
}

/// State of the semantic actions.
pub struct MasBuilder<'s> {
    src: &'s str,
    file: String,
    pub diagnostics: Vec<Diagnostic>,
    /// Spans of (A) and (B) forms, to tell the generation and to report mixing.
    signals_a: Vec<Span>,
    signals_b: Vec<Span>,
}

impl<'s> MasBuilder<'s> {
    fn error(&mut self, code: &str, msg: impl Into<String>, span: Span, hint: &str) {
        let d = Diagnostic::error(code, msg, self.file.clone(), span).with_hint(hint);
        self.diagnostics.push(d);
    }

    /// Records a syntax error the parser recovered from.
    pub fn recover(&mut self, e: ErrorRecovery<usize, MasTok, Diagnostic>) {
        let d = syntax_error(e.error, self.src, &self.file);
        self.diagnostics.push(d);
    }

    /// The text at `span`.
    pub fn text(&self, span: Span) -> Spanned<String> {
        Spanned::new(self.src[span.clone()].to_string(), span)
    }

    /// Quoted strings (joined by `+`) without quotes.
    pub fn string(&self, span: Span) -> Spanned<String> {
        Spanned::new(joined_strings(&self.src[span.clone()]), span)
    }

    /// A dotted reference `a.b` as the path `a/b`.
    pub fn path(&self, span: Span) -> Spanned<String> {
        Spanned::new(self.src[span.clone()].replace('.', "/"), span)
    }

    /// An integer value.
    pub fn int(&mut self, span: Span) -> Value {
        match self.src[span.clone()].parse::<i64>() {
            Ok(i) => Value::Int(Spanned::new(i, span)),
            Err(_) => {
                self.error(
                    "E0204",
                    "integer out of range",
                    span.clone(),
                    "use a smaller number",
                );
                Value::Int(Spanned::new(0, span))
            }
        }
    }

    /// A float value.
    pub fn float(&mut self, span: Span) -> Value {
        let f = self.src[span.clone()].parse::<f64>().unwrap_or(0.0);
        Value::Float(Spanned::new(f, span))
    }

    /// The environment use clause.
    pub fn env(
        &mut self,
        reference: Spanned<String>,
        as_environment: bool,
        params: Vec<InitParam>,
        span: Span,
    ) -> EnvUse {
        if as_environment {
            self.signals_a.push(span.clone());
        } else {
            self.signals_b.push(span.clone());
        }
        EnvUse {
            reference,
            params,
            as_environment,
            span,
        }
    }

    /// `key = value` of the environment.
    pub fn param(&mut self, key: Spanned<String>, value: Value, span: Span) -> InitParam {
        InitParam {
            key,
            value: init_value(&value),
            span,
        }
    }

    /// An agent definition.
    pub fn agent(
        &mut self,
        name: Spanned<String>,
        as_agent: Option<Span>,
        items: Vec<AgentItem>,
        span: Span,
    ) -> AgentDef {
        match &as_agent {
            Some(s) => self.signals_a.push(s.clone()),
            None => self.signals_b.push(name.span.clone()),
        }
        AgentDef {
            name,
            as_agent,
            items,
            span,
        }
    }

    /// `use m as ROLE [module].` or `use m for ROLE.`
    pub fn use_role(
        &mut self,
        reference: Spanned<String>,
        role: Spanned<String>,
        marbel: bool,
        span: Span,
    ) -> AgentItem {
        let word = role.value.as_str();
        let (r, alias) = if marbel {
            self.signals_b.push(span.clone());
            match word {
                "decisions" => (Some(Role::Main), false),
                "updates" => (Some(Role::Event), false),
                "init" => (Some(Role::Init), false),
                "shutdown" => (Some(Role::Shutdown), false),
                "decision" | "main" => (Some(Role::Main), true),
                "update" | "event" | "events" => (Some(Role::Event), true),
                _ => (None, false),
            }
        } else {
            self.signals_a.push(span.clone());
            let r = match word {
                "init" => Some(Role::Init),
                "event" => Some(Role::Event),
                "main" => Some(Role::Main),
                "shutdown" => Some(Role::Shutdown),
                _ => None,
            };
            (r, false)
        };
        let role_value = r.unwrap_or_else(|| {
            let allowed = if marbel {
                "`decisions`, `updates` or `init`"
            } else {
                "`init`, `event`, `main` or `shutdown`"
            };
            self.error(
                "E0606",
                format!("`{word}` is not a module role"),
                role.span.clone(),
                &format!("use {allowed}"),
            );
            Role::Main
        });
        if alias {
            let canonical = match role_value {
                Role::Main => "decisions",
                Role::Event => "updates",
                _ => "init",
            };
            self.diagnostics.push(
                Diagnostic::warning(
                    "W0602",
                    format!("`for {word}` is read as `for {canonical}`"),
                    self.file.clone(),
                    role.span.clone(),
                )
                .with_hint(format!("write `for {canonical}`")),
            );
        }
        AgentItem::Use {
            reference,
            role: Spanned::new(role_value, role.span),
            marbel,
            span,
        }
    }

    /// `add|update|replace p/n.`
    pub fn percept(
        &mut self,
        mode: Spanned<String>,
        name: Spanned<String>,
        arity: Spanned<String>,
        span: Span,
    ) -> AgentItem {
        self.signals_b.push(span.clone());
        let mode = match mode.value.as_str() {
            "add" => PerceptMode::Add,
            "update" => PerceptMode::Update,
            _ => PerceptMode::Replace,
        };
        let n = arity.value.parse::<usize>().unwrap_or_else(|_| {
            self.error(
                "E0204",
                "an arity is a small number that is not negative",
                arity.span.clone(),
                "write the number of arguments of the percept",
            );
            0
        });
        AgentItem::Percept {
            mode,
            name,
            arity: n,
            span,
        }
    }

    /// A launch rule in the 2014 form.
    pub fn launch(
        &mut self,
        when: Option<Entity>,
        instrs: Vec<Spanned<String>>,
        constraints: Vec<Constraint>,
        span: Span,
    ) -> LaunchRule {
        let mut max = None;
        let mut instructions = Vec::new();
        let last = instrs.len().saturating_sub(1);
        let mut constraints = Some(constraints);
        for (i, reference) in instrs.into_iter().enumerate() {
            let ispan = reference.span.clone();
            let constraints = if i == last {
                constraints.take().unwrap_or_default()
            } else {
                Vec::new()
            };
            let mut name = None;
            let mut count = None;
            for c in constraints {
                match (c.key.value.as_str(), &c.value) {
                    ("name", Value::Star(s)) => name = Some(AgentName::Entity(s.clone())),
                    ("name", Value::Ident(n) | Value::Str(n)) => {
                        name = Some(AgentName::Given(n.clone()))
                    }
                    ("number", Value::Int(i)) if i.value >= 1 => {
                        count = Some(Spanned::new(i.value as u64, i.span.clone()))
                    }
                    ("max", Value::Int(i)) if i.value >= 0 => {
                        max = Some(Spanned::new(i.value as u64, i.span.clone()))
                    }
                    // Learning parameters: accepted, not used.
                    ("alpha" | "gamma" | "epsilon" | "decay", Value::Float(_) | Value::Int(_)) => {}
                    (k, _) => self.error(
                        "E0203",
                        format!("`{k}` with this value is not a launch constraint"),
                        c.key.span.clone(),
                        "use `name = N`, `name = *`, `number = K` or `max = M`",
                    ),
                }
            }
            instructions.push(LaunchInstruction {
                name,
                reference,
                count,
                span: ispan,
            });
        }
        let condition = match when {
            None => None,
            Some(Entity::Any(s)) if max.is_none() => Some(EntitySpec::Any(s)),
            Some(Entity::Any(s)) => Some(EntitySpec::Constraints {
                name: None,
                entity_type: None,
                max,
                span: s,
            }),
            Some(Entity::Is(k, v)) => {
                let span = k.span.start..v.span.end;
                let (mut name, mut entity_type) = (None, None);
                match k.value.as_str() {
                    "type" => entity_type = Some(v),
                    "name" => name = Some(v),
                    _ => self.error(
                        "E0203",
                        format!("`{}` is not an entity condition", k.value),
                        k.span.clone(),
                        "use `when * launch ...`, `when type = T launch ...` or `when name = N launch ...`",
                    ),
                }
                Some(EntitySpec::Constraints {
                    name,
                    entity_type,
                    max,
                    span,
                })
            }
        };
        LaunchRule {
            condition,
            instructions,
            span,
        }
    }
}

fn init_value(v: &Value) -> InitValue {
    match v {
        Value::Ident(s) => InitValue::Ident(s.clone()),
        Value::Int(i) => InitValue::Int(i.clone()),
        Value::Float(f) => InitValue::Float(f.clone()),
        // BW4T examples write numbers as strings (`agentcount = "3"`).
        Value::Str(s) => match s.value.trim().parse::<i64>() {
            Ok(i) => InitValue::Int(Spanned::new(i, s.span.clone())),
            Err(_) => InitValue::Str(s.clone()),
        },
        Value::Function(n, args, span) => InitValue::Function {
            name: n.clone(),
            args: args.iter().map(init_value).collect(),
            span: span.clone(),
        },
        Value::List(items, span) => InitValue::List {
            items: items.iter().map(init_value).collect(),
            span: span.clone(),
        },
        Value::Star(s) => InitValue::Ident(Spanned::new("*".into(), s.clone())),
    }
}

/// Parses a modular `.mas2g` file; the generation is read from its forms, and mixing (A) and
/// (B) forms is an error.
pub fn parse(src: &str, file: &str) -> (ModMas, Vec<Diagnostic>) {
    let (toks, mut diags) = tokens(src, file);
    let mut b = MasBuilder {
        src,
        file: file.to_string(),
        diagnostics: Vec::new(),
        signals_a: Vec::new(),
        signals_b: Vec::new(),
    };
    let result = grammar::MasParser::new().parse(&mut b, toks.into_iter().map(Ok::<_, Diagnostic>));
    let (env, agents, launch) = match result {
        Ok(x) => x,
        Err(e) => {
            b.diagnostics.push(syntax_error(e, src, file));
            (None, Vec::new(), Vec::new())
        }
    };
    let generation = match (b.signals_a.first(), b.signals_b.first()) {
        (Some(a), Some(bs)) => {
            let at = if a.start > bs.start {
                a.clone()
            } else {
                bs.clone()
            };
            b.error(
                "E0605",
                "this file mixes modular GOAL (A) and MARBEL (B) forms",
                at,
                "(A) writes `use X as environment`, `define a as agent { use m as main module. }`; \
                 (B) writes `use X with ...`, `define a { use m for decisions. }`",
            );
            Generation::Modular
        }
        (None, Some(_)) => Generation::Marbel,
        _ => Generation::Modular,
    };
    diags.append(&mut b.diagnostics);
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    let mas = ModMas {
        file: file.to_string(),
        generation,
        env,
        agents,
        launch,
    };
    (mas, diags)
}

fn syntax_error(
    e: lalrpop_util::ParseError<usize, MasTok, Diagnostic>,
    src: &str,
    file: &str,
) -> Diagnostic {
    use lalrpop_util::ParseError;
    let list = crate::syntax::goal::errors::expected_list;
    let d = match e {
        ParseError::User { error } => return error,
        ParseError::InvalidToken { location } => {
            Diagnostic::error("E0202", "invalid token", file, location..location + 1)
        }
        ParseError::UnrecognizedEof { location, expected } => Diagnostic::error(
            "E0202",
            format!("unexpected end of file, expected {}", list(&expected)),
            file,
            location..location,
        ),
        ParseError::UnrecognizedToken {
            token: (l, _, r),
            expected,
        } => Diagnostic::error(
            "E0202",
            format!("unexpected `{}`, expected {}", &src[l..r], list(&expected)),
            file,
            l..r,
        ),
        ParseError::ExtraToken { token: (l, _, r) } => {
            Diagnostic::error("E0202", format!("unexpected `{}`", &src[l..r]), file, l..r)
        }
    };
    d.with_hint(
        "a modular MAS file is: `use ... as environment with ... .`, then `define ... { ... }` \
         agent definitions, then `launchpolicy { ... }`",
    )
}

impl ModMas {
    /// A compact, indented printed form for snapshots (spans as byte ranges).
    pub fn dump(&self) -> String {
        use std::fmt::Write;
        let mut o = String::new();
        let _ = writeln!(o, "mas {} ({})", self.file, self.generation.label());
        if let Some(e) = &self.env {
            let _ = writeln!(
                o,
                "  environment {:?} as_environment={} @{:?}",
                e.reference.value, e.as_environment, e.span
            );
            for p in &e.params {
                let v = crate::syntax::mas2g::ast::show(&p.value);
                let _ = writeln!(o, "    {} = {v} @{:?}", p.key.value, p.span);
            }
        }
        for a in &self.agents {
            let form = if a.as_agent.is_some() {
                "as agent"
            } else {
                "{}"
            };
            let _ = writeln!(o, "  define {} ({form}) @{:?}", a.name.value, a.span);
            for i in &a.items {
                let _ = match i {
                    AgentItem::Use {
                        reference,
                        role,
                        marbel,
                        span,
                    } => writeln!(
                        o,
                        "    use {:?} role={} {} @{span:?}",
                        reference.value,
                        role.value.keyword(),
                        if *marbel { "(for)" } else { "(as)" }
                    ),
                    AgentItem::Percept {
                        mode,
                        name,
                        arity,
                        span,
                    } => writeln!(o, "    {mode:?} {}/{arity} @{span:?}", name.value),
                };
            }
        }
        let classic = crate::syntax::mas2g::ast::MasFile {
            launch_rules: self.launch.clone(),
            ..Default::default()
        };
        for line in classic.dump().lines().skip(1) {
            let _ = writeln!(o, "{line}");
        }
        o
    }
}

/// For a modular `.mas2g` text: its launch rules as a 2014 [`MasFile`] (what test files need
/// to know which agents a system launches) and its diagnostics; `None` for a 2014 MAS text.
pub fn classic_launch(
    text: &str,
    file: &str,
) -> Option<(crate::syntax::mas2g::ast::MasFile, Vec<Diagnostic>)> {
    if super::detect::mas_generation(text) == Generation::Classic {
        return None;
    }
    let (m, diags) = parse(text, file);
    let mas = crate::syntax::mas2g::ast::MasFile {
        file: file.to_string(),
        launch_rules: m.launch,
        ..Default::default()
    };
    Some((mas, diags))
}
