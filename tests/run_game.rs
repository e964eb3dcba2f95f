//! A full BW4T game with the built-in default team (the reference team, 3 robots, default map)
//! completes within a tick budget; the summary is snapshotted.

use goal::mas::run::{run, Quiet, RunOptions};
use goal::mas::{default_team, EndReason};

/// Ticks the built-in team may take for the default map.
const BUDGET: u64 = 3_000;

#[test]
fn the_default_team_completes_a_game_within_budget() {
    let system = default_team::system().expect("the built-in team compiles");
    let opts = RunOptions {
        max_ticks: BUDGET,
        workers: 2,
        trace_rules: false,
        ..RunOptions::default()
    };
    let (s, _) = run(&system, &opts, None, &mut Quiet).expect("runs");
    assert_eq!(
        s.end,
        EndReason::Completed,
        "{}",
        goal::mas::summary::table(&s)
    );
    assert!(s.completed);
    assert!(s.ticks <= BUDGET);
    let env = s.env.as_ref().expect("environment statistics");
    assert_eq!(
        Some(s.deliveries.right),
        env["sequence_length"].as_u64(),
        "every block of the sequence delivered"
    );
    assert_eq!(s.agents.len(), 3);
    assert!(s.agents.values().all(|a| a.error.is_none() && a.cycles > 0));
    insta::assert_snapshot!(goal::mas::summary::table(&s));
}
