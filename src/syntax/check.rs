//! Checking one file by its extension: read it safely, parse it, collect every diagnostic.

use crate::diag::Diagnostic;
use crate::syntax::goal;
use crate::syntax::modular::{self, ast::Generation};
use std::path::Path;

/// Files larger than this are refused with a diagnostic.
pub const MAX_FILE_BYTES: u64 = 10 * 1024 * 1024;

/// The result of checking one file: its text (for rendering) and its diagnostics.
#[derive(Clone, Debug)]
pub struct FileReport {
    /// The file name as given.
    pub file: String,
    /// The file's text (empty if it could not be read).
    pub source: String,
    pub diagnostics: Vec<Diagnostic>,
}

impl FileReport {
    /// True when some diagnostic is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// Reads a source file: missing files, directories, invalid UTF-8 and files over 10 MB are
/// diagnostics.
pub fn read_source(path: &Path) -> Result<String, Diagnostic> {
    let file = path.display().to_string();
    let err = |code: &str, msg: String| Diagnostic::error(code, msg, file.clone(), 0..0);
    let meta = std::fs::metadata(path)
        .map_err(|e| err("E0017", format!("cannot read `{file}`: {}", io_reason(&e))))?;
    if meta.is_dir() {
        return Err(err("E0017", format!("`{file}` is a directory, not a file")));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(err(
            "E0019",
            format!(
                "`{file}` is {} bytes, more than the limit of {MAX_FILE_BYTES} bytes",
                meta.len()
            ),
        ));
    }
    let bytes = std::fs::read(path)
        .map_err(|e| err("E0017", format!("cannot read `{file}`: {}", io_reason(&e))))?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        Diagnostic::error(
            "E0018",
            format!("`{file}` is not valid UTF-8 (invalid byte at offset {at})"),
            file.clone(),
            at..at,
        )
        .with_hint("save the file as UTF-8")
    })
}

fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".to_string(),
        std::io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        _ => e.to_string(),
    }
}

/// Checks one file, dispatching on its extension (.goal, .mod2g, .pl).
pub fn check_path(path: &Path) -> FileReport {
    let file = path.display().to_string();
    let source = match read_source(path) {
        Ok(s) => s,
        Err(d) => {
            return FileReport {
                file,
                source: String::new(),
                diagnostics: vec![d],
            }
        }
    };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let diagnostics = match ext {
        "goal" => {
            let (program, mut d) = goal::parse_goal(&file, &source);
            d.extend(crate::syntax::validate::validate(
                &program,
                Some(base_dir(path)),
            ));
            d
        }
        "mod2g" if modular::detect::module_generation(&source, base_dir(path)) != Generation::Classic => {
            let gen = modular::detect::module_generation(&source, base_dir(path));
            modular::check::check_module_file(path, &source, gen)
        }
        "act2g" => modular::check::check_act_file(path, &source),
        "mod2g" => {
            let (module, mut d) = goal::parse_mod2g(&file, &source);
            if let Some(m) = &module {
                d.extend(crate::syntax::validate::validate_module_file(
                    m,
                    &file,
                    Some(base_dir(path)),
                ));
            }
            d
        }
        "pl" => modular::check::check_pl_file(path, &source),
        "mas2g" => {
            let (mas, mut d) = crate::syntax::mas2g::parse(&source, &file);
            d.extend(crate::syntax::mas2g::check_files(&mas, base_dir(path)));
            d
        }
        "test2g" => {
            let (test, mut d) = crate::syntax::test2g::parse(&source, &file);
            if let Some(t) = &test {
                d.extend(crate::syntax::test2g::check_files(t, base_dir(path)));
            }
            d
        }
        _ => vec![Diagnostic::error(
            "E0024",
            format!("unknown kind of file `{file}`"),
            file.clone(),
            0..0,
        )
        .with_hint("goal check reads .goal, .mod2g, .act2g, .pl, .mas2g and .test2g files, and directories")],
    };
    FileReport {
        file,
        source,
        diagnostics,
    }
}

/// The directory that paths written in `path` are relative to.
fn base_dir(path: &Path) -> &Path {
    path.parent().unwrap_or(Path::new("."))
}

/// Checks one file and, for a `.mas2g`, also the agent files it names that exist (each once);
/// for a directory, every `.mas2g` file in it with everything those use.
pub fn check_path_with_agents(path: &Path) -> Vec<FileReport> {
    with_agents(path, &|p| vec![check_path(p)])
}

/// Checks one file with `check` and, for a `.mas2g`, also the `.goal` agent files it names that
/// exist (each once); for a directory, every `.mas2g` file in it. `check` may return several
/// reports for one file (its imported files). Modular `.mas2g` files are checked with everything
/// they use by the modular front end.
pub fn with_agents(path: &Path, check: &dyn Fn(&Path) -> Vec<FileReport>) -> Vec<FileReport> {
    if path.is_dir() {
        return check_dir(path, &|m| with_agents(m, check));
    }
    if path.extension().and_then(|e| e.to_str()) == Some("mas2g") {
        if let Ok(text) = read_source(path) {
            if modular::detect::mas_generation(&text) != Generation::Classic {
                return modular::check::check_mas(path, &text);
            }
        }
    }
    let mut out = check(path);
    let Some(report) = out.first() else {
        return out;
    };
    if path.extension().and_then(|e| e.to_str()) == Some("mas2g") && !report.source.is_empty() {
        let (mas, _) = crate::syntax::mas2g::parse(&report.source, &report.file);
        for agent in crate::syntax::mas2g::check::agent_file_paths(&mas, base_dir(path)) {
            if agent.is_file() && agent.extension().and_then(|e| e.to_str()) == Some("goal") {
                out.extend(check(&agent));
            }
        }
    }
    out
}

/// Checks a project directory: every `.mas2g` file directly in it (sorted by name) and what
/// they use, each file reported once.
pub fn check_dir(dir: &Path, each: &dyn Fn(&Path) -> Vec<FileReport>) -> Vec<FileReport> {
    let mut mas: Vec<_> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some("mas2g"))
        .collect();
    mas.sort();
    if mas.is_empty() {
        let file = dir.display().to_string();
        let d = Diagnostic::error(
            "E0017",
            format!("`{file}` is a directory with no .mas2g file to check"),
            file.clone(),
            0..0,
        )
        .with_hint(
            "give the directory of a project (with its .mas2g files), or the files to check",
        );
        return vec![FileReport {
            file,
            source: String::new(),
            diagnostics: vec![d],
        }];
    }
    let mut out: Vec<FileReport> = Vec::new();
    for m in mas {
        for r in each(&m) {
            if !out.iter().any(|o| o.file == r.file) {
                out.push(r);
            }
        }
    }
    out
}
