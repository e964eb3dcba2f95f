//! The validator (§11): every program in `agents/` has no errors, and one negative fixture per
//! error and warning code (rendered diagnostics snapshotted, code and line:column asserted).

use goal::diag::Diagnostic;
use goal::syntax::{goal::parse_goal, validate::validate};
use std::path::{Path, PathBuf};

#[path = "negative_support/mod.rs"]
mod common;

/// Parses and validates a file given relative to the crate root.
fn check(rel: &str) -> (String, Vec<Diagnostic>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let source = std::fs::read_to_string(&path).expect("file readable");
    let (program, mut diags) = parse_goal(rel, &source);
    diags.extend(validate(&program, path.parent()));
    (source, diags)
}

fn goal_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() && !p.ends_with("invalid") {
            goal_files(&p, out);
        } else if p.extension().and_then(|e| e.to_str()) == Some("goal") {
            out.push(p);
        }
    }
}

#[test]
fn every_agent_program_validates_without_errors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    goal_files(&root.join("agents"), &mut files);
    goal_files(&root.join("tests/fixtures/goal"), &mut files);
    assert!(
        files.len() >= 5,
        "expected the agent corpus, found {files:?}"
    );
    for f in files {
        let rel = f
            .strip_prefix(root)
            .expect("inside the crate")
            .to_string_lossy()
            .into_owned();
        let (source, diags) = check(&rel);
        let errors: Vec<&Diagnostic> = diags.iter().filter(|d| d.is_error()).collect();
        println!("=== {rel}\n{}", common::render_all(&source, &diags));
        assert!(
            errors.is_empty(),
            "{rel}:\n{}",
            common::render_all(&source, &diags)
        );
    }
}

#[test]
fn negative_fixtures_report_their_code_at_the_expected_place() {
    for (rel, code, line, col) in common::negative_fixtures("tests/fixtures/invalid", "goal") {
        let (source, diags) = check(&rel);
        common::assert_reported(&rel, &source, &diags, &code, line, col);
        let stem = Path::new(&rel)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("?")
            .to_string();
        insta::assert_snapshot!(
            format!("validator_{stem}"),
            common::render_all(&source, &diags)
        );
    }
}
