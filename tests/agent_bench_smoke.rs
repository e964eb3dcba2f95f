//! Smoke test for the cycle benchmark's robot agent: it compiles, acts every cycle, tracks
//! its percepts and keeps its belief base bounded.

#[path = "../benches/cycle/robot.rs"]
mod robot;

use goal::agent::{Agent, AgentConfig, Program, TraceLevel};

#[test]
fn robot_agent_acts_every_cycle_with_bounded_beliefs() {
    let p = Program::from_source("robot.goal", &robot::robot_program()).expect("robot compiles");
    assert_eq!(
        p.blocks.iter().map(|b| b.rules.len()).sum::<usize>(),
        40,
        "40 rules"
    );
    let cfg = AgentConfig {
        trace: TraceLevel::Off,
        ..AgentConfig::default()
    };
    let mut a = Agent::new(p, "robot", cfg);
    let mut sizes = Vec::new();
    for n in 0..200 {
        let out = a.step(&robot::percepts(n), &[]);
        assert!(out.stopped.is_none(), "{:?}", out.stopped);
        assert_eq!(out.env_actions.len(), 1, "one goTo per cycle");
        sizes.push(a.mental_state().beliefs.len());
    }
    assert!(
        sizes[199] <= sizes[10] + 1,
        "beliefs stay bounded: {sizes:?}"
    );
    assert!(a.mental_state().beliefs.len() >= 200);
}
