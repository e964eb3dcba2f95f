//! Turns parsed `.mas2g` sections into a [`MasFile`]: merges sections (a duplicate section is
//! warned about and ignored), interprets `key = value` options and reports misuse.

use super::ast::*;
use super::raw::*;
use crate::diag::Diagnostic;
use std::collections::BTreeMap;

/// Builds the AST from the sections in file order, adding diagnostics to `diags`.
pub fn build(sections: Vec<Section>, file: &str, diags: &mut Vec<Diagnostic>) -> MasFile {
    let mut mas = MasFile {
        file: file.to_string(),
        ..MasFile::default()
    };
    let mut seen: BTreeMap<&'static str, crate::diag::Span> = BTreeMap::new();
    for section in sections {
        let (kind, span) = match &section {
            Section::Environment { span, .. } => ("environment", span.clone()),
            Section::AgentFiles { span, .. } => ("agentfiles", span.clone()),
            Section::LaunchPolicy { span, .. } => ("launchpolicy", span.clone()),
        };
        if seen.contains_key(kind) {
            let head = span.start..span.start + kind.len();
            diags.push(
                Diagnostic::warning(
                    "W0201",
                    format!("duplicate `{kind}` section; only the first one is used"),
                    file,
                    head,
                )
                .with_hint(format!(
                    "merge the contents into the first `{kind}` section"
                )),
            );
            continue;
        }
        seen.insert(kind, span);
        match section {
            Section::Environment { items, span } => {
                mas.environment = Some(environment(items, span, file, diags))
            }
            Section::AgentFiles { files, .. } => {
                mas.agent_files = files
                    .into_iter()
                    .map(|f| agent_file(f, file, diags))
                    .collect()
            }
            Section::LaunchPolicy { rules, .. } => {
                mas.launch_rules = rules
                    .into_iter()
                    .map(|r| launch_rule(r, file, diags))
                    .collect()
            }
        }
    }
    mas
}

fn environment(
    items: Vec<EnvItem>,
    span: crate::diag::Span,
    file: &str,
    diags: &mut Vec<Diagnostic>,
) -> Environment {
    let mut env: Option<Spanned<String>> = None;
    let mut init: Option<Vec<InitParam>> = None;
    for item in items {
        match item {
            EnvItem::Env(s, at) => {
                if env.is_some() {
                    diags.push(Diagnostic::warning(
                        "W0202",
                        "duplicate `env`; the first one is used",
                        file,
                        at,
                    ));
                } else {
                    env = Some(s);
                }
            }
            EnvItem::Init(params, at) => {
                if init.is_some() {
                    diags.push(Diagnostic::warning(
                        "W0202",
                        "duplicate `init`; the first one is used",
                        file,
                        at,
                    ));
                } else {
                    init = Some(params);
                }
            }
        }
    }
    let mut kept: Vec<InitParam> = Vec::new();
    let mut keys: std::collections::BTreeSet<String> = Default::default();
    for p in init.unwrap_or_default() {
        if !keys.insert(p.key.value.clone()) {
            diags.push(
                Diagnostic::warning(
                    "W0202",
                    format!(
                        "duplicate init parameter `{}`; the first one is used",
                        p.key.value
                    ),
                    file,
                    p.key.span.clone(),
                )
                .with_hint("remove one of the two values"),
            );
        } else {
            kept.push(p);
        }
    }
    if env.is_none() {
        diags.push(
            Diagnostic::warning(
                "W0203",
                "`environment` section without `env`; the section is ignored",
                file,
                span.start..span.start + "environment".len(),
            )
            .with_hint("add `env = \"bw4t\".` to use the built-in BW4T environment"),
        );
    }
    Environment {
        env,
        init: kept,
        span,
    }
}

/// Reports a duplicated option key; true if `key` was already seen.
fn duplicate(
    seen: &mut std::collections::BTreeSet<String>,
    p: &RawParam,
    file: &str,
    diags: &mut Vec<Diagnostic>,
) -> bool {
    if !seen.insert(p.key.value.clone()) {
        diags.push(Diagnostic::warning(
            "W0204",
            format!("duplicate option `{}`; the first one is used", p.key.value),
            file,
            p.span.clone(),
        ));
        return true;
    }
    false
}

fn ident_value(p: &RawParam, file: &str, diags: &mut Vec<Diagnostic>) -> Option<Spanned<String>> {
    match &p.value {
        RawValue::Ident(s) | RawValue::Str(s) => Some(s.clone()),
        RawValue::Int(i) => {
            diags.push(Diagnostic::error(
                "E0204",
                format!(
                    "`{}` must be a name, found the number {}",
                    p.key.value, i.value
                ),
                file,
                i.span.clone(),
            ));
            None
        }
    }
}

fn agent_file(raw: RawAgentFile, file: &str, diags: &mut Vec<Diagnostic>) -> AgentFile {
    // Windows separators in real files: `"agents\\robot.goal"`.
    let path = Spanned::new(raw.path.value.replace('\\', "/"), raw.path.span);
    let mut out = AgentFile {
        path,
        name: None,
        language: None,
        span: raw.span,
    };
    let mut seen = std::collections::BTreeSet::new();
    for p in &raw.params {
        if duplicate(&mut seen, p, file, diags) {
            continue;
        }
        match p.key.value.as_str() {
            "name" => out.name = ident_value(p, file, diags),
            "language" => out.language = ident_value(p, file, diags),
            other => diags.push(
                Diagnostic::error(
                    "E0203",
                    format!("unknown agent file option `{other}`"),
                    file,
                    p.key.span.clone(),
                )
                .with_hint("the options of an agent file are `name` and `language`"),
            ),
        }
    }
    if let Some(l) = &out.language {
        match crate::kr::KrKind::parse(&l.value) {
            Err(_) => diags.push(
                Diagnostic::warning(
                    "W0205",
                    format!("unknown KR language `{}`; the run's engine is used", l.value),
                    file,
                    l.span.clone(),
                )
                .with_hint("write `language = scryer`, `native` or `swiprolog` (the run's engine, `--kr`), or leave it out"),
            ),
            Ok(Some(k)) if !k.available() => diags.push(
                Diagnostic::error(
                    "E0209",
                    format!("this goal was built without the {} engine", k.name()),
                    file,
                    l.span.clone(),
                )
                .with_hint("build with the default features, or write `language = native`"),
            ),
            Ok(_) => {}
        }
    }
    out
}

fn count(c: Option<Spanned<i64>>, file: &str, diags: &mut Vec<Diagnostic>) -> Option<Spanned<u64>> {
    let c = c?;
    if c.value < 1 {
        diags.push(
            Diagnostic::error(
                "E0204",
                format!("agent count must be at least 1, found {}", c.value),
                file,
                c.span.clone(),
            )
            .with_hint("write `[N]` with N ≥ 1, or leave it out to launch one agent"),
        );
        return None;
    }
    Some(Spanned::new(c.value as u64, c.span))
}

fn launch_rule(raw: RawLaunchRule, file: &str, diags: &mut Vec<Diagnostic>) -> LaunchRule {
    let condition = raw.condition.map(|c| match c {
        RawEntitySpec::Any(s) => EntitySpec::Any(s),
        RawEntitySpec::Constraints(params, span) => {
            let (mut name, mut entity_type, mut max) = (None, None, None);
            let mut seen = std::collections::BTreeSet::new();
            for p in &params {
                if duplicate(&mut seen, p, file, diags) {
                    continue;
                }
                match p.key.value.as_str() {
                    "name" => name = ident_value(p, file, diags),
                    "type" => entity_type = ident_value(p, file, diags),
                    "max" => match &p.value {
                        RawValue::Int(i) if i.value >= 0 => {
                            max = Some(Spanned::new(i.value as u64, i.span.clone()))
                        }
                        other => {
                            let span = match other {
                                RawValue::Int(i) => i.span.clone(),
                                RawValue::Ident(s) | RawValue::Str(s) => s.span.clone(),
                            };
                            diags.push(Diagnostic::error(
                                "E0204",
                                "`max` must be a non-negative integer",
                                file,
                                span,
                            ));
                        }
                    },
                    other => diags.push(
                        Diagnostic::error(
                            "E0203",
                            format!("unknown entity constraint `{other}`"),
                            file,
                            p.key.span.clone(),
                        )
                        .with_hint("the constraints are `name`, `type` and `max`"),
                    ),
                }
            }
            EntitySpec::Constraints {
                name,
                entity_type,
                max,
                span,
            }
        }
    });
    let instructions = raw
        .instructions
        .into_iter()
        .map(|i| LaunchInstruction {
            name: i.name,
            reference: i.reference,
            count: count(i.count, file, diags),
            span: i.span,
        })
        .collect();
    LaunchRule {
        condition,
        instructions,
        span: raw.span,
    }
}
