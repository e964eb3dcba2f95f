//! Full BW4T games played by the reference team written in modular GOAL (A,
//! `agents/bw4t/modular/`) and in MARBEL (B, `agents/bw4t/marbel/`): banana, rainbow and random
//! with 1 and 3 robots. Each game must deliver the whole sequence without wrong deliveries or
//! agent errors; the figures are snapshotted.

use goal::mas::run::{run, Quiet, RunOptions};
use goal::mas::system::load_mas;
use serde_json::json;
use std::path::PathBuf;

fn play(team: &str, map: &str, robots: usize) -> serde_json::Value {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("agents/bw4t")
        .join(team)
        .join("team.mas2g");
    let sys = load_mas(&file).unwrap_or_else(|p| {
        panic!(
            "{}",
            p.iter().map(|p| p.render()).collect::<Vec<_>>().join("\n")
        )
    });
    assert!(
        sys.warnings.is_empty(),
        "warnings: {}",
        sys.warnings[0].render()
    );
    let opts = RunOptions {
        seed: Some(1),
        map: Some(map.to_string()),
        robots: Some(robots),
        max_ticks: if robots == 1 { 8_000 } else { 4_000 },
        workers: 2,
        trace_rules: false,
        ..RunOptions::default()
    };
    let (s, err) =
        run(&sys, &opts, None, &mut Quiet).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let what = format!("{team} on {map} with {robots} robot(s)");
    assert_eq!(err, None, "{what}: runtime failure");
    assert!(s.completed, "{what}: not completed after {} ticks", s.ticks);
    assert_eq!(s.deliveries.wrong, 0, "{what}: wrong deliveries");
    assert_eq!(s.agents.len(), robots, "{what}: one agent per robot");
    for (name, a) in &s.agents {
        assert_eq!(a.error, None, "{what}: {name} stopped on an error");
        assert!(a.env_actions > 0, "{what}: {name} never acted");
    }
    if robots > 1 {
        assert!(s.messages > 0, "{what}: a team coordinates by messages");
    }
    json!({
        "team": team,
        "map": map,
        "robots": robots,
        "completed": s.completed,
        "ticks": s.ticks,
        "deliveries": s.deliveries,
        "messages": s.messages,
    })
}

macro_rules! game {
    ($name:ident, $team:expr, $map:expr, $robots:expr) => {
        #[test]
        fn $name() {
            insta::assert_json_snapshot!(play($team, $map, $robots));
        }
    };
}

game!(modular_banana_1, "modular", "banana", 1);
game!(modular_banana_3, "modular", "banana", 3);
game!(modular_rainbow_1, "modular", "rainbow", 1);
game!(modular_rainbow_3, "modular", "rainbow", 3);
game!(modular_random_1, "modular", "random", 1);
game!(modular_random_3, "modular", "random", 3);
game!(marbel_banana_1, "marbel", "banana", 1);
game!(marbel_banana_3, "marbel", "banana", 3);
game!(marbel_rainbow_1, "marbel", "rainbow", 1);
game!(marbel_rainbow_3, "marbel", "rainbow", 3);
game!(marbel_random_1, "marbel", "random", 1);
game!(marbel_random_3, "marbel", "random", 3);

/// The three generations of the reference team play the same game: the lowering of (A) and (B)
/// to one program representation keeps the team's behaviour.
#[test]
fn generations_play_the_same_game() {
    let a = play("modular", "banana", 3);
    let b = play("marbel", "banana", 3);
    assert_eq!(a["ticks"], b["ticks"]);
    assert_eq!(a["messages"], b["messages"]);
}

/// `goal test` on the shipped test files of both teams: every robot's test passes, and the
/// reports (agent, test, outcome) are snapshotted.
#[test]
fn shipped_team_tests_pass() {
    use goal::testing::runner::{run_file, TestOptions};
    let mut lines = Vec::new();
    for team in ["modular", "marbel"] {
        let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("agents/bw4t")
            .join(team)
            .join("team.test2g");
        for r in run_file(&file, &TestOptions::default()) {
            assert_eq!(r.outcome, goal::testing::Outcome::Passed, "{}", r.to_text());
            lines.push(format!("{team} {}/{} {:?}", r.agent, r.test, r.outcome));
        }
    }
    insta::assert_snapshot!(lines.join("\n"));
}

/// A golden trace of a modular system: deterministic, and its rule labels name lines of the
/// module files (not of the text the files were assembled in).
#[test]
fn modular_trace_is_golden() {
    use goal::testing::golden::{compare, record};
    std::env::set_current_dir(env!("CARGO_MANIFEST_DIR")).expect("manifest dir");
    let path = std::path::Path::new("tests/fixtures/modular/pingpong/pingpong.mas2g");
    let sys = load_mas(path).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let opts = RunOptions {
        workers: 2,
        ..RunOptions::default()
    };
    let trace = record(&sys, &opts).expect("runs");
    assert_eq!(compare(&trace, &record(&sys, &opts).expect("runs")), None);
    assert!(
        trace.contains("\"rule\":\"event:2\""),
        "labels are lines of the module file"
    );
    insta::assert_snapshot!("modular_pingpong_trace", trace);
}

/// `goal check`, `goal run` and `goal test` on modular systems through the binary.
#[test]
fn the_binary_checks_runs_and_tests_modular_systems() {
    use std::process::Command;
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let goal = env!("CARGO_BIN_EXE_goal");
    let out = Command::new(goal)
        .args(["check", "agents/bw4t/modular", "agents/bw4t/marbel"])
        .current_dir(&root)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("0 errors, 0 warnings"), "{stderr}");
    let out = Command::new(goal)
        .args(["run", "tests/fixtures/modular/pingpong/pingpong.mas2g"])
        .current_dir(&root)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("messages    6"), "{stderr}");
    // A module with an error: exit code 1 and the file, line and column of the problem.
    let dir = std::env::temp_dir().join(format!("goal-modular-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(
        dir.join("team.mas2g"),
        "define a as agent { use m as main module. }\nlaunchpolicy { launch a. }\n",
    )
    .expect("write");
    std::fs::write(
        dir.join("m.mod2g"),
        "module m {\n  if bel(x) then fly.\n}\n",
    )
    .expect("write");
    let out = Command::new(goal)
        .args(["run", &dir.join("team.mas2g").display().to_string()])
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("m.mod2g:2:18"), "{stderr}");
}
