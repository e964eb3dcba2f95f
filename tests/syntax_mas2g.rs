//! `.mas2g` parsing and checking: correct fixtures (AST snapshots) and one negative fixture per
//! diagnostic code (rendered diagnostics snapshotted, code and line:column asserted).

use goal::diag::Diagnostic;
use goal::syntax::mas2g;
use std::path::Path;

#[path = "negative_support/mod.rs"]
mod common;

fn parse_and_check(rel: &str) -> (String, mas2g::MasFile, Vec<Diagnostic>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let source = std::fs::read_to_string(&path).expect("fixture readable");
    let (mas, mut diags) = mas2g::parse(&source, rel);
    let base = path.parent().expect("fixture has a directory");
    diags.extend(mas2g::check_files(&mas, base));
    diags.extend(goal::mas::envcheck::check_mas(&mas).1);
    (source, mas, diags)
}

#[test]
fn correct_fixtures_parse_without_diagnostics() {
    for name in ["bw4t", "every_construct"] {
        let rel = format!("tests/fixtures/mas2g/{name}.mas2g");
        let (source, mas, diags) = parse_and_check(&rel);
        let rendered: Vec<String> = diags.iter().map(|d| d.render(&source)).collect();
        assert!(diags.is_empty(), "{rel}: {}", rendered.join("\n"));
        insta::assert_snapshot!(format!("mas2g_{name}"), mas.dump());
    }
}

#[test]
fn every_construct_has_the_expected_shape() {
    let (_, mas, _) = parse_and_check("tests/fixtures/mas2g/every_construct.mas2g");
    assert_eq!(mas.agent_files.len(), 2);
    assert_eq!(mas.agent_files[1].path.value, "agents/coordinator.goal");
    assert_eq!(mas.agent_files[1].reference_name(), "coordinator");
    assert_eq!(mas.launch_rules.len(), 5);
    assert_eq!(mas.launch_rules[1].instructions[0].count(), 3);
    assert!(mas.launch_rules[2].condition.is_some());
    assert!(mas.may_launch("helper2"));
    assert!(mas.may_launch("boss"));
    let env = mas
        .environment
        .as_ref()
        .and_then(|e| e.env.as_ref())
        .map(|e| e.value.clone());
    assert_eq!(env.as_deref(), Some("bw4t"));
}

#[test]
fn launched_names_follow_the_counting_scheme() {
    let src = "agentfiles { \"a.goal\". } launchpolicy { launch bob:a[2], a. }";
    let (mas, diags) = mas2g::parse(src, "x.mas2g");
    assert!(diags.is_empty(), "{diags:?}");
    assert!(mas.may_launch("bob1") && mas.may_launch("bob2") && mas.may_launch("a"));
    assert!(!mas.may_launch("bob") && !mas.may_launch("bob3") && !mas.may_launch("carol"));
}

#[test]
fn negative_fixtures_report_their_code_at_the_expected_place() {
    for (rel, code, line, col) in common::negative_fixtures("tests/fixtures/mas2g/invalid", "mas2g")
    {
        let (source, _, diags) = parse_and_check(&rel);
        common::assert_reported(&rel, &source, &diags, &code, line, col);
        let stem = Path::new(&rel)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("?")
            .to_string();
        insta::assert_snapshot!(
            format!("mas2g_invalid_{stem}"),
            common::render_all(&source, &diags)
        );
    }
}

#[test]
fn garbage_never_panics() {
    let inputs = [
        "",
        "}",
        "{",
        "environment",
        "environment {",
        "agentfiles { \"a",
        "launchpolicy { launch",
        "launchpolicy { when [",
        "environment { env = \"x\" + }",
        "/*",
        "%",
        "\u{0}",
        "[[[[",
        "launchpolicy { launch a:b[99999999999999999999]. }",
        "agentfiles { . . . }",
    ];
    for input in inputs {
        let (_, diags) = mas2g::parse(input, "g.mas2g");
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
        "[",
        "]",
        "(",
        ")",
        ".",
        ",",
        ":",
        "*",
        "+",
        "=",
        "\"",
        "'",
        "%",
        "/*",
        "*/",
        "@env",
        "launch ",
        "when ",
        "entity",
        " do ",
        "max",
        "type",
        "name",
        "environment",
        "agentfiles",
        "launchpolicy",
        "-",
        "9999999999999999999999",
        "1.5",
        "é",
        "\0",
        "\n",
    ];
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("tests/fixtures/mas2g");
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
                .filter(|p| p.extension().is_some_and(|e| e == "mas2g"))
                .map(|p| std::fs::read(p).expect("fixture")),
        );
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x3a52);
    for _ in 0..30_000 {
        let pick = rng.gen_range(0..corpus.len());
        let src = common::mutate(&mut rng, &corpus[pick], &tokens);
        let (mas, mut diags) = mas2g::parse(&src, "m.mas2g");
        diags.extend(mas2g::check_files(&mas, &dir));
        common::assert_spans_inside("m.mas2g", &src, &diags);
    }
}

#[test]
fn goal_check_of_a_mas_file_also_checks_its_agent_files() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mas2g/every_construct.mas2g");
    let reports = goal::syntax::check::check_path_with_agents(&path);
    let files: Vec<String> = reports
        .iter()
        .map(|r| {
            Path::new(&r.file)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        })
        .collect();
    assert_eq!(
        files,
        ["every_construct.mas2g", "explorer.goal", "coordinator.goal"]
    );
    for r in &reports {
        assert!(!r.has_errors(), "{}: {:?}", r.file, r.diagnostics);
    }
}

/// Every `.mas2g` and `.test2g` shipped under `agents/` checks without errors (with the agent
/// files a MAS names).
#[test]
fn shipped_mas_and_test_files_have_no_errors() {
    fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        let mut paths: Vec<_> = entries.filter_map(|e| e.ok()).map(|e| e.path()).collect();
        paths.sort();
        for p in paths {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "mas2g" || e == "test2g") {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("agents"),
        &mut files,
    );
    if files.is_empty() {
        println!("no .mas2g or .test2g files under agents/ yet");
    }
    for f in files {
        for r in goal::syntax::check::check_path_with_agents(&f) {
            let rendered: Vec<String> = r.diagnostics.iter().map(|d| d.render(&r.source)).collect();
            assert!(!r.has_errors(), "{}:\n{}", r.file, rendered.join(""));
        }
    }
}

#[test]
fn old_environment_and_launch_forms_parse() {
    let src = "environment{ \"environments\\BW4T2\\BW4TClient.jar\". init [agentcount = \"1\"] . }\n\
               agentfiles{ \"agents\\ag.goal\". \"stackBuilder.goal\". }\n\
               launchpolicy{ launch ag[100]:ag. when entity@env do launch stackbuilder:stackBuilder. }";
    let (mas, diags) = mas2g::parse(src, "old.mas2g");
    assert!(diags.is_empty(), "{diags:?}");
    let env = mas.environment.as_ref().unwrap();
    // Backslashes are path separators, not escapes.
    assert_eq!(
        env.env.as_ref().unwrap().value,
        "environments\\BW4T2\\BW4TClient.jar"
    );
    assert_eq!(env.init.len(), 1);
    assert_eq!(mas.agent_files[0].path.value, "agents/ag.goal");
    let inst = &mas.launch_rules[0].instructions[0];
    assert_eq!(inst.reference.value, "ag");
    assert_eq!(inst.count(), 100);
    assert!(mas.may_launch("ag100") && !mas.may_launch("ag101"));
    assert!(mas.launch_rules[1].condition.is_some());
}
