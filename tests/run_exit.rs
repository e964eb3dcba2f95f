//! What a user of `goal` sees when something goes wrong: the exit codes of docs/exit-codes.md,
//! messages on stderr, refused environment actions, quotas, signals, bad flag values, closed
//! pipes and agent output that tries to mess with the terminal.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn fixture(name: &str) -> String {
    root()
        .join("tests/fixtures/runtime")
        .join(name)
        .display()
        .to_string()
}

fn goal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn temp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-exit-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

#[test]
fn help_lists_the_exit_codes() {
    let o = goal(&["--help"]);
    let out = text(&o.stdout);
    for code in ["0 ", "1 ", "2 ", "3 ", "4 ", "5 ", "130", "141", "143"] {
        assert!(out.contains(&format!("  {code}")), "{code} missing:\n{out}");
    }
}

#[test]
fn a_refused_environment_action_stops_the_agent_and_says_why() {
    let o = goal(&["run", &fixture("misspelt.mas2g"), "--max-ticks", "300"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    let line = err
        .lines()
        .find(|l| l.starts_with("warning: agent Bot1 stopped"))
        .unwrap_or_else(|| panic!("no stop message:\n{err}"));
    assert!(line.contains("misspelt.goal:4:"), "located: {line}");
    assert!(
        line.contains("environment action goto('RoomA1') failed: unknown action goto/1"),
        "{line}"
    );
    // Once: the agent stops at the first refusal, as GOAL does.
    assert_eq!(
        err.matches("goto('RoomA1') failed").count(),
        2,
        "warning + table: {err}"
    );
    assert!(!err.contains("tick limit"), "{err}");
}

#[test]
fn a_run_that_hits_the_tick_limit_exits_3() {
    let o = goal(&["run", &fixture("wander.mas2g"), "--max-ticks", "5"]);
    assert_eq!(o.status.code(), Some(3), "{}", text(&o.stderr));
}

#[test]
fn a_system_without_environment_stops_at_the_cycle_limit_and_says_so() {
    let o = goal(&["run", &fixture("flood.mas2g"), "--max-cycles", "3"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("cycle limit reached"), "{err}");
    assert!(!err.contains("tick limit"), "{err}");
}

#[test]
fn unwritable_stats_file_exits_1() {
    let o = goal(&[
        "run",
        &fixture("clock.goal"),
        "--stats",
        "/nonexistent-dir/s.json",
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write stats file"), "{err}");
}

#[test]
fn bad_flag_values_are_refused_with_the_flag_and_the_range() {
    for (flag, value) in [
        ("--realtime", "1e-20"),
        ("--realtime", "0"),
        ("--realtime", "nan"),
        ("--time-limit", "1e300"),
        ("--time-limit", "0"),
        ("--time-limit", "nan"),
        ("--workers", "0"),
        ("--max-ticks", "0"),
        ("--max-memory", "0"),
        ("--cycle-time", "0"),
    ] {
        let o = goal(&["run", &fixture("clock.goal"), flag, value]);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {err}");
        assert!(err.contains(flag), "{flag} {value}: {err}");
        assert!(err.contains("must be"), "{flag} {value}: {err}");
        assert!(!err.contains("panicked"), "{flag} {value}: {err}");
    }
}

#[test]
fn agent_output_cannot_drive_the_terminal_or_fake_lines() {
    let o = goal(&["run", &fixture("escapes.goal")]);
    let out = text(&o.stdout);
    assert_eq!(out, "\\e[2J\\x00\\nBot2: hi\n");
    assert!(!o.stdout.contains(&0x1b) && !o.stdout.contains(&0));
    let o = goal(&["run", &fixture("escapes.goal"), "--prefix"]);
    assert_eq!(text(&o.stdout), "escapes: \\e[2J\\x00\\nBot2: hi\n");
}

#[test]
fn get_time_answers_simulated_time_in_lock_step() {
    let a = goal(&["run", &fixture("clock.goal")]);
    assert_eq!(a.status.code(), Some(0), "{}", text(&a.stderr));
    // One tick is 0.01 simulated seconds; the same on every run.
    assert_eq!(text(&a.stdout), "0.0\n0.01\n0.02\n");
    assert_eq!(goal(&["run", &fixture("clock.goal")]).stdout, a.stdout);
}

#[test]
fn the_belief_quota_stops_only_the_hoarder() {
    let o = goal(&["run", &fixture("hoarder.goal"), "--max-beliefs", "100"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    assert!(
        err.contains("hoarder.goal:5: the belief base holds more than 100 facts"),
        "{err}"
    );
}

#[test]
fn a_cycle_over_its_time_quota_is_cut() {
    let o = goal(&["run", &fixture("hoarder.goal"), "--cycle-time", "0.001"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    // Cut inside the query (the engine checks the deadline) or between steps.
    assert!(
        err.contains("hoarder.goal:5:") && err.contains("time quota"),
        "{err}"
    );
}

#[test]
fn a_full_mailbox_drops_messages_and_reports_it_while_the_run_goes_on() {
    let dir = temp("mailbox");
    let stats = dir.join("s.json");
    let o = goal(&[
        "run",
        &fixture("flood.mas2g"),
        "--max-mailbox",
        "10",
        "--max-cycles",
        "5",
        "--stats",
        stats.to_str().expect("utf-8"),
    ]);
    let err = text(&o.stderr);
    assert_eq!(err.matches("listener: mailbox full").count(), 1, "{err}");
    assert!(err.contains("listener: 200 messages dropped"), "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).expect("stats")).expect("JSON");
    assert_eq!(s["agents"]["listener"]["messages_dropped"], 200);
    assert_eq!(s["agents"]["listener"]["cycles"], 5, "the listener goes on");
    assert_eq!(s["end"], "cycle_limit");
}

#[test]
fn the_memory_cap_ends_the_run_with_exit_5() {
    let dir = temp("memory");
    let stats = dir.join("s.json");
    let o = goal(&[
        "run",
        &fixture("wander.mas2g"),
        "--max-memory",
        "1",
        "--stats",
        stats.to_str().expect("utf-8"),
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(5), "{err}");
    assert!(
        err.contains("more than its cap of 1 MiB (--max-memory)"),
        "{err}"
    );
    let s = std::fs::read_to_string(&stats).expect("stats");
    assert!(s.contains("\"end\": \"memory_limit\""), "{s}");
}

#[test]
fn the_time_limit_stops_a_run_that_would_go_on() {
    let o = goal(&[
        "run",
        &fixture("wander.mas2g"),
        "--max-ticks",
        "100000000",
        "--time-limit",
        "0.5",
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("time limit reached"), "{err}");
}

/// Starts a long run, waits until its trace has begun, sends `signal`, and returns the exit
/// code, the trace and the stats.
fn interrupt(signal: &str, tag: &str) -> (Option<i32>, String, String) {
    let dir = temp(tag);
    let (trace, stats) = (dir.join("t.jsonl"), dir.join("s.json"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_goal"))
        .args([
            "run",
            &fixture("wander.mas2g"),
            "--max-ticks",
            "100000000",
            "--trace",
            trace.to_str().expect("utf-8"),
            "--stats",
            stats.to_str().expect("utf-8"),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("starts");
    let waited = Instant::now();
    while std::fs::metadata(&trace).map_or(0, |m| m.len()) < 10_000 {
        assert!(
            waited.elapsed() < Duration::from_secs(60),
            "the run never traced"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let sent = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
    let status = child.wait().expect("exits");
    let t = std::fs::read_to_string(&trace).expect("trace");
    let s = std::fs::read_to_string(&stats).expect("stats written");
    (status.code(), t, s)
}

fn check_interrupted(code: Option<i32>, expected: i32, trace: &str, stats: &str) {
    assert_eq!(code, Some(expected));
    assert!(trace.ends_with('\n'), "no cut line");
    for line in trace.lines() {
        let _: serde_json::Value = serde_json::from_str(line).expect("every line is JSON");
    }
    let last: serde_json::Value =
        serde_json::from_str(trace.lines().last().expect("lines")).expect("JSON");
    assert_eq!(last["type"], "end");
    assert_eq!(last["end"], "interrupted");
    let s: serde_json::Value = serde_json::from_str(stats).expect("JSON");
    assert_eq!(s["end"], "interrupted");
}

#[test]
fn ctrl_c_finishes_the_round_and_writes_the_end_record_and_stats() {
    let (code, t, s) = interrupt("-INT", "sigint");
    check_interrupted(code, 130, &t, &s);
}

#[test]
fn sigterm_stops_cleanly_too() {
    let (code, t, s) = interrupt("-TERM", "sigterm");
    check_interrupted(code, 143, &t, &s);
}

#[test]
fn goal_test_into_a_closed_pipe_ends_quietly() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(["test", "agents"])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    let mut out = child.stdout.take().expect("stdout");
    let mut first = [0u8; 1];
    out.read_exact(&mut first).expect("some output");
    drop(out);
    let mut err = String::new();
    let _ = child
        .stderr
        .take()
        .expect("stderr")
        .read_to_string(&mut err);
    let status = child.wait().expect("exits");
    assert_eq!(status.code(), Some(141), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn goal_prolog_error_answer_exits_1() {
    let dir = temp("prolog");
    let pl = dir.join("k.pl");
    std::fs::write(&pl, "p(1).\n").expect("write");
    let o = goal(&["prolog", pl.to_str().expect("utf-8"), "-q", "X is foo + 1"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o.stdout).starts_with("error"), "{}", text(&o.stdout));
}

#[test]
fn goal_test_reports_every_file_of_a_directory_when_one_breaks() {
    let dir = temp("testdir");
    let fixtures = root().join("tests/fixtures/test2g");
    for (sub, name) in [
        ("passing", "sections.test2g"),
        ("failing", "count.mas2g"),
        ("failing", "count.goal"),
    ] {
        std::fs::create_dir_all(dir.join(sub)).expect("dir");
        std::fs::copy(fixtures.join(sub).join(name), dir.join(sub).join(name)).expect("copy");
    }
    // Sorted first: a test file whose MAS does not exist, and one that is not even a test.
    std::fs::write(
        dir.join("a_missing.test2g"),
        "masTest { mas = \"nowhere.mas2g\". x { t { assert bel(true). } } }\n",
    )
    .expect("write");
    std::fs::write(dir.join("b_garbage.test2g"), "this is not a test file\n").expect("write");
    let o = goal(&["test", dir.to_str().expect("utf-8")]);
    let out = text(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("a_missing.test2g"), "{out}");
    assert!(out.contains("b_garbage.test2g"), "{out}");
    assert!(
        out.lines()
            .any(|l| l.contains("sections.test2g") && l.contains("... passed")),
        "{out}"
    );
}

#[test]
fn goal_test_runs_the_same_runtime_as_goal_run() {
    let dir = root().join("tests/fixtures/runtime/unified");
    let run = goal(&["run", dir.join("mover.mas2g").to_str().expect("utf-8")]);
    let test = goal(&["test", dir.join("mover.test2g").to_str().expect("utf-8")]);
    let why = "environment action move(a) by an agent without an entity";
    let run_err = text(&run.stderr);
    assert_eq!(run.status.code(), Some(4), "{run_err}");
    assert!(run_err.contains(why), "{run_err}");
    // The test sees the same fatal error (it used to drop the action silently and pass).
    let out = text(&test.stdout);
    assert_eq!(test.status.code(), Some(1), "{out}");
    assert!(out.contains("FAILED") && out.contains(why), "{out}");
}

#[test]
fn a_cycle_sending_more_than_its_quota_is_a_runtime_error() {
    let o = goal(&["run", &fixture("shouter.goal"), "--max-sent", "100"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    assert!(
        err.contains("shouter.goal:4: the cycle sent more than 100 messages"),
        "{err}"
    );
}
