//! `goal new`: every template in every generation makes a project that passes `goal check` and
//! `goal test` at once (and whose `goal run` completes); every file of its `templates/`
//! directory is written; an existing directory is never overwritten.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const TEMPLATES: [&str; 3] = ["bw4t", "blocks", "empty"];
const GENERATIONS: [&str; 3] = ["2014", "modular", "course"];

/// A fresh empty directory under the system temp dir.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-new-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn goal(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn ok(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what}: exit {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status.code(),
        text(&out.stdout),
        text(&out.stderr)
    );
}

/// The sorted file names in a directory.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("listable")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The `.mas2g` and `.test2g` file of a project directory.
fn main_files(project: &Path) -> (String, String) {
    let names = listing(project);
    let one = |ext: &str| {
        let found: Vec<&String> = names.iter().filter(|n| n.ends_with(ext)).collect();
        assert_eq!(found.len(), 1, "one {ext} file in {names:?}");
        found[0].clone()
    };
    (one(".mas2g"), one(".test2g"))
}

#[test]
fn every_template_and_generation_checks_runs_and_passes_its_test() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = temp_dir("all");
    for template in TEMPLATES {
        for generation in GENERATIONS {
            let name = format!("{template}-{generation}");
            let made = goal(
                &dir,
                &[
                    "new",
                    &name,
                    "--template",
                    template,
                    "--generation",
                    generation,
                ],
            );
            ok(&made, &format!("goal new {name}"));
            assert!(
                text(&made.stderr).contains("created"),
                "{}",
                text(&made.stderr)
            );
            let project = dir.join(&name);

            // Every file of its templates/ directory (where it has one; others are shipped
            // agents) is written, and a README beside them.
            let written = listing(&project);
            let dir = root.join("templates").join(template).join(generation);
            if dir.is_dir() {
                let mut expected = listing(&dir);
                expected.push("README.md".into());
                expected.sort();
                assert_eq!(written, expected, "{name}");
            }
            assert!(
                written.contains(&"README.md".to_string()),
                "{name}: {written:?}"
            );
            let readme = std::fs::read_to_string(project.join("README.md")).expect("readme");
            assert!(readme.starts_with(&format!("# {name}\n")), "{readme}");
            assert!(
                !readme.contains("{{"),
                "unfilled placeholder in {name}:\n{readme}"
            );

            let (mas, test) = main_files(&project);
            let check = goal(&project, &["check", &mas]);
            ok(&check, &format!("goal check {name}/{mas}"));
            assert!(
                text(&check.stderr).contains(" 0 errors, 0 warnings"),
                "{name}: {}",
                text(&check.stderr)
            );
            let tested = goal(&project, &["test", &test]);
            ok(&tested, &format!("goal test {name}/{test}"));
            assert!(text(&tested.stdout).contains("test result: ok."), "{name}");
            let run = goal(&project, &["run", &mas]);
            ok(&run, &format!("goal run {name}/{mas}"));
            let summary = text(&run.stderr);
            let expected_end = if template == "bw4t" {
                "result      completed"
            } else {
                "result      all agents stopped"
            };
            assert!(summary.contains(expected_end), "{name}:\n{summary}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_existing_directory_is_refused_and_left_alone() {
    let dir = temp_dir("exists");
    std::fs::create_dir_all(dir.join("mine")).expect("dir");
    std::fs::write(dir.join("mine/robot.goal"), "my work").expect("file");
    let out = goal(&dir, &["new", "mine"]);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.contains("`mine` already exists"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.join("mine/robot.goal")).expect("kept"),
        "my work"
    );
    assert_eq!(listing(&dir.join("mine")), vec!["robot.goal".to_string()]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unknown_template_is_a_usage_error_listing_the_choices() {
    let dir = temp_dir("usage");
    let out = goal(&dir, &["new", "x", "--template", "bw5t"]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(err.contains("bw4t") && err.contains("blocks"), "{err}");
    assert!(!dir.join("x").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
