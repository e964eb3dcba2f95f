//! One fixture per parser diagnostic (`tests/fixtures/goal/invalid/<CODE>_*.goal`): the file's
//! code is reported, every span lies in the file, and the rendered diagnostics are snapshotted.

use goal::syntax::goal::{parse_goal, parse_mod2g};
use std::path::Path;

#[test]
fn each_invalid_fixture_reports_its_code() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/goal/invalid");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("fixture directory")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(names.len() >= 15, "fixtures missing: {names:?}");
    for name in names {
        let src = std::fs::read_to_string(dir.join(&name)).expect("fixture");
        let file = format!("invalid/{name}");
        let diags = if name.ends_with(".mod2g") {
            parse_mod2g(&file, &src).1
        } else {
            parse_goal(&file, &src).1
        };
        let code = &name[..5];
        assert!(
            diags.iter().any(|d| d.code == code),
            "{name}: expected {code}, got {diags:#?}"
        );
        let mut rendered = String::new();
        for d in &diags {
            assert!(d.span.end <= src.len(), "{name}: {d:?}");
            rendered.push_str(&d.render(&src));
        }
        let stem = name.split('.').next().unwrap_or(&name).to_string();
        insta::assert_snapshot!(stem, rendered);
    }
}

#[test]
fn several_errors_in_one_file_are_all_reported() {
    let src = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/goal/invalid/E0014_several_errors.goal"),
    )
    .expect("fixture");
    let (program, diags) = parse_goal("x.goal", &src);
    let lines: Vec<usize> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.line_col(&src).0)
        .collect();
    // The broken spec (line 4), `if ... act.` (10), `forall ... then` (12), `a + + b` (13).
    assert_eq!(lines, vec![4, 10, 12, 13], "{diags:#?}");
    // The good rules around the broken ones are still in the AST.
    let main = program
        .modules
        .iter()
        .find(|m| m.name() == "main")
        .expect("main module");
    assert_eq!(main.program.as_ref().map(|p| p.rules.len()), Some(2));
}

#[test]
fn deep_nesting_of_blocks_and_terms_is_a_diagnostic_not_a_crash() {
    let blocks = "main module { program { if true then ".to_string()
        + &"{ if true then ".repeat(5_000)
        + "a."
        + &"}".repeat(5_000)
        + "}}";
    let (_, diags) = parse_goal("deep.goal", &blocks);
    assert!(diags.iter().any(|d| d.code == "E0016"), "{diags:?}");
    let terms = format!(
        "main module {{ program {{ if bel({}a{}) then act. }} }}",
        "f(".repeat(100_000),
        ")".repeat(100_000)
    );
    let (_, diags) = parse_goal("deep.goal", &terms);
    for d in &diags {
        assert!(d.span.end <= terms.len());
    }
}

#[test]
fn a_missing_dot_loses_only_its_own_rule() {
    let src = "main module {\n program {\n  if bel(p) then a\n  if bel(q) then b.\n  forall bel(r) do c.\n }\n}\n";
    let (program, diags) = parse_goal("m.goal", src);
    let errors: Vec<(usize, usize)> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.line_col(src))
        .collect();
    assert_eq!(errors, vec![(4, 3)], "{diags:#?}");
    let rules = &program.modules[0].program.as_ref().expect("program").rules;
    assert_eq!(rules.len(), 2);
    assert_eq!(rules[0].span.start, src.find("if bel(q)").expect("rule"));
}
