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
