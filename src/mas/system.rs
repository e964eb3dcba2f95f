//! A loaded multi-agent system: the environment's init parameters, one compiled program per
//! agent file (parsed and validated once, shared by every agent of that file) and the launch
//! rules. Loads from disk, from files built into the binary, or a single `.goal` file.

use super::environment::{Builtin, EnvSetup};
use crate::agent::Program;
use crate::diag::Diagnostic;
use crate::syntax::mas2g::ast::{AgentName, LaunchInstruction, LaunchRule, Spanned};
use crate::term::Term;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A diagnostic together with the text of the file it points into (for rendering).
#[derive(Clone, Debug)]
pub struct Problem {
    pub diagnostic: Diagnostic,
    pub source: Arc<str>,
}

impl Problem {
    /// A problem without source text (e.g. a file that could not be read).
    pub fn bare(diagnostic: Diagnostic) -> Problem {
        Problem {
            diagnostic,
            source: Arc::from(""),
        }
    }

    /// The rustc-like rendering with a source excerpt.
    pub fn render(&self) -> String {
        self.diagnostic.render(&self.source)
    }
}

/// Where the files of a system come from.
#[derive(Clone, Debug)]
pub enum Origin {
    /// Paths relative to this directory.
    Disk(PathBuf),
    /// Files built into the binary: (path, text).
    Embedded(&'static [(&'static str, &'static str)]),
}

impl Origin {
    fn read(&self, path: &str) -> Result<(String, String), Diagnostic> {
        match self {
            Origin::Disk(base) => {
                let full = base.join(path);
                let text = crate::syntax::check::read_source(&full)?;
                Ok((full.display().to_string(), text))
            }
            Origin::Embedded(files) => files
                .iter()
                .find(|(p, _)| *p == path)
                .map(|(p, t)| (p.to_string(), t.to_string()))
                .ok_or_else(|| {
                    Diagnostic::error(
                        "E0205",
                        format!("agent file `{path}` not found"),
                        path,
                        0..0,
                    )
                }),
        }
    }

    fn base_dir(&self) -> Option<&Path> {
        match self {
            Origin::Disk(b) => Some(b.as_path()),
            Origin::Embedded(_) => None,
        }
    }
}

/// A multi-agent system ready to launch.
#[derive(Clone, Debug)]
pub struct MasSystem {
    /// The `.mas2g` file (or the single `.goal` file).
    pub file: String,
    /// The built-in environment and its init parameters; `None` runs without an environment.
    pub env: Option<EnvSetup>,
    /// Compiled programs by reference name.
    pub programs: BTreeMap<String, Arc<Program>>,
    /// The KR engine an agent file's entry chose (`language = scryer` or `native`).
    pub engines: BTreeMap<String, crate::kr::KrKind>,
    /// Agent file path (as loaded) by reference name.
    pub files: BTreeMap<String, String>,
    /// Launch rules in file order.
    pub rules: Vec<LaunchRule>,
    /// Warnings met while loading.
    pub warnings: Vec<Problem>,
}

/// Loads a `.mas2g` file from disk.
pub fn load_mas(path: &Path) -> Result<MasSystem, Vec<Problem>> {
    let file = path.display().to_string();
    let text = crate::syntax::check::read_source(path).map_err(|d| vec![Problem::bare(d)])?;
    // Modular GOAL (A) and MARBEL (B) systems are assembled by their own loader.
    if crate::syntax::modular::detect::mas_generation(&text)
        != crate::syntax::modular::ast::Generation::Classic
    {
        return super::modular::load(path, &text);
    }
    let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    from_mas_text(&file, &text, Origin::Disk(base))
}

/// Builds a system from `.mas2g` text whose agent files come from `origin`.
pub fn from_mas_text(file: &str, text: &str, origin: Origin) -> Result<MasSystem, Vec<Problem>> {
    let src: Arc<str> = Arc::from(text);
    let (mas, mut diags) = crate::syntax::mas2g::parse(text, file);
    if let Some(base) = origin.base_dir() {
        diags.extend(crate::syntax::mas2g::check_files(&mas, base));
    }
    let (setup, env_diags) = super::envcheck::check_mas(&mas);
    diags.extend(env_diags);
    let wrap = |d: Diagnostic| Problem {
        diagnostic: d,
        source: src.clone(),
    };
    let (errors, warnings): (Vec<_>, Vec<_>) = diags.into_iter().partition(|d| d.is_error());
    if !errors.is_empty() {
        return Err(errors.into_iter().map(wrap).collect());
    }
    let mut system = MasSystem {
        file: file.to_string(),
        env: None,
        programs: BTreeMap::new(),
        engines: BTreeMap::new(),
        files: BTreeMap::new(),
        rules: mas.launch_rules.clone(),
        warnings: warnings.into_iter().map(wrap).collect(),
    };
    system.env = setup.map(|s| with_map_path(s, &origin));
    let kind = system.env.as_ref().map(|e| e.kind);
    let mut problems = Vec::new();
    let mut compiled: BTreeMap<String, (String, Arc<Program>)> = BTreeMap::new();
    for af in &mas.agent_files {
        let reference = af.reference_name();
        if system.programs.contains_key(&reference) {
            continue;
        }
        if let Some(Ok(Some(kind))) = af
            .language
            .as_ref()
            .map(|l| crate::kr::KrKind::parse(&l.value))
        {
            system.engines.insert(reference.clone(), kind);
        }
        // The same file under two reference names is compiled once and shared.
        if let Some((path, prog)) = compiled.get(&af.path.value) {
            system.files.insert(reference.clone(), String::clone(path));
            system.programs.insert(reference, Arc::clone(prog));
            continue;
        }
        match compile_file(&origin, &af.path.value, kind) {
            Ok((path, prog, warns)) => {
                system.warnings.extend(warns);
                compiled.insert(af.path.value.clone(), (path.clone(), prog.clone()));
                system.files.insert(reference.clone(), path);
                system.programs.insert(reference, prog);
            }
            Err(p) => problems.extend(p),
        }
    }
    if problems.is_empty() {
        Ok(system)
    } else {
        Err(problems)
    }
}

/// A system of one agent (named after the file) without an environment.
pub fn load_agent(path: &Path) -> Result<MasSystem, Vec<Problem>> {
    let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("agent");
    let reference = name.strip_suffix(".goal").unwrap_or(name).to_string();
    let (file, prog, warnings) = compile_file(&Origin::Disk(base), name, None)?;
    let inst = LaunchInstruction {
        name: Some(AgentName::Given(Spanned::new(reference.clone(), 0..0))),
        reference: Spanned::new(reference.clone(), 0..0),
        count: None,
        span: 0..0,
    };
    Ok(MasSystem {
        file: file.clone(),
        env: None,
        programs: BTreeMap::from([(reference.clone(), prog)]),
        engines: BTreeMap::new(),
        files: BTreeMap::from([(reference, file)]),
        rules: vec![LaunchRule {
            condition: None,
            instructions: vec![inst],
            span: 0..0,
        }],
        warnings,
    })
}

type Compiled = (String, Arc<Program>, Vec<Problem>);

/// Reads, parses, validates and compiles one agent file; with an environment, also checks its
/// `@env` actions and percept queries against it.
fn compile_file(
    origin: &Origin,
    path: &str,
    env: Option<Builtin>,
) -> Result<Compiled, Vec<Problem>> {
    let (file, text) = origin.read(path).map_err(|d| vec![Problem::bare(d)])?;
    // The same front end as `goal check`: imports, validation and compilation.
    let loaded = crate::agent::load::load_goal(&file, &text, origin.base_dir());
    let problems = loaded.diagnostics.into_iter().map(|s| Problem {
        diagnostic: s.diagnostic,
        source: s.source,
    });
    let Some(prog) = loaded.program else {
        return Err(problems.filter(|p| p.diagnostic.is_error()).collect());
    };
    let mut warnings: Vec<Problem> = problems.collect();
    if let Some(kind) = env {
        // The environment's actions and percepts: the program parsed clean, so parse it again
        // for its AST (cheap next to compiling it).
        let (ast, _) = crate::syntax::goal::parse_goal(&file, &text);
        let source: Arc<str> = Arc::from(text.as_str());
        warnings.extend(
            super::envcheck::check_program(kind, &ast)
                .into_iter()
                .map(|diagnostic| Problem {
                    diagnostic,
                    source: source.clone(),
                }),
        );
    }
    Ok((file, prog, warnings))
}

/// The setup with a map file named relative to the `.mas2g` file made relative to the
/// working directory (`\\` separators of Windows paths read as `/`).
pub(crate) fn with_map_path(mut setup: EnvSetup, origin: &Origin) -> EnvSetup {
    let (Some(map), Some(base)) = (setup.params.get("map"), origin.base_dir()) else {
        return setup;
    };
    let text = match map {
        Term::Atom(s) => s.name().to_string(),
        Term::Str(s) => s.to_string(),
        _ => return setup,
    };
    let path = text.replace('\\', "/");
    if crate::bw4t::map::builtin(&text).is_none() && base.join(&path).is_file() {
        let joined = base.join(&path).display().to_string();
        setup.params.insert("map".into(), Term::string(&joined));
    }
    setup
}
