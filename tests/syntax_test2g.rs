//! `.test2g` parsing and checking: a fixture with every construct (AST snapshot) and one negative
//! fixture per diagnostic code (rendered diagnostics snapshotted, code and line:column asserted).

use goal::diag::Diagnostic;
use goal::syntax::test2g::{self, ast::TestSection};
use std::path::Path;

#[path = "negative_support/mod.rs"]
mod common;

fn parse_and_check(rel: &str) -> (String, Option<test2g::MasTest>, Vec<Diagnostic>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let source = std::fs::read_to_string(&path).expect("fixture readable");
    let (test, mut diags) = test2g::parse(&source, rel);
    if let Some(t) = &test {
        let base = path.parent().expect("fixture has a directory");
        diags.extend(test2g::check_files(t, base));
    }
    (source, test, diags)
}

#[test]
fn every_construct_parses_without_diagnostics() {
    let rel = "tests/fixtures/test2g/every_construct.test2g";
    let (source, test, diags) = parse_and_check(rel);
    assert!(diags.is_empty(), "{}", common::render_all(&source, &diags));
    let test = test.expect("parsed");
    assert_eq!(test.mas.value, "blocks.mas2g");
    assert_eq!(test.timeout.as_ref().map(|t| t.value), Some(20));
    assert_eq!(test.agents.len(), 2);
    assert_eq!(test.agents[1].agents.len(), 2);
    let sections = &test.agents[0].tests[0].sections;
    assert_eq!(sections.len(), 6);
    match &sections[4] {
        TestSection::Evaluate {
            conditions,
            boundary,
            ..
        } => {
            assert_eq!(conditions.len(), 8);
            assert!(boundary.as_ref().is_some_and(|b| b.until));
        }
        other => panic!("expected evaluate, found {other:?}"),
    }
    insta::assert_snapshot!(
        "test2g_every_construct",
        test2g::dump::mas_test(&test, &source)
    );
}

#[test]
fn negative_fixtures_report_their_code_at_the_expected_place() {
    for (rel, code, line, col) in
        common::negative_fixtures("tests/fixtures/test2g/invalid", "test2g")
    {
        let (source, _, diags) = parse_and_check(&rel);
        common::assert_reported(&rel, &source, &diags, &code, line, col);
        let stem = Path::new(&rel)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("?")
            .to_string();
        insta::assert_snapshot!(
            format!("test2g_invalid_{stem}"),
            common::render_all(&source, &diags)
        );
    }
}

#[test]
fn garbage_never_panics() {
    let inputs = [
        "",
        "masTest",
        "masTest {",
        "masTest { mas = ",
        "masTest { mas = \"x\". a { t { do",
        "masTest { mas = \"x\". a { t { evaluate { reactTo(",
        "masTest { mas = \"x\". a { t { assert bel(\"unterminated",
        "do(do(do(",
        "reactTo(reactTo(",
        "/*",
        "\u{0}",
        "masTest { mas = \"x\". timeout = -1. }",
    ];
    for input in inputs {
        let (_, diags) = test2g::parse(input, "g.test2g");
        assert!(
            !diags.is_empty() || input.is_empty(),
            "{input:?} gave no diagnostic"
        );
        for d in &diags {
            assert!(
                d.span.start <= d.span.end && d.span.end <= input.len() + 1,
                "{input:?}: {d:?}"
            );
        }
    }
}

#[test]
fn mutated_fixtures_never_panic_and_spans_stay_in_the_file() {
    use rand::{Rng, SeedableRng};
    let tokens = [
        "{",
        "}",
        "(",
        ")",
        ".",
        ",",
        ":",
        "+",
        "->",
        "\"",
        "'",
        "%",
        "/*",
        "*/",
        "do(",
        "not(",
        "reactTo(",
        "evaluate {",
        " in do ",
        "until ",
        "while ",
        "always ",
        "never ",
        "eventually ",
        "atend ",
        "watch ",
        "assert ",
        "bel(",
        "masTest",
        "mas = ",
        "timeout = ",
        "é",
        "\0",
        "\n",
    ];
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/test2g");
    let mut corpus: Vec<Vec<u8>> = Vec::new();
    for sub in [dir.clone(), dir.join("invalid")] {
        let mut names: Vec<_> = std::fs::read_dir(&sub)
            .expect("fixtures")
            .filter_map(|e| e.ok())
            .map(|e| e.path())
            .collect();
        names.sort();
        corpus.extend(
            names
                .into_iter()
                .filter(|p| p.extension().is_some_and(|e| e == "test2g"))
                .map(|p| std::fs::read(p).expect("fixture")),
        );
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x7e57);
    for i in 0..30_000 {
        let pick = rng.gen_range(0..corpus.len());
        let src = common::mutate(&mut rng, &corpus[pick], &tokens);
        let (test, mut diags) = test2g::parse(&src, "t.test2g");
        // The file-system checks read the MAS file: run them on a sample only.
        if let (Some(t), true) = (&test, i % 20 == 0) {
            diags.extend(test2g::check_files(t, &dir));
        }
        common::assert_spans_inside("t.test2g", &src, &diags);
    }
}
