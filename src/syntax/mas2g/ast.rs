//! The AST of a `.mas2g` file: environment, agent files and launch rules, with byte spans.

use crate::diag::Span;
use std::fmt::Write;

/// A value with the byte span it was read from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    pub value: T,
    pub span: Span,
}

impl<T> Spanned<T> {
    /// Wraps `value` read at `span`.
    pub fn new(value: T, span: Span) -> Spanned<T> {
        Spanned { value, span }
    }
}

/// A whole `.mas2g` file.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MasFile {
    pub file: String,
    pub environment: Option<Environment>,
    pub agent_files: Vec<AgentFile>,
    pub launch_rules: Vec<LaunchRule>,
}

/// The `environment { env = "...". init = [...]. }` section.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// `env = "bw4t"` names the built-in environment; other values are paths (to a jar).
    pub env: Option<Spanned<String>>,
    pub init: Vec<InitParam>,
    pub span: Span,
}

/// One `key = value` of the environment's `init` list.
#[derive(Clone, Debug, PartialEq)]
pub struct InitParam {
    pub key: Spanned<String>,
    pub value: InitValue,
    pub span: Span,
}

/// A value of an `init` parameter (EIS parameter).
#[derive(Clone, Debug, PartialEq)]
pub enum InitValue {
    Ident(Spanned<String>),
    Int(Spanned<i64>),
    Float(Spanned<f64>),
    Str(Spanned<String>),
    Function {
        name: Spanned<String>,
        args: Vec<InitValue>,
        span: Span,
    },
    List {
        items: Vec<InitValue>,
        span: Span,
    },
}

impl InitValue {
    /// The byte span of the whole value.
    pub fn span(&self) -> Span {
        match self {
            InitValue::Ident(s) | InitValue::Str(s) => s.span.clone(),
            InitValue::Int(i) => i.span.clone(),
            InitValue::Float(f) => f.span.clone(),
            InitValue::Function { span, .. } | InitValue::List { span, .. } => span.clone(),
        }
    }
}

/// One entry of `agentfiles`: `"file.goal" [name = ref, language = swiprolog]`.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentFile {
    /// The path as written, relative to the `.mas2g` file.
    pub path: Spanned<String>,
    pub name: Option<Spanned<String>>,
    pub language: Option<Spanned<String>>,
    pub span: Span,
}

impl AgentFile {
    /// The reference name: `name=` if given, otherwise the file's base name without `.goal`.
    pub fn reference_name(&self) -> String {
        if let Some(n) = &self.name {
            return n.value.clone();
        }
        let base = self.path.value.rsplit(['/', '\\']).next().unwrap_or("");
        base.strip_suffix(".goal").unwrap_or(base).to_string()
    }
}

/// A launch rule: unconditional (`launch ...`) or conditional (`when ... @env do launch ...`).
#[derive(Clone, Debug, PartialEq)]
pub struct LaunchRule {
    pub condition: Option<EntitySpec>,
    pub instructions: Vec<LaunchInstruction>,
    pub span: Span,
}

/// Which entities a conditional launch rule applies to.
#[derive(Clone, Debug, PartialEq)]
pub enum EntitySpec {
    /// `entity`: any new or freed entity.
    Any(Span),
    /// `[name = .., type = .., max = N]`.
    Constraints {
        name: Option<Spanned<String>>,
        entity_type: Option<Spanned<String>>,
        max: Option<Spanned<u64>>,
        span: Span,
    },
}

/// The name given to launched agents.
#[derive(Clone, Debug, PartialEq)]
pub enum AgentName {
    /// `*`: the entity's name.
    Entity(Span),
    Given(Spanned<String>),
}

/// `given : ref [N]` (or a bare `ref [N]`).
#[derive(Clone, Debug, PartialEq)]
pub struct LaunchInstruction {
    /// `None` for a bare `ref`: the agent is named after the reference.
    pub name: Option<AgentName>,
    pub reference: Spanned<String>,
    pub count: Option<Spanned<u64>>,
    pub span: Span,
}

impl LaunchInstruction {
    /// The number of agents to launch (`[N]`, default 1).
    pub fn count(&self) -> u64 {
        self.count.as_ref().map_or(1, |c| c.value)
    }
}

impl MasFile {
    /// A compact, indented printed form for snapshots (spans as byte ranges).
    pub fn dump(&self) -> String {
        let mut o = String::new();
        let _ = writeln!(o, "mas {}", self.file);
        if let Some(e) = &self.environment {
            let _ = writeln!(o, "  environment @{:?}", e.span);
            if let Some(env) = &e.env {
                let _ = writeln!(o, "    env {:?} @{:?}", env.value, env.span);
            }
            for p in &e.init {
                let _ = writeln!(
                    o,
                    "    init {} = {} @{:?}",
                    p.key.value,
                    show(&p.value),
                    p.span
                );
            }
        }
        for f in &self.agent_files {
            let _ = write!(
                o,
                "  agentfile {:?} ref={}",
                f.path.value,
                f.reference_name()
            );
            if let Some(l) = &f.language {
                let _ = write!(o, " language={}", l.value);
            }
            let _ = writeln!(o, " @{:?}", f.span);
        }
        for r in &self.launch_rules {
            match &r.condition {
                None => {
                    let _ = write!(o, "  launch");
                }
                Some(EntitySpec::Any(_)) => {
                    let _ = write!(o, "  when entity do launch");
                }
                Some(EntitySpec::Constraints {
                    name,
                    entity_type,
                    max,
                    ..
                }) => {
                    let _ = write!(o, "  when [");
                    let mut parts = Vec::new();
                    if let Some(n) = name {
                        parts.push(format!("name={}", n.value));
                    }
                    if let Some(t) = entity_type {
                        parts.push(format!("type={}", t.value));
                    }
                    if let Some(m) = max {
                        parts.push(format!("max={}", m.value));
                    }
                    let _ = write!(o, "{}] do launch", parts.join(","));
                }
            }
            for (i, inst) in r.instructions.iter().enumerate() {
                let sep = if i == 0 { " " } else { ", " };
                let name = match &inst.name {
                    None => String::new(),
                    Some(AgentName::Entity(_)) => "*:".into(),
                    Some(AgentName::Given(g)) => format!("{}:", g.value),
                };
                let _ = write!(o, "{sep}{name}{}[{}]", inst.reference.value, inst.count());
            }
            let _ = writeln!(o, " @{:?}", r.span);
        }
        o
    }
}

/// Prints an init value in `.mas2g` syntax (iteratively bounded by the lexer's nesting limit).
pub fn show(v: &InitValue) -> String {
    match v {
        InitValue::Ident(s) => s.value.clone(),
        InitValue::Int(i) => i.value.to_string(),
        InitValue::Float(f) => f.value.to_string(),
        InitValue::Str(s) => format!("{:?}", s.value),
        InitValue::Function { name, args, .. } => {
            let a: Vec<String> = args.iter().map(show).collect();
            format!("{}({})", name.value, a.join(", "))
        }
        InitValue::List { items, .. } => {
            let a: Vec<String> = items.iter().map(show).collect();
            format!("[{}]", a.join(", "))
        }
    }
}
