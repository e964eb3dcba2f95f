//! Loading a modular GOAL (A) or MARBEL (B) `.mas2g`: every agent definition is assembled into
//! one 2014 program (`syntax::modular`), compiled, and its line numbers mapped back to the files
//! they come from. The result is an ordinary [`MasSystem`], so launching, running, tracing and
//! testing have one path for every generation.

use super::system::{env_params, MasSystem, Origin, Problem};
use crate::agent::Program;
use crate::diag::Diagnostic;
use crate::env::InitParams;
use crate::syntax::mas2g::ast::{Environment, MasFile, Spanned};
use crate::syntax::modular::check::{check_agent, is_builtin_env};
use crate::syntax::modular::sources::SourceSet;
use crate::term::Term;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// Loads the modular `.mas2g` at `path` with text `text`.
pub fn load(path: &Path, text: &str) -> Result<MasSystem, Vec<Problem>> {
    let file = path.display().to_string();
    let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let src: Arc<str> = Arc::from(text);
    let (mas, diags) = crate::syntax::modular::mas::parse(text, &file);
    let wrap = |d: Diagnostic| Problem {
        diagnostic: d,
        source: src.clone(),
    };
    let mut warnings = Vec::new();
    let mut problems = Vec::new();
    for d in diags {
        if d.is_error() {
            problems.push(wrap(d));
        } else {
            warnings.push(wrap(d));
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let env = mas.env.as_ref().and_then(|e| {
        if !is_builtin_env(&e.reference.value) {
            warnings.push(wrap(
                Diagnostic::warning(
                    "W0207",
                    format!(
                        "environment `{}` is not built in: running without one",
                        e.reference.value
                    ),
                    file.clone(),
                    e.reference.span.clone(),
                )
                .with_hint("only BW4T is built in (a reference whose name contains `bw4t`)"),
            ));
            return None;
        }
        // One place maps the reference and parameters to the built-in environment.
        let classic = MasFile {
            file: file.clone(),
            environment: Some(Environment {
                env: Some(Spanned::new("bw4t".to_string(), e.reference.span.clone())),
                init: e.params.clone(),
                span: e.span.clone(),
            }),
            agent_files: Vec::new(),
            launch_rules: Vec::new(),
        };
        let params = env_params(&classic, &Origin::Disk(base.clone()))?;
        let (params, notes) = client_params(params);
        warnings.extend(notes.into_iter().map(|n| {
            wrap(
                Diagnostic::warning("W0608", n, file.clone(), e.span.clone())
                    .with_hint("the built-in BW4T reads map, robots, seed and its own options"),
            )
        }));
        Some(params)
    });
    let mut programs = BTreeMap::new();
    let mut files = BTreeMap::new();
    for agent in &mas.agents {
        let (build, diags) = check_agent(&mas, text, &base, agent);
        let mut errors = Vec::new();
        for d in diags {
            let (d, text) = build.sources.localize(d);
            let p = Problem {
                diagnostic: d,
                source: text,
            };
            if p.diagnostic.is_error() {
                errors.push(p);
            } else {
                warnings.push(p);
            }
        }
        for (name, span) in &build.unsupported {
            let d = Diagnostic::error(
                "E0600",
                format!("`{name}` cannot be run by this runtime yet"),
                file.clone(),
                span.clone(),
            )
            .with_hint("remove the action; see docs/modular-goal.md for what is supported");
            let (d, text) = build.sources.localize(d);
            errors.push(Problem {
                diagnostic: d,
                source: text,
            });
        }
        if !errors.is_empty() {
            problems.extend(errors);
            continue;
        }
        match Program::compile(&build.program, &build.sources.text) {
            Ok(mut prog) => {
                let main_file = main_file(&build.sources, &prog);
                if let Some(p) = Arc::get_mut(&mut prog) {
                    for w in std::mem::take(&mut p.warnings) {
                        let (d, text) = build.sources.localize(w);
                        warnings.push(Problem {
                            diagnostic: d,
                            source: text,
                        });
                    }
                    localize_lines(p, &build.sources);
                    p.file = main_file.clone();
                }
                files.insert(agent.name.value.clone(), main_file);
                programs.insert(agent.name.value.clone(), prog);
            }
            Err(ds) => problems.extend(ds.into_iter().map(|d| {
                let (d, text) = build.sources.localize(d);
                Problem {
                    diagnostic: d,
                    source: text,
                }
            })),
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    Ok(MasSystem {
        file,
        env,
        programs,
        files,
        rules: mas.launch,
        warnings,
    })
}

/// The file of the agent's main module (the file a trace names for the agent).
fn main_file(sources: &SourceSet, prog: &Program) -> String {
    let line = prog.modules[prog.main].line;
    sources.local_line(line).0.to_string()
}

/// Line numbers of the compiled program (lines of the shared text) as lines of their own files.
fn localize_lines(p: &mut Program, sources: &SourceSet) {
    let mas_file = sources.segments[0].name.as_str();
    for m in &mut p.modules {
        m.line = sources.local_line(m.line).1;
    }
    for b in &mut p.blocks {
        for r in &mut b.rules {
            let module = r.label.rsplit_once(':').map_or("", |(m, _)| m).to_string();
            let (file, line) = sources.local_line(r.line);
            r.line = line;
            // Rules the lowering added point into the MAS file: say so in their label.
            r.label = if file == mas_file {
                let base = Path::new(file)
                    .file_name()
                    .and_then(|f| f.to_str())
                    .unwrap_or(file);
                format!("{module}:{base}:{line}").into()
            } else {
                format!("{module}:{line}").into()
            };
            if let crate::agent::program::Body::Combo(actions) = &mut r.body {
                for a in actions {
                    a.line = sources.local_line(a.line).1;
                }
            }
        }
    }
}

/// BW4T client parameters (§4.4 of the modular reference) as the built-in environment's:
/// keys in any case, `agentcount` → `robots`, a built-in map name in any case; keys that only
/// matter to the Java client or server are dropped with a note. Returns the notes.
fn client_params(params: InitParams) -> (InitParams, Vec<String>) {
    let mut out = InitParams::new();
    let mut notes = Vec::new();
    for (key, value) in params {
        let lower = key.to_ascii_lowercase();
        let known = crate::bw4t::INIT_PARAMS
            .iter()
            .find(|k| k.eq_ignore_ascii_case(&key));
        match (lower.as_str(), known) {
            ("agentcount", _) => {
                out.entry("robots".to_string()).or_insert(value);
            }
            ("map", _) => {
                let name = match &value {
                    Term::Atom(s) => Some(s.name().to_string()),
                    Term::Str(s) => Some(s.to_string()),
                    _ => None,
                };
                let builtin = name
                    .map(|n| n.to_ascii_lowercase())
                    .filter(|n| crate::bw4t::map::builtin(n).is_some());
                out.insert("map".into(), builtin.map_or(value, |n| Term::string(&n)));
            }
            // The client's `speed` is ticks per second; lock-step runs ignore it.
            ("speed", _) => {
                notes.push("`speed` (ticks per second) is ignored in lock-step runs".into())
            }
            (_, Some(k)) => {
                out.insert(k.to_string(), value);
            }
            ("humancount", _) if value != Term::Int(0) => notes.push(
                "`humancount`: no human entities are created (there is no GUI to drive them)"
                    .into(),
            ),
            (
                "clientip" | "clientport" | "serverip" | "serverport" | "launchgui" | "goal"
                | "goalhuman" | "agentclass" | "kill" | "log" | "humancount",
                _,
            ) => {}
            _ => notes.push(format!("init parameter `{key}` is not known: ignored")),
        }
    }
    (out, notes)
}
