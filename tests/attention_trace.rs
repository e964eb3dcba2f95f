//! The trace says which attention set each goal event concerns: modules with a focus write
//! `attention_pushed`/`attention_popped`, and goal events in a pushed set carry its number
//! (`attention`); events of the top-level goal base leave the field out, so traces of programs
//! without focus are what they were before.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `file` (relative to the crate) with `goal run --trace` and returns the trace's records.
fn run(file: &str, name: &str) -> Vec<Value> {
    let dir = std::env::temp_dir().join(format!("goal-attn-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let trace: PathBuf = dir.join("trace.jsonl");
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .current_dir(root())
        .args(["run", file, "--trace"])
        .arg(&trace)
        .output()
        .expect("goal runs");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&trace).expect("a trace");
    let _ = std::fs::remove_dir_all(&dir);
    text.lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

/// The goal and attention events of the trace, one line each: `goal_adopted near(box) in 1`
/// (no `in` when the event leaves the set out), `pushed pickUp focus=new [] as 1`,
/// `popped pickUp 1`; prefixed with the tick.
fn goal_events(records: &[Value]) -> Vec<String> {
    let mut out = Vec::new();
    for r in records.iter().filter(|r| r["type"] == "cycle") {
        for e in r["events"].as_array().expect("events") {
            let s = |k: &str| e[k].as_str().unwrap_or("?").to_string();
            let line = match e["event"].as_str().unwrap_or("") {
                kind @ ("goal_adopted" | "goal_dropped" | "goal_achieved") => {
                    match e.get("attention") {
                        Some(n) => format!("{kind} {} in {n}", s("goal")),
                        None => format!("{kind} {}", s("goal")),
                    }
                }
                "attention_pushed" => format!(
                    "pushed {} focus={} {} as {}",
                    s("module"),
                    s("focus"),
                    e["goals"],
                    e["attention"]
                ),
                "attention_popped" => format!("popped {} {}", s("module"), e["attention"]),
                _ => continue,
            };
            out.push(format!("{} {line}", r["tick"]));
        }
    }
    out
}

#[test]
fn a_focus_new_module_has_its_own_numbered_attention_set() {
    let records = run("tests/fixtures/attention/picker.goal", "new");
    assert_eq!(
        goal_events(&records),
        [
            "0 goal_adopted delivered(box)",
            "0 pushed pickUp focus=new [] as 1",
            "0 goal_adopted near(box) in 1",
            "1 goal_achieved near(box) in 1",
            "1 goal_adopted holding(box) in 1",
            "2 goal_achieved holding(box) in 1",
            "3 popped pickUp 1",
            "5 goal_achieved delivered(box)",
        ]
    );
    // The push comes right after the module's entry, the pop right before its exit.
    let events: Vec<String> = records
        .iter()
        .filter(|r| r["type"] == "cycle")
        .flat_map(|r| r["events"].as_array().cloned().unwrap_or_default())
        .map(|e| e["event"].as_str().unwrap_or("").to_string())
        .filter(|e| e.starts_with("module_") || e.starts_with("attention_"))
        .collect();
    assert_eq!(
        events,
        [
            "module_entered",
            "module_exited",
            "module_entered",
            "module_entered",
            "attention_pushed",
            "attention_popped",
            "module_exited",
            "module_exited",
        ]
    );
}

#[test]
fn select_and_filter_sets_start_with_their_goals_and_drop_reaches_every_set() {
    let records = run("tests/fixtures/attention/focused.goal", "filter");
    assert_eq!(
        goal_events(&records),
        [
            "0 goal_adopted item(a)",
            "0 goal_adopted task(sweep)",
            "0 pushed handle focus=filter [\"item(a)\"] as 1",
            "0 goal_dropped item(a)",
            "0 goal_dropped item(a) in 1",
            "1 popped handle 1",
            "2 pushed chores focus=select [\"task(sweep)\"] as 1",
            "2 goal_achieved task(sweep) in 1",
            "3 popped chores 1",
            // Back in main: the goal check of the top-level base.
            "3 goal_achieved task(sweep)",
        ]
    );
}

#[test]
fn programs_without_focus_write_no_attention_sets() {
    for (file, name) in [
        ("agents/counter/counter.goal", "counter"),
        ("agents/pingpong/pingpong.mas2g", "pingpong"),
    ] {
        let records = run(file, name);
        let text: String = records.iter().map(|r| r.to_string()).collect();
        assert!(text.contains("goal_adopted"), "{name} adopts goals");
        assert!(!text.contains("attention"), "{name}: {text}");
    }
}
