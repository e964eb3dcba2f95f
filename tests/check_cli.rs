//! `goal check` as a user runs it: every program in `agents/` is accepted; bad files (missing,
//! directory, invalid UTF-8, too large, unterminated quote or comment) give diagnostics and exit 1.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `goal check ARGS...`: (exit code, stdout, stderr).
fn check(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("check")
        .args(args)
        .current_dir(root())
        .output()
        .expect("run goal");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A scratch directory for this test binary (under the target directory).
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("check_cli");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir.join(name)
}

fn files_under(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files_under(&p, out);
        } else if matches!(
            p.extension().and_then(|e| e.to_str()),
            Some("goal" | "mod2g" | "mas2g" | "test2g" | "pl")
        ) {
            out.push(p);
        }
    }
}

#[test]
fn every_program_in_agents_is_accepted() {
    let mut files = Vec::new();
    files_under(&root().join("agents"), &mut files);
    files.sort();
    assert!(files.len() >= 5, "corpus missing: {files:?}");
    let args: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, stdout, stderr) = check(&args);
    assert!(!stdout.contains("error["), "{stdout}");
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(stderr.contains("0 errors"), "{stderr}");
}

#[test]
fn missing_file_and_directory_are_errors() {
    let (code, stdout, _) = check(&["no/such/file.goal"]);
    assert_eq!(code, 1);
    assert!(
        stdout.contains("error[E0017]") && stdout.contains("no such file"),
        "{stdout}"
    );
    let (code, stdout, _) = check(&["agents"]);
    assert_eq!(code, 1);
    assert!(
        stdout.contains("error[E0017]") && stdout.contains("is a directory"),
        "{stdout}"
    );
}

#[test]
fn invalid_utf8_and_huge_files_are_errors() {
    let bad = scratch("latin1.goal");
    std::fs::write(&bad, b"main module { program { if bel(caf\xe9) then a. } }").expect("write");
    let (code, stdout, _) = check(&[bad.to_str().expect("path")]);
    assert_eq!(code, 1);
    assert!(stdout.contains("error[E0018]"), "{stdout}");
    assert!(stdout.contains("offset 34"), "{stdout}");

    let huge = scratch("huge.goal");
    let line = "% padding padding padding padding padding padding padding padding\n";
    let text = line.repeat(10 * 1024 * 1024 / line.len() + 1);
    std::fs::write(&huge, text).expect("write");
    let (code, stdout, _) = check(&[huge.to_str().expect("path")]);
    assert_eq!(code, 1);
    assert!(stdout.contains("error[E0019]"), "{stdout}");
}

#[test]
fn unterminated_quote_and_comment_report_line_and_column() {
    let (code, stdout, _) = check(&[
        "tests/fixtures/goal/invalid/E0011_unterminated_quote.goal",
        "tests/fixtures/goal/invalid/E0012_unterminated_comment.goal",
    ]);
    assert_eq!(code, 1);
    assert!(
        stdout.contains("E0011_unterminated_quote.goal:3:14"),
        "{stdout}"
    );
    assert!(
        stdout.contains("E0012_unterminated_comment.goal:3:3"),
        "{stdout}"
    );
}

#[test]
fn warnings_alone_exit_zero() {
    let (code, stdout, stderr) = check(&["tests/fixtures/goal/legacy_send.goal"]);
    assert!(stdout.contains("warning[W0002]"), "{stdout}");
    assert!(!stdout.contains("error["), "{stdout}");
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn json_format_gives_one_object_per_line() {
    let (code, stdout, _) = check(&[
        "--format",
        "json",
        "tests/fixtures/goal/invalid/E0014_several_errors.goal",
    ]);
    assert_eq!(code, 1);
    let objects: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    let errors: Vec<(String, u64, u64)> = objects
        .iter()
        .filter(|o| o["code"] == "E0014")
        .map(|o| {
            (
                o["code"].as_str().unwrap_or("").to_string(),
                o["line"].as_u64().unwrap_or(0),
                o["column"].as_u64().unwrap_or(0),
            )
        })
        .collect();
    assert_eq!(
        errors,
        vec![
            ("E0014".to_string(), 4, 31),
            ("E0014".to_string(), 10, 13),
            ("E0014".to_string(), 12, 17),
            ("E0014".to_string(), 13, 22),
        ]
    );
}
