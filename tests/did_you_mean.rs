//! "Did you mean": every lookup of a name suggests the near known name (issue: teaching). One
//! test per kind of lookup: actions, predicates, modules, macros, agents in `.mas2g` launch
//! rules and in `.test2g` blocks, maps, percepts and command-line values.

use goal::syntax::check::check_path_with_agents;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Writes a project into a fresh directory named after the test.
fn project(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-dym-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (f, text) in files {
        std::fs::write(dir.join(f), text).expect("write");
    }
    dir
}

/// Every `code: message (hint)` that `goal check` reports for `file`.
fn diagnostics(dir: &Path, file: &str) -> Vec<String> {
    check_path_with_agents(&dir.join(file))
        .iter()
        .flat_map(|r| r.diagnostics.iter())
        .map(|d| {
            format!(
                "{}: {} ({})",
                d.code,
                d.message,
                d.hint.clone().unwrap_or_default()
            )
        })
        .collect()
}

fn assert_hint(diags: &[String], code: &str, hint: &str) {
    assert!(
        diags
            .iter()
            .any(|d| d.starts_with(code) && d.contains(hint)),
        "no {code} with `{hint}` in {diags:#?}"
    );
}

const MAIN_2014: &str = "main module {
    knowledge { color(red). }
    program {
        #define ready bel(color(red)).
        if redy then goto(r1).
        if bel(colour(X)) then print(X).
    }
    actionspec { goTo(P) { pre { true } post { true } } }
}";

#[test]
fn actions() {
    let dir = project("actions", &[("a.goal", MAIN_2014)]);
    assert_hint(
        &diagnostics(&dir, "a.goal"),
        "E0104",
        "did you mean `goTo/1`?",
    );
}

#[test]
fn predicates() {
    let dir = project("predicates", &[("a.goal", MAIN_2014)]);
    assert_hint(
        &diagnostics(&dir, "a.goal"),
        "E0121",
        "did you mean `color/1`?",
    );
}

#[test]
fn macros() {
    let dir = project("macros", &[("a.goal", MAIN_2014)]);
    assert_hint(
        &diagnostics(&dir, "a.goal"),
        "E0118",
        "did you mean the macro `ready/0`?",
    );
}

const MODULAR_MAS: &str = "use \"bw4t-client-3.8.5.jar\" as environment with agentcount = \"1\".
define robot as agent { use robotmain as main module. }
launchpolicy { when * launch robto. }";

#[test]
fn modules() {
    let dir = project(
        "modules",
        &[
            ("team.mas2g", MODULAR_MAS),
            (
                "robotMain.mod2g",
                "module robotMain { if true then exit-module. }",
            ),
        ],
    );
    assert_hint(
        &diagnostics(&dir, "team.mas2g"),
        "E0607",
        "did you mean `robotMain`?",
    );
}

#[test]
fn agents_in_launch_rules() {
    let dir = project("launch", &[("team.mas2g", MODULAR_MAS)]);
    assert_hint(
        &diagnostics(&dir, "team.mas2g"),
        "E0206",
        "did you mean `robot`?",
    );
    let classic = project(
        "launch2014",
        &[
            (
                "team.mas2g",
                "agentfiles { \"robot.goal\". }\nlaunchpolicy { launch r : robto. }",
            ),
            (
                "robot.goal",
                "main module { program { if true then exit-module. } }",
            ),
        ],
    );
    assert_hint(
        &diagnostics(&classic, "team.mas2g"),
        "E0206",
        "did you mean `robot`?",
    );
}

#[test]
fn agents_in_test_files() {
    let dir = project(
        "test2g",
        &[
            (
                "team.mas2g",
                "agentfiles { \"robot.goal\". }\nlaunchpolicy { launch robot : robot. }",
            ),
            (
                "robot.goal",
                "main module { program { if true then exit-module. } }",
            ),
            (
                "team.test2g",
                "masTest { mas = \"team.mas2g\". robto { t { do main. } } }",
            ),
        ],
    );
    assert_hint(
        &diagnostics(&dir, "team.test2g"),
        "E0306",
        "did you mean `robot`?",
    );
}

#[test]
fn maps() {
    let err = goal::bw4t::map::load("banan").expect_err("no such map");
    let hint = err[0].hint.clone().unwrap_or_default();
    assert!(
        hint.contains("did you mean the built-in map `banana`?"),
        "{hint}"
    );
}

#[test]
fn percepts() {
    let dir = project(
        "percepts",
        &[
            (
                "team.mas2g",
                "environment { env = \"bw4t-client-3.8.5.jar\". }\nagentfiles { \"robot.goal\". }\nlaunchpolicy { when entity@env do launch robot : robot. }",
            ),
            (
                "robot.goal",
                "main module { program { if bel(percept(atblock(B))) then print(B). } }",
            ),
        ],
    );
    let diags: Vec<String> = goal::mas::envcheck::check_path(&dir.join("team.mas2g"))
        .iter()
        .flat_map(|r| r.diagnostics.iter())
        .map(|d| format!("{}: {}", d.code, d.message))
        .collect();
    assert!(
        diags.iter().any(|d| d.contains("did you mean atBlock/1?")),
        "{diags:#?}"
    );
}

#[test]
fn command_line_values() {
    let goal = env!("CARGO_BIN_EXE_goal");
    let out = Command::new(goal)
        .args(["run", "--map", "banan", "--max-ticks", "1"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("did you mean the built-in map `banana`?"),
        "{err}"
    );
    let out = Command::new(goal)
        .args(["test", "--format", "jsn", "x.test2g"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("a similar value exists: 'json'"), "{err}");
}
