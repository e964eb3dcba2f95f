//! `goal prolog`: the built binary loads `.pl` files and prints the answers of queries.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

/// A `.pl` file in a fresh temporary directory, removed on drop.
struct TempPl {
    dir: PathBuf,
    path: PathBuf,
}

impl TempPl {
    fn new(name: &str, text: &str) -> TempPl {
        let dir =
            std::env::temp_dir().join(format!("goal-cli-prolog-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join(format!("{name}.pl"));
        std::fs::write(&path, text).expect("write temp file");
        TempPl { dir, path }
    }
}

impl Drop for TempPl {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

const FAMILY: &str = "\
% a small family
parent(tom, bob).
parent(tom, liz).
parent(bob, ann).
parent(bob, 'Pat Q').
ancestor(X, Y) :- parent(X, Y).
ancestor(X, Y) :- parent(X, Z), ancestor(Z, Y).
pair(X, f(X, _)).
";

fn goal(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run goal");
    {
        let mut input = child.stdin.take().expect("stdin");
        if let Some(text) = stdin {
            input.write_all(text.as_bytes()).expect("write stdin");
        }
    }
    child.wait_with_output().expect("wait for goal")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn query(file: &TempPl, q: &str) -> (String, Output) {
    let o = goal(&["prolog", file.path.to_str().unwrap_or(""), "-q", q], None);
    (stdout(&o), o)
}

#[test]
fn prints_every_answer_with_named_variables_in_order() {
    let f = TempPl::new("answers", FAMILY);
    let (out, o) = query(&f, "ancestor(tom, Who), Who \\== liz");
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(out, "Who = bob\nWho = ann\nWho = 'Pat Q'\n");
    let (out, _) = query(&f, "parent(P, C), _Hidden = P");
    assert_eq!(
        out.lines().next(),
        Some("P = tom, C = bob"),
        "variables starting with _ are not shown"
    );
    let (out, _) = query(&f, "findall(C, parent(bob, C), L)");
    assert_eq!(out, "C = _, L = [ann,'Pat Q']\n");
    let (out, _) = query(&f, "pair(a, T)");
    assert_eq!(out, "T = f(a,_)\n");
}

#[test]
fn prints_true_false_and_errors() {
    let f = TempPl::new("tfe", FAMILY);
    assert_eq!(query(&f, "parent(tom, bob)").0, "true\n");
    assert_eq!(query(&f, "parent(ann, X)").0, "false\n");
    assert_eq!(
        query(&f, "undefined_predicate(X)").0,
        "false\n",
        "undefined predicates fail in GOAL"
    );
    let (out, o) = query(&f, "X is Y + 1");
    assert_eq!(o.status.code(), Some(1), "an error answer exits 1");
    assert!(out.starts_with("error"), "got {out:?}");
    assert!(out.contains("instantiation_error"), "got {out:?}");
    assert_eq!(out.lines().count(), 1);
}

#[test]
fn reads_queries_from_stdin_without_q() {
    let f = TempPl::new("stdin", FAMILY);
    let o = goal(
        &["prolog", f.path.to_str().unwrap_or("")],
        Some("parent(tom, X).\n\nparent(X, ann)\nparent(nobody, _)\n"),
    );
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(stdout(&o), "X = bob\nX = liz\nX = bob\nfalse\n");
}

#[test]
fn load_errors_exit_1_with_diagnostics() {
    let f = TempPl::new("bad", "p(a).\np(b :- .\nq(X) :- assert(X).\n");
    let (out, o) = query(&f, "p(X)");
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(out, "");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("error"), "stderr: {err}");
    assert!(err.contains("bad.pl"), "diagnostics name the file: {err}");

    let f = TempPl::new("protected", "q(X) :- assert(X).\n");
    let (_, o) = query(&f, "q(a)");
    assert_eq!(
        o.status.code(),
        Some(1),
        "protected predicates are rejected at load time"
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("assert"), "stderr: {err}");
}

#[test]
fn malformed_query_is_a_diagnostic_not_a_crash() {
    let f = TempPl::new("malformed", FAMILY);
    let (out, o) = query(&f, "parent(tom, ");
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(out, "");
    assert!(!String::from_utf8_lossy(&o.stderr).contains("panicked"));
}
