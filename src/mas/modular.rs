//! Loading a modular GOAL (A) or MARBEL (B) `.mas2g`: every agent definition is assembled into
//! one 2014 program (`syntax::modular`), compiled, and its line numbers mapped back to the files
//! they come from. The result is an ordinary [`MasSystem`], so launching, running, tracing and
//! testing have one path for every generation.

use super::system::{with_map_path, MasSystem, Origin, Problem};
use crate::agent::Program;
use crate::diag::Diagnostic;
use crate::syntax::mas2g::ast::{Environment, MasFile};
use crate::syntax::modular::check::check_agent;
use crate::syntax::modular::mas::{EnvUse, ModMas};
use crate::syntax::modular::sources::SourceSet;
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
    // The environment is selected and checked as for a 2014 `.mas2g` (one place decides).
    let env = mas.env.as_ref().and_then(|e| {
        let classic = classic_env(&mas, e);
        let (setup, diags) = super::envcheck::check_mas(&classic);
        for d in diags {
            if d.is_error() {
                problems.push(wrap(d));
            } else {
                warnings.push(wrap(d));
            }
        }
        setup.map(|s| with_map_path(s, &Origin::Disk(base.clone())))
    });
    if !problems.is_empty() {
        return Err(problems);
    }
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
                    p.channels = true;
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
        engines: BTreeMap::new(),
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
            r.file = file.into();
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

/// The environment of a modular `.mas2g` as a 2014 `.mas2g` with only that section, so that one
/// function (`envcheck::check_mas`) selects and checks the environment of every generation.
pub fn classic_env(mas: &ModMas, e: &EnvUse) -> MasFile {
    MasFile {
        file: mas.file.clone(),
        environment: Some(Environment {
            env: Some(e.reference.clone()),
            init: e.params.clone(),
            span: e.span.clone(),
        }),
        agent_files: Vec::new(),
        launch_rules: Vec::new(),
    }
}
