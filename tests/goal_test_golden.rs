//! Golden traces: scenario traces snapshotted with insta, and the user workflow round trip
//! (record with `goal run --trace`, check with `goal test --golden`, change the agent, check
//! again and read the difference).

use goal::mas::run::RunOptions;
use goal::mas::system;
use goal::testing::golden::{check, compare, record, GoldenOptions};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh scratch directory for this test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-golden-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

fn opts() -> RunOptions {
    RunOptions {
        workers: 2,
        ..RunOptions::default()
    }
}

#[test]
fn ping_pong_scenario_trace() {
    std::env::set_current_dir(root()).expect("manifest dir");
    let sys = system::load_mas(Path::new("agents/pingpong/pingpong.mas2g")).expect("loads");
    let trace = record(&sys, &opts()).expect("runs");
    assert_eq!(record(&sys, &opts()).expect("runs"), trace, "deterministic");
    insta::assert_snapshot!("pingpong_trace", trace);
}

#[test]
fn counter_trace_does_not_depend_on_the_worker_count() {
    std::env::set_current_dir(root()).expect("manifest dir");
    let sys = system::load_mas(Path::new("agents/counter/counter.mas2g")).expect("loads");
    let one = record(
        &sys,
        &RunOptions {
            workers: 1,
            ..opts()
        },
    )
    .expect("runs");
    let two = record(
        &sys,
        &RunOptions {
            workers: 2,
            ..opts()
        },
    )
    .expect("runs");
    assert_eq!(compare(&one, &two), None);
    let end = one.lines().last().unwrap_or_default();
    insta::assert_snapshot!("counter_trace_end", end);
}

const COUNTER_MAS: &str =
    "agentfiles {\n\t\"counter.goal\".\n}\nlaunchpolicy {\n\tlaunch counter.\n}\n";

#[test]
fn golden_round_trip_through_the_library() {
    let dir = scratch("lib");
    let agent = std::fs::read_to_string(root().join("agents/counter/counter.goal")).expect("agent");
    std::fs::write(dir.join("counter.goal"), &agent).expect("write");
    std::fs::write(dir.join("counter.mas2g"), COUNTER_MAS).expect("write");
    let mas = dir.join("counter.mas2g");
    let sys = system::load_mas(&mas).expect("loads");
    let golden = dir.join("golden.jsonl");
    std::fs::write(&golden, record(&sys, &opts()).expect("runs")).expect("write");
    let o = GoldenOptions {
        system: Some(mas.clone()),
        ..GoldenOptions::default()
    };
    assert_eq!(check(&golden, &o), Ok(None), "an unchanged agent passes");
    // Count in steps of two from 40 on: the trace changes at the 41st increment.
    let changed = agent.replace("M is N + 1", "M is N + 1 + N // 40");
    assert_ne!(changed, agent, "the agent text has the increment");
    std::fs::write(dir.join("counter.goal"), changed).expect("write");
    let diff = check(&golden, &o)
        .expect("runs")
        .expect("a changed agent differs");
    assert_eq!(diff.agent.as_deref(), Some("counter"));
    assert!(diff.round.is_some());
    insta::assert_snapshot!("golden_difference", diff.to_text());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn golden_round_trip_through_the_cli() {
    let dir = scratch("cli");
    let agent = std::fs::read_to_string(root().join("agents/counter/counter.goal")).expect("agent");
    std::fs::write(dir.join("counter.goal"), &agent).expect("write");
    std::fs::write(dir.join("counter.mas2g"), COUNTER_MAS).expect("write");
    let goal = env!("CARGO_BIN_EXE_goal");
    let run = Command::new(goal)
        .current_dir(&dir)
        .args(["run", "counter.mas2g", "--trace", "golden.jsonl"])
        .output()
        .expect("goal run");
    assert!(run.status.success());
    let check = |dir: &Path| {
        Command::new(goal)
            .current_dir(dir)
            .args(["test", "--golden", "golden.jsonl"])
            .output()
            .expect("goal test")
    };
    let ok = check(&dir);
    let text = String::from_utf8_lossy(&ok.stdout).to_string();
    assert!(ok.status.success(), "{text}");
    assert_eq!(text, "golden golden.jsonl ... passed\n");
    std::fs::write(
        dir.join("counter.goal"),
        agent.replace("print(M)", "print(count(M))"),
    )
    .expect("write");
    let bad = check(&dir);
    let text = String::from_utf8_lossy(&bad.stdout).to_string();
    assert_eq!(bad.status.code(), Some(1));
    insta::assert_snapshot!("golden_cli_difference", text);
    let _ = std::fs::remove_dir_all(&dir);
}
