//! `goal run` on the built binary: the default team from an empty directory, stdout carrying
//! only agent output, identical trace files for the same seed, the stats file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh empty directory under the system temp dir.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-run-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn goal(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("run")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn no_arguments_runs_the_built_in_team_from_an_empty_directory() {
    let dir = temp_dir("default");
    let out = goal(&dir, &["--max-ticks", "40", "--stats", "s.json"]);
    let err = text(&out.stderr);
    // The tick limit ends the run before the sequence is delivered: exit code 3.
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert_eq!(text(&out.stdout), "", "the default robots print nothing");
    assert!(err.contains("result"), "{err}");
    assert!(err.contains("Bot1") && err.contains("Bot3"), "{err}");
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("s.json")).expect("stats written"))
            .expect("stats are JSON");
    assert_eq!(stats["ticks"], 40);
    assert_eq!(stats["completed"], false);
    assert_eq!(stats["seed"], 0);
    assert_eq!(stats["map"], "banana");
    assert!(stats["deliveries"]["right"].is_u64());
    assert!(stats["deliveries"]["wrong"].is_u64());
    assert!(stats["messages"].is_u64());
    for bot in ["Bot1", "Bot2", "Bot3"] {
        let a = &stats["agents"][bot];
        assert!(a["cycles"].as_u64().is_some_and(|c| c > 0), "{bot}: {a}");
        assert!(
            a["actions"].is_u64() && a["idle_ticks"].is_u64(),
            "{bot}: {a}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_single_agent_prints_only_its_own_output_on_stdout() {
    let counter = root().join("agents/counter/counter.goal");
    let out = goal(&root(), &[counter.to_str().expect("utf-8 path")]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let want: String = (1..=100)
        .map(|i| format!("{i}\n"))
        .chain(["counted to 100\n".to_string()])
        .collect();
    assert_eq!(text(&out.stdout), want);
    assert!(text(&out.stderr).contains("all agents stopped"));
}

#[test]
fn same_seed_same_trace_file_and_workers_do_not_matter() {
    let dir = temp_dir("trace");
    let mas = root().join("tests/fixtures/mas/robots.mas2g");
    let mas = mas.to_str().expect("utf-8 path");
    let mut traces = Vec::new();
    for (name, workers) in [("a", "1"), ("b", "1"), ("c", "2")] {
        let file = format!("{name}.jsonl");
        let out = goal(
            &dir,
            &[
                mas,
                "--seed",
                "5",
                "--max-ticks",
                "80",
                "--workers",
                workers,
                "--trace",
                &file,
            ],
        );
        assert_eq!(out.status.code(), Some(3), "{}", text(&out.stderr));
        traces.push(std::fs::read(dir.join(&file)).expect("trace written"));
    }
    assert!(traces[0].len() > 1000);
    assert_eq!(traces[0], traces[1], "same seed: byte-identical trace");
    assert_eq!(traces[0], traces[2], "--workers 1 and 2: identical trace");
    let first = text(&traces[0]);
    let header: serde_json::Value =
        serde_json::from_str(first.lines().next().expect("a header")).expect("JSON");
    assert_eq!(header["seed"], 5);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_failing_agent_is_in_the_summary() {
    let mas = root().join("tests/fixtures/mas/failing.mas2g");
    let out = goal(&root(), &[mas.to_str().expect("utf-8 path")]);
    assert_eq!(
        out.status.code(),
        Some(4),
        "an agent stopped on a runtime error"
    );
    let err = text(&out.stderr);
    assert!(
        err.lines()
            .any(|l| l.starts_with("crasher") && l.contains("error:") && l.contains("1/0")),
        "{err}"
    );
    assert!(err
        .lines()
        .any(|l| l.starts_with("worker1") && l.ends_with("stopped")));
    // Both workers print 1..20; crasher prints nothing.
    assert_eq!(text(&out.stdout).lines().count(), 40);
}

#[test]
fn a_bad_file_is_a_diagnostic_not_a_crash() {
    let dir = temp_dir("bad");
    std::fs::write(dir.join("bad.goal"), "main module { program { if then. } }").expect("write");
    let out = goal(&dir, &["bad.goal"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("error"));
    let out = goal(&dir, &["missing.mas2g"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("missing.mas2g"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn map_and_robots_options_replace_the_defaults() {
    let dir = temp_dir("map");
    let out = goal(
        &dir,
        &[
            "--map",
            "tiny",
            "--robots",
            "2",
            "--max-ticks",
            "10",
            "--stats",
            "s.json",
        ],
    );
    assert_eq!(out.status.code(), Some(3), "{}", text(&out.stderr));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("s.json")).expect("stats"))
            .expect("JSON");
    assert_eq!(stats["map"], "tiny");
    let agents: Vec<&String> = stats["agents"]
        .as_object()
        .map(|o| o.keys().collect())
        .unwrap_or_default();
    assert_eq!(agents, ["Bot1", "Bot2"]);
    let out = goal(&dir, &["--map", "no-such-map", "--max-ticks", "10"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("no-such-map"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A query that never ends by itself (no budget stops it soon) in one agent of two.
const ENDLESS: &str =
    "main module { program { if bel(between(1, inf, X), X < 0) then print(X). } }";

#[test]
fn the_cycle_time_quota_interrupts_a_long_query_and_the_other_agent_goes_on() {
    let dir = temp_dir("cycle-quota");
    std::fs::write(dir.join("slow.goal"), ENDLESS).unwrap();
    std::fs::write(
        dir.join("busy.goal"),
        "init module { beliefs { n(0). } }
         main module { program { if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)) + print(M). } }",
    )
    .unwrap();
    std::fs::write(
        dir.join("two.mas2g"),
        "agentfiles { \"slow.goal\". \"busy.goal\". } launchpolicy { launch slow:slow. launch busy:busy. }",
    )
    .unwrap();
    let out = goal(
        &dir,
        &["two.mas2g", "--cycle-time", "0.2", "--workers", "1"],
    );
    let err = text(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(4),
        "an agent stopped on an error: {err}"
    );
    assert!(err.contains("query interrupted"), "{err}");
    assert!(err.contains("slow.goal:1"), "located: {err}");
    assert_eq!(
        text(&out.stdout),
        "1\n2\n3\n4\n5\n",
        "the other agent finished: {err}"
    );
}

#[test]
fn the_run_time_limit_interrupts_a_query_that_is_running() {
    let dir = temp_dir("time-limit-query");
    std::fs::write(dir.join("slow.goal"), ENDLESS).unwrap();
    // No cycle quota: only the run's time limit can stop the query.
    let out = goal(
        &dir,
        &["slow.goal", "--time-limit", "0.5", "--cycle-time", "1000"],
    );
    let err = text(&out.stderr);
    assert_ne!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("query interrupted"), "{err}");
}
