//! Resolving the `#import` lines of a `.goal` program: which file each one names (trying the
//! known extensions when the path has none, as GOAL did), and reading the imported `.mod2g`
//! modules and `.pl` clauses. `goal check` and `goal run` both use this, so they agree on what a
//! file means.

use crate::diag::Diagnostic;
use crate::syntax::ast::{AgentProgram, Import, ImportKind, Module};
use crate::syntax::prolog::{Located, Reader};
use std::path::{Path, PathBuf};

/// Extensions tried, in order, for an import path written without one.
pub fn known_extensions(kind: ImportKind) -> &'static [&'static str] {
    match kind {
        ImportKind::Module => &["mod2g"],
        ImportKind::Prolog => &["pl", "pro", "prolog"],
    }
}

/// The file an import names: the path as written when it is a file, else (for a path without an
/// extension) the first known extension that names a file.
pub fn resolve_path(dir: &Path, import: &Import) -> Option<PathBuf> {
    let path = dir.join(&import.path);
    if path.is_file() {
        return Some(path);
    }
    if Path::new(&import.path).extension().is_some() {
        return None;
    }
    known_extensions(import.kind)
        .iter()
        .map(|ext| dir.join(format!("{}.{ext}", import.path)))
        .find(|p| p.is_file())
}

/// A module read from an imported `.mod2g` file, with that file's name and text (its spans
/// refer to that text).
#[derive(Clone, Debug)]
pub struct ImportedModule {
    pub file: String,
    pub source: String,
    pub module: Module,
}

/// A problem found in an imported file (its spans refer to `source`).
#[derive(Clone, Debug)]
pub struct ImportProblem {
    pub source: String,
    pub diagnostic: Diagnostic,
}

/// What the imports of one program bring in.
#[derive(Clone, Debug, Default)]
pub struct Imports {
    /// Modules of imported `.mod2g` files, in import order.
    pub modules: Vec<ImportedModule>,
    /// Clauses of imported `.pl` files, in import order (they join the knowledge).
    pub knowledge: Vec<Located>,
    /// Imports that name no file (E0120), in the importing file.
    pub missing: Vec<Diagnostic>,
    /// Errors and warnings inside the imported files.
    pub problems: Vec<ImportProblem>,
}

/// Reads every import of `program` (top level and inside modules) relative to `dir`.
pub fn read_imports(program: &AgentProgram, dir: &Path) -> Imports {
    let mut out = Imports::default();
    let mut work: Vec<(PathBuf, Import, String)> = program
        .imports
        .iter()
        .chain(program.modules.iter().flat_map(|m| m.imports.iter()))
        .map(|i| (dir.to_path_buf(), i.clone(), program.file.clone()))
        .rev()
        .collect();
    let mut seen: Vec<PathBuf> = Vec::new();
    while let Some((dir, import, importer)) = work.pop() {
        let Some(path) = resolve_path(&dir, &import) else {
            let d = missing(&importer, &import);
            if importer == program.file {
                out.missing.push(d);
            } else {
                out.problems.push(ImportProblem {
                    source: importer_source(&out, &importer),
                    diagnostic: d,
                });
            }
            continue;
        };
        // A file imported twice is read once.
        if seen.contains(&path) {
            continue;
        }
        seen.push(path.clone());
        let name = path.display().to_string();
        let text = match crate::syntax::check::read_source(&path) {
            Ok(t) => t,
            Err(d) => {
                out.problems.push(ImportProblem {
                    source: String::new(),
                    diagnostic: d,
                });
                continue;
            }
        };
        let diags = match import.kind {
            ImportKind::Module => {
                let (m, d) = super::parse_mod2g(&name, &text);
                if let Some(module) = m {
                    // Prolog files imported inside the module are relative to its own file.
                    let here = path.parent().unwrap_or(Path::new(".")).to_path_buf();
                    for i in module.imports.iter().rev() {
                        work.push((here.clone(), i.clone(), name.clone()));
                    }
                    out.modules.push(ImportedModule {
                        file: name,
                        source: text.clone(),
                        module,
                    });
                }
                d
            }
            ImportKind::Prolog => {
                let mut reader = Reader::goal(name);
                let (clauses, mut d) = reader.clauses(&text, 0);
                d.append(&mut reader.warnings);
                out.knowledge.extend(clauses);
                d
            }
        };
        out.problems
            .extend(diags.into_iter().map(|diagnostic| ImportProblem {
                source: text.clone(),
                diagnostic,
            }));
    }
    out
}

/// The text of an imported module file (for diagnostics that point into it).
fn importer_source(out: &Imports, file: &str) -> String {
    out.modules
        .iter()
        .find(|m| m.file == file)
        .map_or(String::new(), |m| m.source.clone())
}

fn missing(importer: &str, import: &Import) -> Diagnostic {
    let tried = if Path::new(&import.path).extension().is_none() {
        let exts: Vec<String> = known_extensions(import.kind)
            .iter()
            .map(|e| format!("`.{e}`"))
            .collect();
        format!(" (also tried with {})", exts.join(", "))
    } else {
        String::new()
    };
    Diagnostic::error(
        "E0120",
        format!("imported file `{}` not found{tried}", import.path),
        importer,
        import.span.clone(),
    )
    .with_hint("the path is relative to the directory of the importing file")
}
