//! `goal test` on the shipped agents: every `.test2g` file under `agents/` passes, through the
//! library and through the built binary (exit code, text and JSON output).

use goal::testing::runner::{run_file, TestOptions};
use goal::testing::Outcome;
use std::path::{Path, PathBuf};
use std::process::Command;

fn shipped_tests() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("agents");
    let mut found = Vec::new();
    let mut stack = vec![root];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir)
            .expect("agents/ is readable")
            .flatten()
        {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "test2g") {
                found.push(p);
            }
        }
    }
    found.sort();
    found
}

#[test]
fn every_shipped_test_file_passes() {
    let files = shipped_tests();
    let names: Vec<String> = files
        .iter()
        .filter_map(|f| f.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    // Sorted by full path: blocksworld, bw4t (marbel/team, modular/team, robot, team),
    // counter, pingpong.
    assert_eq!(
        names,
        [
            "stacker.test2g",
            "team.test2g",
            "team.test2g",
            "robot.test2g",
            "team.test2g",
            "counter.test2g",
            "pingpong.test2g"
        ]
    );
    let mut failures = Vec::new();
    let mut count = 0;
    for f in &files {
        for r in run_file(f, &TestOptions::default()) {
            count += 1;
            if r.outcome != Outcome::Passed {
                failures.push(r.to_text());
            }
        }
    }
    assert!(failures.is_empty(), "failing tests:\n{}", failures.join(""));
    // stacker 1, MARBEL and modular teams 3 each, robot 1, team 3 (Bot1, Bot2, Bot3),
    // counter 1, ping-pong 1.
    assert_eq!(count, 13);
}

#[test]
fn the_binary_reports_and_exits_zero_when_all_pass() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .current_dir(dir)
        .args(["test", "agents/counter", "agents/pingpong/pingpong.test2g"])
        .output()
        .expect("goal runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(text.contains("counter/countsTo100 ... passed"), "{text}");
    assert!(text.contains("ping/rally ... passed"), "{text}");
    assert!(text.ends_with("test result: ok. 2 passed; 0 failed; 0 timed out; 0 errors\n"));
}

#[test]
fn json_output_has_one_object_per_test_and_failures_exit_one() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .current_dir(dir)
        .args([
            "test",
            "--format",
            "json",
            "--max-ticks",
            "500",
            "agents/counter/counter.test2g",
            "tests/fixtures/test2g/failing/never.test2g",
        ])
        .output()
        .expect("goal runs");
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("each line is JSON"))
        .collect();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["status"], "passed");
    assert_eq!(rows[0]["test"], "countsTo100");
    assert_eq!(rows[1]["status"], "failed");
    assert_eq!(rows[1]["kind"], "evaluate");
    assert_eq!(rows[1]["bindings"], "N=3");
}
