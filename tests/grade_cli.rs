//! `goal grade` on the built binary: the fixture class of six submissions (good, slow, wrong
//! colours, crashing, endless loop, reading a file) gives the expected table as CSV, JSON and
//! HTML; a tournament of two submissions; submissions without a runnable `.mas2g`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh empty directory under the system temp dir.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-grade-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// `goal grade ARGS` from the repository root.
fn grade(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("grade")
        .args(args)
        .current_dir(root())
        .output()
        .expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

const MAP: &str = "tests/fixtures/grade/maps/two-rooms.toml";
/// Limits that keep the test short: the good runs complete in about 600 ticks.
const LIMITS: &[&str] = &["--ticks", "3000", "--time-limit", "60", "--jobs", "2"];

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap().flatten() {
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn the_fixture_class_gives_the_expected_table_in_every_format() {
    let dir = temp_dir("class");
    let (csv, json, html) = (dir.join("t.csv"), dir.join("t.json"), dir.join("t.html"));
    let mut args = vec![
        "tests/fixtures/grade/class",
        "--maps",
        MAP,
        "--seeds",
        "1,2",
    ];
    args.extend_from_slice(LIMITS);
    let outs = [&csv, &json, &html].map(|p| p.display().to_string());
    for o in &outs {
        args.extend_from_slice(&["--out", o]);
    }
    let out = grade(&args);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");

    // CSV: the table itself.
    let table = std::fs::read_to_string(&csv).unwrap();
    insta::assert_snapshot!("class_table_csv", table);
    // The same table on standard output, aligned.
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("submission"), "{stdout}");
    assert_eq!(stdout.lines().count(), table.lines().count());

    // JSON: the table, the ranking, the tests and every run; wall times are the only
    // machine-dependent values, and notes name absolute paths.
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let runs = v["runs"].as_array_mut().unwrap();
    assert_eq!(runs.len(), 12);
    let mut notes = std::collections::BTreeMap::new();
    for r in runs.iter_mut() {
        assert!(r["wall_seconds"].as_f64().is_some_and(|w| w >= 0.0), "{r}");
        r["wall_seconds"] = "[wall]".into();
        if let Some(n) = r.as_object_mut().unwrap().remove("note") {
            notes.insert(r["submission"].as_str().unwrap().to_string(), n);
        }
    }
    // Each failing submission stopped for its own reason; the file was never read.
    let note = |s: &str| notes[s].as_str().unwrap().to_string();
    assert!(note("crashing").contains("zero_divisor"), "{notes:?}");
    assert!(note("endless_loop").contains("depth limit"), "{notes:?}");
    assert!(
        note("file_reader").contains("permission_error"),
        "{notes:?}"
    );
    assert!(note("file_reader").contains("open/3"), "{notes:?}");
    assert!(!notes.contains_key("good"), "{notes:?}");
    insta::assert_json_snapshot!("class_report_json", v);

    // HTML: well-formed, self-contained, with the table and the plots.
    let page = std::fs::read_to_string(&html).unwrap();
    well_formed(&page);
    assert!(page.contains("<table>") && page.contains("<td>wrong_colours</td>"));
    assert_eq!(page.matches("<svg").count(), 2, "ticks per map and ranking");
    assert!(page.contains("<title>good on"), "bars name what they show");
    for external in ["src=", "href=", "<script", "@import", "url("] {
        assert!(!page.contains(external), "external asset: {external}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Fails unless `page` parses as XML to its end with balanced tags.
fn well_formed(page: &str) {
    use quick_xml::events::Event;
    let mut r = quick_xml::Reader::from_str(page);
    let mut depth = 0i64;
    let mut elements = 0;
    loop {
        match r.read_event() {
            Ok(Event::Start(_)) => {
                depth += 1;
                elements += 1;
            }
            Ok(Event::End(_)) => depth -= 1,
            Ok(Event::Empty(_)) => elements += 1,
            Ok(Event::Eof) => break,
            Ok(_) => {}
            Err(e) => panic!("not well-formed at {}: {e}", r.buffer_position()),
        }
        assert!(depth >= 0, "a closing tag without its opening tag");
    }
    assert_eq!(depth, 0, "unclosed elements");
    assert!(elements > 50, "{elements} elements");
}

#[test]
fn a_tournament_of_two_submissions() {
    let dir = temp_dir("tournament");
    let class = root().join("tests/fixtures/grade/class");
    copy_dir(&class.join("good"), &dir.join("good"));
    copy_dir(&class.join("wrong_colours"), &dir.join("wrong_colours"));
    // The map file named relative to the copied .mas2g files: give it on the command line.
    let d = dir.display().to_string();
    let csv = dir.join("standings.csv").display().to_string();
    let json = dir.join("standings.json").display().to_string();
    let mut args = vec![d.as_str(), "--tournament", "--maps", MAP, "--seeds", "1"];
    args.extend_from_slice(LIMITS);
    args.extend_from_slice(&["--out", &csv, "--out", &json]);
    let out = grade(&args);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let standings = std::fs::read_to_string(&csv).unwrap();
    insta::assert_snapshot!("tournament_csv", standings);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // Two matches (each submission once as team 1), each scored per team.
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    let names: Vec<&str> = runs
        .iter()
        .map(|r| r["submission"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["good vs wrong_colours", "wrong_colours vs good"]);
    for r in runs {
        assert_eq!(r["teams"].as_array().unwrap().len(), 2, "{r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn submissions_without_one_mas_file_are_reported_not_skipped() {
    let dir = temp_dir("missing");
    copy_dir(
        &root().join("tests/fixtures/grade/class/good"),
        &dir.join("a_good"),
    );
    std::fs::create_dir_all(dir.join("b_empty")).unwrap();
    std::fs::write(dir.join("b_empty/notes.txt"), "no agents here").unwrap();
    copy_dir(
        &root().join("tests/fixtures/grade/class/good"),
        &dir.join("c_two"),
    );
    std::fs::copy(dir.join("c_two/robot.mas2g"), dir.join("c_two/other.mas2g")).unwrap();
    let d = dir.display().to_string();
    let mut args = vec![d.as_str(), "--maps", MAP];
    args.extend_from_slice(LIMITS);
    let out = grade(&args);
    let (stdout, err) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: submission b_empty is not run: no .mas2g file found"),
        "{err}"
    );
    assert!(
        err.contains("submission c_two is not run: 2 .mas2g files"),
        "{err}"
    );
    let line = |name: &str| {
        stdout
            .lines()
            .find(|l| l.starts_with(name))
            .unwrap()
            .to_string()
    };
    assert!(line("a_good").contains("completed 1"), "{stdout}");
    assert!(
        line("b_empty").contains("not run: no .mas2g file found"),
        "{stdout}"
    );
    assert!(
        line("c_two").contains("other.mas2g, robot.mas2g"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unknown_output_format_or_map_is_a_usage_error() {
    let out = grade(&["tests/fixtures/grade/class", "--out", "table.xlsx"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains(".csv, .json or .html"));
    let out = grade(&["tests/fixtures/grade/class", "--maps", "banana,bananas"]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("`bananas` is neither a built-in map (banana,"),
        "{err}"
    );
}

#[test]
fn file_predicates_are_permission_errors_and_their_names_stay_free() {
    let dir = temp_dir("files");
    std::fs::write(dir.join("secret.txt"), "hidden(42).\n").unwrap();
    std::fs::write(dir.join("kb.pl"), "open(door).\n").unwrap();
    let prolog = |q: &str| {
        Command::new(env!("CARGO_BIN_EXE_goal"))
            .args(["prolog", "kb.pl", "-q", q])
            .current_dir(&dir)
            .output()
            .expect("the binary runs")
    };
    for q in [
        "G =.. [open, 'secret.txt', read, S], call(G)",
        "open('secret.txt', read, S, [])",
        "read_term(T, [])",
        "consult('secret.txt')",
        "shell('ls')",
    ] {
        let out = prolog(q);
        let answer = text(&out.stdout);
        assert_eq!(out.status.code(), Some(1), "{q}: {answer}");
        assert!(answer.contains("permission_error"), "{q}: {answer}");
        assert!(!answer.contains("42"), "{q}: {answer}");
    }
    // Knowledge may still define a predicate of such a name (another arity or its own).
    let out = prolog("open(X)");
    assert_eq!(text(&out.stdout).trim(), "X = door");
    // Names that agents use for beliefs are not taken.
    let out = prolog("seen(a, b)");
    assert_eq!(text(&out.stdout).trim(), "false");
    let _ = std::fs::remove_dir_all(&dir);
}
