//! The diagnostic pages (`docs/diagnostics/CODE.md`, shown by `goal explain CODE`): one page per
//! code of the table and no other; every code the source emits is in the table; each page's
//! wrong example, checked as `goal check` checks it, produces its code, and its fixed example
//! does not (codes that no example can show are listed below, each with the reason). An
//! example whose first block is a ```sh block (about files themselves: missing, not UTF-8, too
//! large; or about starting a run) is run as shell commands with `goal` on the PATH.

use goal::syntax::codes::CODES;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Codes whose examples are not files `goal check` can be run on, and why.
const NOT_BY_FILE_CHECK: &[(&str, &str)] = &[
    (
        "E0016",
        "needs about a thousand nested blocks; the page shows a short example",
    ),
    (
        "E0033",
        "needs over 100 problems in one file: `too_many_problems_end_with_e0033` makes one",
    ),
    ("E0401", "found while compiling; the validator reports E0103 first"),
    ("E0403", "found while compiling; the validator reports E0101 first"),
    ("E0406", "found while compiling; the validator reports E0022 first"),
    ("E0408", "found while compiling; the validator reports E0118 first"),
    (
        "E0410",
        "found while compiling; the validator reports E0119 for a parameter that is not a variable",
    ),
    (
        "E0209",
        "only a binary built without the scryer feature reports it; the test suite's binary has it",
    ),
    ("E0412", "found while compiling; the validator reports E0021 first"),
    (
        "E0413",
        "found while compiling (and by `goal test` for a `do` of a missing module); `goal check` reports E0104",
    ),
    (
        "M0021",
        "only the library's `Bw4t::from_params` reports it (`goal check` and `goal run` leave unknown keys out): `the_m0021_examples_give_their_code_through_the_library` runs the page's examples",
    ),
    (
        "M0030",
        "the built-in environment failing inside while a run starts: no input makes it do so",
    ),
    (
        "M0032",
        "a launch of an agent file that `agentfiles` does not list is refused as E0206 before a run starts",
    ),
    (
        "M0033",
        "the operating system refusing a worker thread: no input makes it do so",
    ),
];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn page(code: &str) -> String {
    let path = root().join("docs/diagnostics").join(format!("{code}.md"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `(file name, text)` of the fenced blocks of the section `## {title}` of a page. The info
/// string is the extension, optionally followed by `file=NAME`; the first block is the one
/// checked, the others are files beside it.
fn section_files(page: &str, title: &str) -> Vec<(String, String)> {
    let start = page
        .find(&format!("\n## {title}\n"))
        .unwrap_or_else(|| panic!("no `## {title}` section"));
    let rest = &page[start + title.len() + 5..];
    let section = &rest[..rest.find("\n## ").unwrap_or(rest.len())];
    let mut files = Vec::new();
    let mut lines = section.lines();
    while let Some(line) = lines.next() {
        let Some(info) = line.strip_prefix("```") else {
            continue;
        };
        let mut words = info.split_whitespace();
        let ext = words.next().unwrap_or("").to_string();
        let name = words
            .find_map(|w| w.strip_prefix("file="))
            .map(str::to_string)
            .unwrap_or_else(|| format!("example.{ext}"));
        let body: Vec<&str> = lines.by_ref().take_while(|l| *l != "```").collect();
        files.push((name, body.join("\n") + "\n"));
    }
    files
}

/// Writes the files into a fresh directory and returns the codes `goal check` reports for the
/// first one (and the files it uses), errors marked.
fn check(code: &str, title: &str, files: &[(String, String)]) -> (BTreeSet<String>, bool) {
    let dir = std::env::temp_dir().join(format!(
        "goal-explain-{code}-{title}-{}",
        std::process::id()
    ));
    write_files(&dir, files);
    let result = if files[0].0 == "example.sh" {
        run_commands(&dir, &files[0].1)
    } else {
        let reports = goal::mas::envcheck::check_path(&dir.join(&files[0].0));
        let codes = reports
            .iter()
            .flat_map(|r| r.diagnostics.iter().map(|d| d.code.clone()))
            .collect();
        (codes, reports.iter().any(|r| r.has_errors()))
    };
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// Writes `(name, text)` files into a fresh directory `dir`.
fn write_files(dir: &Path, files: &[(String, String)]) {
    let _ = std::fs::remove_dir_all(dir);
    for (name, text) in files {
        let path: PathBuf = dir.join(name);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("dir");
        std::fs::write(&path, text).expect("write");
    }
}

/// The rendered diagnostic of `code` in `text`: from its `error[CODE]` line to the next
/// diagnostic.
fn rendered<'a>(text: &'a str, code: &str) -> &'a str {
    let start = text
        .find(&format!("error[{code}]"))
        .unwrap_or_else(|| panic!("no error[{code}] in {text}"));
    let rest = &text[start + 1..];
    let end = [rest.find("error["), rest.find("warning[")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(rest.len());
    &text[start..start + 1 + end]
}

/// Runs the lines of a ```sh example in `dir`; the codes in what the commands printed (on
/// stdout, as `goal check` does, or stderr, as `goal run` does), and whether any line failed.
fn run_commands(dir: &Path, script: &str) -> (BTreeSet<String>, bool) {
    let bin = Path::new(env!("CARGO_BIN_EXE_goal"))
        .parent()
        .expect("bin dir");
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let (mut codes, mut failed) = (BTreeSet::new(), false);
    for line in script.lines().filter(|l| !l.trim().is_empty()) {
        let out = std::process::Command::new("sh")
            .arg("-c")
            .arg(line)
            .current_dir(dir)
            .env("PATH", &path)
            .output()
            .expect("sh runs");
        failed |= !out.status.success();
        let text = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
        for (i, _) in text
            .match_indices("error[")
            .chain(text.match_indices("warning["))
        {
            let code = &text[i..].split(['[', ']']).nth(1).unwrap_or("");
            codes.insert(code.to_string());
        }
    }
    (codes, failed)
}

#[test]
fn every_code_has_a_page_and_every_page_a_code() {
    let codes: BTreeSet<String> = CODES.iter().map(|(c, _)| c.to_string()).collect();
    let pages: BTreeSet<String> = std::fs::read_dir(root().join("docs/diagnostics"))
        .expect("docs/diagnostics")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n != "README.md")
        .map(|n| n.trim_end_matches(".md").to_string())
        .collect();
    assert_eq!(codes, pages);
    let index = std::fs::read_to_string(root().join("docs/diagnostics/README.md")).expect("index");
    for (code, meaning) in CODES {
        let row = format!("| [{code}]({code}.md) | {meaning} |");
        assert!(
            index.contains(&row),
            "docs/diagnostics/README.md lacks {row}"
        );
    }
    for (code, _) in CODES {
        let text = page(code);
        assert!(text.starts_with(&format!("# {code}: ")), "{code}: title");
        assert_eq!(goal::syntax::codes::page(code), Some(text.as_str()));
        assert!(!section_files(&text, "Wrong").is_empty(), "{code}: wrong");
        assert!(!section_files(&text, "Fixed").is_empty(), "{code}: fixed");
    }
}

#[test]
fn every_code_the_source_emits_is_in_the_table() {
    let known: BTreeSet<&str> = CODES.iter().map(|(c, _)| *c).collect();
    let mut stack = vec![root().join("src")];
    let mut unknown = Vec::new();
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).expect("src").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let text = std::fs::read_to_string(&p).unwrap_or_default();
            // String literals that are exactly a code: "E0121".
            for (i, _) in text.match_indices('"') {
                let lit = text.get(i + 1..i + 6);
                let close = text.get(i + 6..i + 7);
                if let (Some(lit), Some("\"")) = (lit, close) {
                    let b = lit.as_bytes();
                    if matches!(b[0], b'E' | b'W' | b'M') && b[1..].iter().all(u8::is_ascii_digit) {
                        if !known.contains(lit) {
                            unknown.push(format!("{}: {lit}", p.display()));
                        }
                    }
                }
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "codes missing from the table: {unknown:?}"
    );
}

#[test]
fn wrong_examples_show_their_code_and_fixed_examples_do_not() {
    let skipped: BTreeSet<&str> = NOT_BY_FILE_CHECK.iter().map(|(c, _)| *c).collect();
    let mut failures = Vec::new();
    for (code, _) in CODES {
        if skipped.contains(code) {
            println!("{code}: not shown by a file check");
            continue;
        }
        let text = page(code);
        let (wrong, _) = check(code, "wrong", &section_files(&text, "Wrong"));
        if !wrong.contains(*code) {
            failures.push(format!("{code}: the wrong example gives {wrong:?}"));
        }
        let (fixed, errors) = check(code, "fixed", &section_files(&text, "Fixed"));
        if fixed.contains(*code) || errors {
            failures.push(format!("{code}: the fixed example gives {fixed:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn goal(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .output()
        .expect("the binary runs")
}

#[test]
fn goal_explain_prints_the_page_of_a_code_in_any_case() {
    for arg in ["E0121", "e0121", " W0110 ", "m0013"] {
        let out = goal(&["explain", arg]);
        assert!(out.status.success(), "{arg}");
        let code = arg.trim().to_ascii_uppercase();
        assert_eq!(String::from_utf8_lossy(&out.stdout), page(&code));
    }
}

#[test]
fn goal_explain_of_an_unknown_code_says_so_and_suggests_one() {
    let out = goal(&["explain", "W0110x"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("`W0110x` is not a diagnostic code"), "{err}");
    assert!(err.contains("did you mean W0110?"), "{err}");
    let out = goal(&["explain", "hello"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("`hello` is not a diagnostic code"), "{err}");
    assert!(!err.contains("did you mean"), "{err}");
}

#[test]
fn rendered_diagnostics_end_with_goal_explain_but_json_does_not() {
    let dir = std::env::temp_dir().join(format!("goal-explain-footer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let file = dir.join("a.goal");
    let files = section_files(&page("E0121"), "Wrong");
    std::fs::write(&file, &files[0].1).expect("write");
    let path = file.to_string_lossy().into_owned();
    let text = goal(&["check", &path]);
    let shown = String::from_utf8_lossy(&text.stdout);
    assert!(shown.contains("error[E0121]"), "{shown}");
    assert!(
        shown
            .trim_end()
            .ends_with("= for more, run goal explain E0121"),
        "{shown}"
    );
    let json = goal(&["check", "--format", "json", &path]);
    let shown = String::from_utf8_lossy(&json.stdout);
    assert!(shown.contains("\"code\":\"E0121\""), "{shown}");
    assert!(!shown.contains("goal explain"), "{shown}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn too_many_problems_end_with_e0033() {
    // 150 rules without `then`: the parser stops recording at 100 and says so.
    let rules = "if bel(p) print(x).\n".repeat(150);
    let text = format!("main module {{ program {{\n{rules}}} }}\n");
    let (_, diags) = goal::syntax::goal::parse_goal("many.goal", &text);
    assert_eq!(diags.len(), 101);
    assert!(diags[..100].iter().all(|d| d.code == "E0014"));
    assert_eq!(diags[100].code, "E0033", "{}", diags[100].message);
}

#[test]
fn map_and_run_errors_end_with_goal_explain() {
    let dir = std::env::temp_dir().join(format!("goal-explain-m-{}", std::process::id()));
    write_files(&dir, &section_files(&page("M0013"), "Wrong"));
    let mas = dir.join("example.mas2g").to_string_lossy().into_owned();
    let out = goal(&["check", &mas]);
    let shown = String::from_utf8_lossy(&out.stdout);
    let d = rendered(&shown, "M0013");
    assert!(d.contains("two-rooms.toml:"), "{d}");
    assert!(
        d.trim_end().ends_with("= for more, run goal explain M0013"),
        "{d}"
    );
    // `goal run` prints its start-up errors on stderr, with the same footer.
    write_files(&dir, &section_files(&page("M0031"), "Wrong"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(["run", "team.mas2g"])
        .current_dir(&dir)
        .output()
        .expect("the binary runs");
    assert_eq!(out.status.code(), Some(1));
    let shown = String::from_utf8_lossy(&out.stderr);
    let d = rendered(&shown, "M0031");
    assert!(
        d.trim_end().ends_with("= for more, run goal explain M0031"),
        "{d}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// M0021 comes only from the library: the parameter of the page's Rust examples, passed to
/// `Bw4t::from_params` as they pass it, gives the code in the wrong example and not in the fixed.
#[test]
fn the_m0021_examples_give_their_code_through_the_library() {
    use goal::bw4t::Bw4t;
    use goal::env::InitParams;
    use goal::term::Term;
    let key = |title: &str| {
        let files = section_files(&page("M0021"), title);
        let text = &files[0].1;
        let open = "InitParams::from([(\"";
        let start = text.find(open).expect("a parameter") + open.len();
        text[start..].split('"').next().expect("a key").to_string()
    };
    let codes =
        |key: String| match Bw4t::from_params(&InitParams::from([(key, Term::atom("true"))])) {
            Ok(_) => Vec::new(),
            Err(ds) => ds.into_iter().map(|d| d.code).collect(),
        };
    assert_eq!(codes(key("Wrong")), ["M0021"]);
    assert_eq!(codes(key("Fixed")), Vec::<String>::new());
}
