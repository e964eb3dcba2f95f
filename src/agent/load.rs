//! The one front end for `.goal` files: parse, read the imports, validate and compile. `goal run`
//! loads agents with it and `goal check` checks `.goal` files with it, so a file that checks
//! clean also compiles, and both commands see the same imported modules and clauses.

use super::program::Program;
use crate::diag::Diagnostic;
use crate::syntax::check::{check_path, read_source, FileReport};
use crate::syntax::goal::imports::{read_imports, Imports};
use std::path::Path;
use std::sync::Arc;

/// A diagnostic with the text of the file it points into (an imported file or the program).
#[derive(Clone, Debug)]
pub struct Sourced {
    pub diagnostic: Diagnostic,
    pub source: Arc<str>,
}

/// The result of loading one `.goal` file.
#[derive(Debug)]
pub struct Loaded {
    /// The compiled program, when there are no errors.
    pub program: Option<Arc<Program>>,
    /// Every error and warning: the program's first, then those of imported files.
    pub diagnostics: Vec<Sourced>,
}

/// Loads the `.goal` text `text` of `file`; imports are read relative to `base_dir` (none are
/// read without one, e.g. for embedded programs).
pub fn load_goal(file: &str, text: &str, base_dir: Option<&Path>) -> Loaded {
    let own: Arc<str> = Arc::from(text);
    let (ast, mut diags) = crate::syntax::goal::parse_goal(file, text);
    let mut imported = Vec::new();
    let imports = match base_dir {
        Some(dir) => read_imports(&ast, dir),
        None => Imports::default(),
    };
    for p in &imports.problems {
        imported.push(Sourced {
            diagnostic: p.diagnostic.clone(),
            source: Arc::from(p.source.as_str()),
        });
    }
    if !diags.iter().any(Diagnostic::is_error) {
        diags.extend(crate::syntax::validate::validate_with(&ast, &imports));
    }
    let clean = !diags.iter().any(Diagnostic::is_error)
        && !imported.iter().any(|s| s.diagnostic.is_error());
    let mut program = None;
    if clean {
        match Program::compile_with(&ast, text, &imports) {
            Ok(p) => {
                diags.extend(p.warnings.iter().cloned());
                program = Some(p);
            }
            Err(ds) => diags.extend(ds),
        }
    }
    let sourced = |d: Diagnostic| {
        // Compile diagnostics may point into an imported module file.
        let source = match imports.modules.iter().find(|m| m.file == d.file) {
            Some(m) => Arc::from(m.source.as_str()),
            None => own.clone(),
        };
        Sourced {
            diagnostic: d,
            source,
        }
    };
    let mut diagnostics: Vec<Sourced> = diags.into_iter().map(sourced).collect();
    diagnostics.extend(imported);
    Loaded {
        program,
        diagnostics,
    }
}

/// Checks one file as `goal check` does: `.goal` files through [`load_goal`] (one report per
/// file that has diagnostics, the program's own first), other files by `syntax::check`.
pub fn check_file(path: &Path) -> Vec<FileReport> {
    if path.extension().and_then(|e| e.to_str()) != Some("goal") {
        return vec![check_path(path)];
    }
    let file = path.display().to_string();
    let source = match read_source(path) {
        Ok(s) => s,
        Err(d) => {
            return vec![FileReport {
                file,
                source: String::new(),
                diagnostics: vec![d],
            }]
        }
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let loaded = load_goal(&file, &source, Some(dir));
    let mut reports = vec![FileReport {
        file: file.clone(),
        source,
        diagnostics: Vec::new(),
    }];
    for s in loaded.diagnostics {
        let at = reports.iter().position(|r| r.file == s.diagnostic.file);
        match at {
            Some(i) => reports[i].diagnostics.push(s.diagnostic),
            None => reports.push(FileReport {
                file: s.diagnostic.file.clone(),
                source: s.source.to_string(),
                diagnostics: vec![s.diagnostic],
            }),
        }
    }
    for r in &mut reports {
        r.diagnostics.sort_by(|a, b| {
            (a.span.start, a.span.end, &a.code).cmp(&(b.span.start, b.span.end, &b.code))
        });
        r.diagnostics.dedup();
    }
    reports
}

/// Checks one file as `goal check` does and, for a `.mas2g`, also the agent files it names.
pub fn check_path_with_agents(path: &Path) -> Vec<FileReport> {
    crate::syntax::check::with_agents(path, &check_file)
}
