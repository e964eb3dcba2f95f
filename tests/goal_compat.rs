//! Programs written for GOAL (2014-2016) mean what their authors meant: the leniencies of GOAL's
//! reader are accepted with warnings, imports load at run time as `goal check` reads them,
//! macros are scoped per module, conditions can query mental models of other agents, and test
//! files behave as GOAL's test runner had them. Fixtures: `tests/fixtures/goal2014/`.

use std::path::Path;
use std::process::Command;

const DIR: &str = "tests/fixtures/goal2014";

/// Runs `goal ARGS...` in the fixture directory: (exit code, stdout, stderr).
fn goal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(DIR))
        .output()
        .expect("run goal");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `goal check FILE`: (exit code, rendered diagnostics).
fn check(file: &str) -> (i32, String) {
    let (code, out, _) = goal(&["check", file]);
    (code, out)
}

/// The lines a single agent or system prints when run (a few ticks, every agent stepped).
fn run(file: &str) -> (i32, Vec<String>) {
    let (code, out, err) = goal(&["run", "--no-skip", "--max-ticks", "6", file]);
    assert!(
        !err.contains("error["),
        "{file} does not load at run time:\n{err}"
    );
    (code, out.lines().map(str::to_string).collect())
}

#[test]
fn a_space_before_the_bracket_is_read_as_goal_did_with_a_warning() {
    let (code, diags) = check("spaced_functor.goal");
    assert_eq!(code, 0, "{diags}");
    insta::assert_snapshot!("spaced_functor", diags);
    let (_, printed) = run("spaced_functor.goal");
    assert_eq!(printed, ["resting", "hall", "kitchen", "wants(kitchen)"]);
}

#[test]
fn standard_prolog_readers_still_refuse_a_space_before_the_bracket() {
    let mut r = goal::syntax::prolog::Reader::new("q");
    assert!(r.term("room (a)", 0).is_err());
    assert!(r.term("p(a))", 0).is_err());
    // Operators keep their meaning: `- (1)` is minus applied to 1, `X is (1+2)` is arithmetic.
    let mut g = goal::syntax::prolog::Reader::goal("q");
    for text in ["X is (1 + 2)", "- (1)", "a :- \\+ (b, c)"] {
        let standard = r.term(text, 0).expect("standard reading").term;
        assert_eq!(
            g.term(text, 0).expect("GOAL reading").term,
            standard,
            "{text}"
        );
    }
    assert!(g.warnings.is_empty());
}

#[test]
fn text_after_a_complete_kr_term_is_ignored_with_a_warning() {
    let (code, diags) = check("trailing_text.goal");
    assert_eq!(code, 0, "{diags}");
    insta::assert_snapshot!("trailing_text", diags);
    let (_, printed) = run("trailing_text.goal");
    assert_eq!(printed, ["arrived(dock)"]);
}

#[test]
fn one_macro_name_in_two_modules_is_scoped_per_module() {
    let (code, diags) = check("macro_scope.goal");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (_, printed) = run("macro_scope.goal");
    assert_eq!(printed, ["main_sees_light", "check_sees_door"]);
}

#[test]
fn an_import_without_extension_finds_the_prolog_file() {
    let (code, diags) = check("import_extension.goal");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (_, printed) = run("import_extension.goal");
    assert_eq!(printed, ["hallo"]);
}

#[test]
fn imports_at_the_end_of_a_file_load_at_run_time_as_check_reads_them() {
    let (code, diags) = check("import_late.goal");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (_, printed) = run("import_late.goal");
    assert_eq!(printed, ["hello(world,1)"]);
}

#[test]
fn a_module_head_with_a_repeated_parameter_is_a_warning() {
    let (code, diags) = check("module_two_arguments.goal");
    assert_eq!(code, 0, "{diags}");
    insta::assert_snapshot!("module_two_arguments", diags);
    let (_, printed) = run("module_two_arguments.goal");
    assert_eq!(printed, ["same(a)"]);
}

#[test]
fn module_parameters_and_nested_rules_scope_variables() {
    let (code, diags) = check("scope.goal");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (_, printed) = run("scope.goal");
    assert_eq!(printed, ["first(a)", "other(b,b)"]);
}

#[test]
fn conditions_query_mental_models_kept_from_messages() {
    let (code, diags) = check("models.mas2g");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (_, printed) = run("models.mas2g");
    // `all` includes bob himself, who does not believe at(room1): that rule never fires.
    assert_eq!(
        printed,
        [
            "alice_at(room1)",
            "alice_wants(box)",
            "someone_at_room1",
            "goal_of(alice)"
        ]
    );
}

#[test]
fn a_test_file_without_tests_passes() {
    let (code, out, err) = goal(&["test", "correct_minimal.test2g"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("no tests"), "{err}");
}

#[test]
fn a_failing_temporal_condition_fails_the_test() {
    let (code, out, _) = goal(&["test", "failing_ltl.test2g"]);
    assert_eq!(code, 1, "{out}");
    insta::assert_snapshot!("failing_ltl", out);
}

#[test]
fn incorrect_programs_are_refused_by_check_and_run_alike() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(DIR)
        .join("incorrect");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .expect("fixtures")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".goal"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 9);
    for f in files {
        let path = format!("incorrect/{f}");
        let (code, diags) = check(&path);
        assert_eq!(code, 1, "{path} passes goal check");
        let (run_code, _, err) = goal(&["run", &path]);
        assert_ne!(run_code, 0, "{path} runs");
        // Both commands name the same errors.
        let codes = |text: &str| -> Vec<String> {
            let mut v: Vec<String> = text
                .lines()
                .filter_map(|l| l.strip_prefix("error["))
                .map(|l| l[..5].to_string())
                .collect();
            v.sort();
            v
        };
        assert_eq!(codes(&diags), codes(&err), "{path}");
        insta::assert_snapshot!(format!("incorrect_{}", f.trim_end_matches(".goal")), diags);
    }
}

#[test]
fn test_files_and_prolog_files_read_kr_text_as_agent_files_do() {
    let (code, diags) = check("spaced_assert.test2g");
    assert_eq!(code, 0, "{diags}");
    insta::assert_snapshot!("spaced_assert", diags);
    let (code, out, _) = goal(&["test", "spaced_assert.test2g"]);
    assert_eq!(code, 0, "{out}");
    let (code, diags) = check("spaced.pl");
    assert_eq!(code, 0, "{diags}");
    assert!(diags.contains("warning[W0010]"), "{diags}");
}

#[test]
fn blocks_world_examples_and_ping_pong_pass_their_tests() {
    let (code, out, err) = goal(&[
        "test",
        "blocksworld/tower.test2g",
        "blocksworld/flatten.test2g",
        "../../../agents/blocksworld/stacker.test2g",
        "../../../agents/pingpong/pingpong.test2g",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    for name in ["buildsTower", "flattens", "rally"] {
        assert!(out.contains(name), "{out}");
    }
    assert!(!out.contains("FAILED"), "{out}");
}

#[test]
fn a_test_may_call_a_module_the_agent_imports() {
    let (code, diags) = check("import_late.test2g");
    assert_eq!((code, diags.as_str()), (0, ""));
    let (code, out, err) = goal(&["test", "import_late.test2g"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn test_conditions_may_ask_about_other_agents_models() {
    for file in ["models.test2g", "models_quiet.test2g"] {
        let (code, diags) = check(file);
        assert_eq!((code, diags.as_str()), (0, ""), "{file}");
        let (code, out, err) = goal(&["test", file]);
        assert_eq!(code, 0, "{file}: {out}{err}");
    }
}
