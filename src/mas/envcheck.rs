//! Checks a `.mas2g` file and its agents against the built-in environment it selects: the
//! environment reference itself, the init parameters, every `@env` action specification and
//! every `percept(...)` query (name and arity), with "did you mean" for near misses.

use super::environment::{select_environment, Builtin, EnvSetup};
use crate::diag::Diagnostic;
use crate::env::{did_you_mean, InitParams};
use crate::syntax::ast::{ActionSpecKind, AgentProgram, LiteralKind, Rule, RuleBody};
use crate::syntax::check::FileReport;
use crate::syntax::mas2g::ast::{InitValue, MasFile};
use crate::syntax::prolog::{Located, TermSpans};
use crate::term::{Float, Term};
use std::path::Path;

/// The init parameters of `mas`'s environment section as terms (the first of duplicate keys).
pub fn init_params(mas: &MasFile) -> InitParams {
    let mut params = InitParams::new();
    for p in mas.environment.iter().flat_map(|e| &e.init) {
        params
            .entry(p.key.value.clone())
            .or_insert_with(|| init_term(&p.value));
    }
    params
}

/// An init value as a term; nesting is bounded by the `.mas2g` lexer, and lists are built
/// without recursion on their length.
fn init_term(v: &InitValue) -> Term {
    match v {
        InitValue::Ident(s) => Term::atom(&s.value),
        InitValue::Int(i) => Term::Int(i.value),
        InitValue::Float(f) => Term::Float(Float(f.value)),
        InitValue::Str(s) => Term::string(&s.value),
        InitValue::Function { name, args, .. } => {
            Term::compound(name.value.as_str(), args.iter().map(init_term).collect())
        }
        InitValue::List { items, .. } => {
            Term::list(items.iter().map(init_term).collect::<Vec<_>>())
        }
    }
}

/// The environment `mas` selects (`None` without an `env`), with an error for one that is not
/// built in and warnings for init parameters that have no effect.
pub fn check_mas(mas: &MasFile) -> (Option<EnvSetup>, Vec<Diagnostic>) {
    let Some(env) = mas.environment.as_ref().and_then(|e| e.env.as_ref()) else {
        return (None, Vec::new());
    };
    let file = mas.file.as_str();
    match select_environment(&env.value, &init_params(mas)) {
        Err(msg) => {
            let d = Diagnostic::error("E0208", msg, file, env.span.clone()).with_hint(
                "write `env = \"bw4t\".` or `env = \"blocksworld\".`, or name a BW4T client jar",
            );
            (None, vec![d])
        }
        Ok(setup) => {
            let span_of = |key: &str| {
                mas.environment
                    .iter()
                    .flat_map(|e| &e.init)
                    .find(|p| p.key.value.eq_ignore_ascii_case(key))
                    .map_or(env.span.clone(), |p| p.span.clone())
            };
            let mut diags: Vec<Diagnostic> = setup
                .warnings
                .iter()
                .map(|(key, text)| Diagnostic::warning("W0207", text.clone(), file, span_of(key)))
                .collect();
            // BW4T settings (except the map, checked when it is loaded) are checked here so that
            // a bad value points at its place in the file.
            if setup.kind == Builtin::Bw4t {
                let mut settings = setup.params.clone();
                settings
                    .retain(|k, _| k != "map" && crate::bw4t::INIT_PARAMS.contains(&k.as_str()));
                if let Err(errors) = crate::bw4t::Bw4t::from_params(&settings) {
                    diags.extend(errors.into_iter().map(|mut d| {
                        let key = d.message.split('`').nth(1).unwrap_or("");
                        let key = if key == "robots" && setup.params.contains_key("robots") {
                            let written = mas_key(mas, &["agentcount", "robots"]);
                            d.message = d.message.replacen("`robots`", &format!("`{written}`"), 1);
                            written
                        } else {
                            key.to_string()
                        };
                        d.file = file.to_string();
                        d.span = span_of(&key);
                        d
                    }));
                }
            }
            // The blocks world's towers are all in the `.mas2g` file: check them here.
            if setup.kind == Builtin::BlocksWorld {
                if let Err(errors) = crate::blocksworld::init::towers(&setup.params) {
                    let key = if setup.params.contains_key("start") {
                        "start"
                    } else {
                        "blocks"
                    };
                    diags.extend(errors.into_iter().map(|mut d| {
                        d.file = file.to_string();
                        d.span = span_of(key);
                        d
                    }));
                }
            }
            (Some(setup), diags)
        }
    }
}

/// The first of `keys` written in `mas`'s init list, in any case (the first of `keys` if none).
fn mas_key(mas: &MasFile, keys: &[&str]) -> String {
    mas.environment
        .iter()
        .flat_map(|e| &e.init)
        .map(|p| p.key.value.clone())
        .find(|k| keys.iter().any(|w| k.eq_ignore_ascii_case(w)))
        .unwrap_or_else(|| keys[0].to_string())
}

/// Warnings for `@env` action specifications and `percept(...)` queries of `program` that the
/// environment `kind` does not have.
pub fn check_program(kind: Builtin, program: &AgentProgram) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let file = program.file.as_str();
    let actions = kind.actions();
    let percepts: Vec<String> = kind
        .percepts()
        .into_iter()
        .map(|(n, a)| format!("{n}/{a}"))
        .collect();
    let percepts: Vec<&str> = percepts.iter().map(String::as_str).collect();
    for module in &program.modules {
        for spec in &module.action_specs {
            check_query(&spec.pre.term, kind, &percepts, file, &mut out);
            if spec.kind != ActionSpecKind::Env {
                continue;
            }
            let (name, arity) = (spec.name.name.name(), spec.params.len());
            let what = format!(
                "is not an action of the built-in {} environment",
                kind.name()
            );
            let Some(msg) = unknown("action", name, arity, &what, actions) else {
                continue;
            };
            out.push(
                Diagnostic::warning("W0210", msg, file, spec.name.span.clone()).with_hint(format!(
                    "its actions are {}; the action will fail",
                    actions.join(", ")
                )),
            );
        }
        let mut rules: Vec<&Rule> = Vec::new();
        if let Some(p) = &module.program {
            rules.extend(&p.rules);
            for m in &p.macros {
                for lit in &m.body {
                    literal(&lit.kind, kind, &percepts, file, &mut out);
                }
            }
        }
        while let Some(rule) = rules.pop() {
            for lit in &rule.condition {
                literal(&lit.kind, kind, &percepts, file, &mut out);
            }
            if let RuleBody::Block(inner) = &rule.body {
                rules.extend(inner);
            }
        }
    }
    out.sort_by_key(|d| d.span.start);
    out
}

/// `"{kind} name/arity {what} (did you mean ...?)"` when `name/arity` is not `known`.
fn unknown(kind: &str, name: &str, arity: usize, what: &str, known: &[&str]) -> Option<String> {
    if known.contains(&format!("{name}/{arity}").as_str()) {
        return None;
    }
    let mut msg = format!("{kind} {name}/{arity} {what}");
    if let Some(k) = did_you_mean(name, arity, known) {
        msg.push_str(&format!(" (did you mean {k}?)"));
    }
    Some(msg)
}

fn literal(l: &LiteralKind, kind: Builtin, known: &[&str], file: &str, out: &mut Vec<Diagnostic>) {
    if let LiteralKind::Mental { query, .. } = l {
        check_query(query, kind, known, file, out);
    }
}

/// Finds every `percept(P)` in a query (iteratively) and checks `P` (or `Q` in `not(Q)`).
fn check_query(q: &Located, kind: Builtin, known: &[&str], file: &str, out: &mut Vec<Diagnostic>) {
    let mut stack: Vec<(&Term, &TermSpans)> = vec![(&q.term, &q.spans)];
    while let Some((t, s)) = stack.pop() {
        let Some((f, n)) = t.functor() else { continue };
        if f.name() == "percept" && n == 1 {
            let mut content = vec![(&t.args()[0], s.args.first().unwrap_or(s))];
            while let Some((p, ps)) = content.pop() {
                let Some((name, arity)) = p.functor() else {
                    continue;
                };
                let child = |i: usize| ps.args.get(i).unwrap_or(ps);
                match (name.name(), arity) {
                    ("," | ";", 2) => {
                        content.extend([(&p.args()[0], child(0)), (&p.args()[1], child(1))])
                    }
                    ("not", 1) => content.push((&p.args()[0], child(0))),
                    (name, arity) => unknown_percept(name, arity, ps, kind, known, file, out),
                }
            }
            continue;
        }
        for (i, a) in t.args().iter().enumerate() {
            stack.push((a, s.args.get(i).unwrap_or(s)));
        }
    }
}

fn unknown_percept(
    name: &str,
    arity: usize,
    at: &TermSpans,
    kind: Builtin,
    known: &[&str],
    file: &str,
    out: &mut Vec<Diagnostic>,
) {
    let what = format!("is never sent by the built-in {} environment", kind.name());
    let Some(msg) = unknown("percept", name, arity, &what, known) else {
        return;
    };
    out.push(
        Diagnostic::warning("W0211", msg, file, at.span.clone())
            .with_hint("see docs/environments.md for the percepts of the built-in environments"),
    );
}

/// `goal check` of one file with the environment checks: for a `.mas2g`, the environment it
/// selects and every agent file it names against that environment.
pub fn check_path(path: &Path) -> Vec<FileReport> {
    if path.is_dir() {
        return crate::syntax::check::check_dir(path, &check_path);
    }
    let mut reports = crate::agent::load::check_path_with_agents(path);
    if path.extension().and_then(|e| e.to_str()) != Some("mas2g") || reports.is_empty() {
        return reports;
    }
    let (source, file) = (&reports[0].source, &reports[0].file);
    let classic = crate::syntax::modular::detect::mas_generation(source)
        == crate::syntax::modular::ast::Generation::Classic;
    let mas = if classic {
        crate::syntax::mas2g::parse(source, file).0
    } else {
        let (modular, _) = crate::syntax::modular::mas::parse(source, file);
        match &modular.env {
            Some(e) => super::modular::classic_env(&modular, e),
            None => return reports,
        }
    };
    let (setup, diags) = check_mas(&mas);
    reports[0].diagnostics.extend(diags);
    let Some(setup) = setup else {
        return reports;
    };
    if let Some(map) = map_report(&setup, path.parent().unwrap_or(Path::new("."))) {
        reports.push(map);
    }
    for r in reports.iter_mut().skip(1) {
        if !r.file.ends_with(".goal") || r.has_errors() {
            continue;
        }
        let (ast, _) = crate::syntax::goal::parse_goal(&r.file, &r.source);
        r.diagnostics.extend(check_program(setup.kind, &ast));
    }
    reports
}

/// The problems of the BW4T map file `setup` names (relative to `base`), as a report on that
/// file; `None` for a built-in map, a map without problems, or no BW4T.
fn map_report(setup: &EnvSetup, base: &Path) -> Option<FileReport> {
    if setup.kind != Builtin::Bw4t {
        return None;
    }
    let name = match setup.params.get("map")? {
        Term::Atom(a) => a.name().to_string(),
        Term::Str(s) => s.to_string(),
        _ => return None,
    };
    if crate::bw4t::map::builtin(&name).is_some() {
        return None;
    }
    let path = base.join(name.replace('\\', "/"));
    let file = path.display().to_string();
    let errors = crate::bw4t::map::load(&file).err()?;
    Some(FileReport {
        source: std::fs::read_to_string(&path).unwrap_or_default(),
        file,
        diagnostics: errors,
    })
}
