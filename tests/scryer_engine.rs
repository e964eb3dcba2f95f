//! The scryer KR engine (`--kr scryer`, `language = scryer`): the shipped agents give the same
//! traces and test results on both engines, an agent that needs scryer (DCG, catch/throw) runs
//! on it and is refused on the native engine with a message naming the engine it needs, and
//! agent code cannot reach files through it.
#![cfg(feature = "scryer")]

use goal::kr::KrKind;
use goal::mas::run::RunOptions;
use goal::mas::system;
use goal::testing::golden::{compare, record};
use goal::testing::runner::{run_file, TestOptions};
use goal::testing::Outcome;
use std::path::Path;
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn opts(kr: KrKind) -> RunOptions {
    RunOptions {
        workers: 2,
        max_ticks: 2_000,
        kr,
        ..RunOptions::default()
    }
}

#[test]
fn shipped_agents_give_the_same_trace_on_both_engines() {
    std::env::set_current_dir(root()).expect("manifest dir");
    for mas in [
        "agents/counter/counter.mas2g",
        "agents/pingpong/pingpong.mas2g",
        "agents/blocksworld/stacker.mas2g",
    ] {
        let sys = system::load_mas(Path::new(mas)).expect("loads");
        let native = record(&sys, &opts(KrKind::Native)).expect("runs on native");
        let scryer = record(&sys, &opts(KrKind::Scryer)).expect("runs on scryer");
        assert_eq!(compare(&native, &scryer), None, "{mas}");
    }
}

#[test]
fn shipped_test_files_pass_on_scryer() {
    for f in [
        "agents/counter/counter.test2g",
        "agents/pingpong/pingpong.test2g",
        "agents/blocksworld/stacker.test2g",
    ] {
        let o = TestOptions {
            kr: KrKind::Scryer,
            ..TestOptions::default()
        };
        for r in run_file(&root().join(f), &o) {
            assert_eq!(r.outcome, Outcome::Passed, "{}", r.to_text());
        }
    }
}

fn goal(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("goal runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn an_agent_with_a_dcg_and_catch_runs_on_scryer() {
    let (code, out, err) = goal(&["run", "tests/fixtures/scryer/parse.mas2g"]);
    assert_eq!(code, Some(0), "{out}\n{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines,
        ["go('RoomA1')", "2", "zero_divisor", "small", "big"],
        "{err}"
    );
    // The same program with the run's engine: refused, naming the engine it needs.
    let (code, _, err) = goal(&["run", "tests/fixtures/scryer/parse_native.mas2g"]);
    assert_ne!(code, Some(0));
    assert!(err.contains("only the scryer engine"), "{err}");
    assert!(err.contains("--kr scryer"), "{err}");
    let (code, out, err) = goal(&[
        "run",
        "--kr",
        "scryer",
        "tests/fixtures/scryer/parse_native.mas2g",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("zero_divisor"), "{out}");
    // `goal check` warns which engine it needs.
    let (_, out, err) = goal(&["check", "tests/fixtures/scryer/parse.goal"]);
    assert!(
        format!("{out}{err}").contains("runs only on the scryer KR engine"),
        "{out}{err}"
    );
}

#[test]
fn goal_prolog_answers_on_scryer() {
    let dir = std::env::temp_dir().join(format!("goal-scryer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let kb = dir.join("kb.pl");
    std::fs::write(
        &kb,
        "digits([D|T]) --> digit(D), digits(T).\ndigits([D]) --> digit(D).\n\
         digit(D) --> [D], { member(D, [0,1,2,3,4,5,6,7,8,9]) }.\n",
    )
    .expect("write");
    let kb = kb.to_string_lossy().into_owned();
    let (code, out, err) = goal(&[
        "prolog",
        "--kr",
        "scryer",
        &kb,
        "-q",
        "phrase(digits(Ds), [1,2,3])",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(out, "Ds = [1,2,3]\n");
    // Files stay out of reach, even through a goal built at run time.
    let target = dir.join("written").to_string_lossy().into_owned();
    let q = format!("atom_chars(A, [o, p, e, n]), G =.. [A, '{target}', write, _], call(G)");
    let (_, out, _) = goal(&["prolog", "--kr", "scryer", &kb, "-q", &q]);
    assert!(out.contains("permission_error"), "{out}");
    assert!(!Path::new(&target).exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn long_answers_with_variables_are_named_without_crashing() {
    // 100,000 fresh variables in a list: renaming them used to recurse down the list and
    // overflow the stack.
    let (code, out, err) = goal(&[
        "prolog",
        "--kr",
        "scryer",
        "-q",
        "findall(X, between(1, 100000, _), L), length(L, N)",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        out.ends_with("N = 100000\n"),
        "{}",
        &out[out.len().saturating_sub(300)..]
    );
}

#[test]
fn the_default_bw4t_game_starts_the_same_on_scryer() {
    // The first 150 ticks (the whole game takes minutes in a debug build; README has it).
    std::env::set_current_dir(root()).expect("manifest dir");
    let sys = system::load_mas(Path::new("agents/bw4t/bw4t.mas2g")).expect("loads");
    let short = |kr| RunOptions {
        max_ticks: 150,
        ..opts(kr)
    };
    let native = record(&sys, &short(KrKind::Native)).expect("runs on native");
    let scryer = record(&sys, &short(KrKind::Scryer)).expect("runs on scryer");
    assert_eq!(compare(&native, &scryer), None);
}
