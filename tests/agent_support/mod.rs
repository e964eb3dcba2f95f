//! Helpers for the agent tests: compile `.goal` text, run cycles, read the mental state.
#![allow(dead_code)]

use goal::agent::{Agent, AgentConfig, CycleOutput, Message, Program};
use goal::syntax::prolog::Reader;
use goal::term::Term;

/// Compiles a program or panics with its diagnostics.
pub fn program(src: &str) -> std::sync::Arc<Program> {
    match Program::from_source("test.goal", src) {
        Ok(p) => p,
        Err(d) => panic!(
            "program does not compile:\n{}",
            d.iter()
                .map(|x| x.render(src))
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

/// An agent named `a` with seed 1 (and the given other agents).
pub fn agent_with(src: &str, name: &str, others: &[&str], seed: u64) -> Agent {
    let cfg = AgentConfig {
        seed,
        agents: others.iter().map(|s| s.to_string()).collect(),
        ..AgentConfig::default()
    };
    Agent::new(program(src), name, cfg)
}

/// An agent named `a`.
pub fn agent(src: &str) -> Agent {
    agent_with(src, "a", &[], 1)
}

/// Reads one term.
pub fn t(text: &str) -> Term {
    Reader::new("t").term(text, 0).expect("term").term
}

/// Runs `n` cycles without input; returns all outputs.
pub fn run(a: &mut Agent, n: usize) -> Vec<CycleOutput> {
    (0..n).map(|_| a.step(&[], &[])).collect()
}

/// Runs one cycle with percepts (given as text) and messages.
pub fn step(a: &mut Agent, percepts: &[&str], msgs: &[Message]) -> CycleOutput {
    let ps: Vec<Term> = percepts.iter().map(|p| t(p)).collect();
    a.step(&ps, msgs)
}

/// The beliefs as sorted text.
pub fn beliefs(a: &Agent) -> Vec<String> {
    let mut v: Vec<String> = a
        .mental_state()
        .beliefs
        .iter()
        .map(|t| t.to_string())
        .collect();
    v.sort();
    v
}

/// The current goals as text, in order.
pub fn goals(a: &Agent) -> Vec<String> {
    a.mental_state()
        .attention
        .current()
        .goals()
        .iter()
        .map(|g| g.term.to_string())
        .collect()
}

/// All printed lines of some outputs.
pub fn printed(outs: &[CycleOutput]) -> Vec<String> {
    outs.iter().flat_map(|o| o.printed.clone()).collect()
}

/// All environment actions of some outputs, as text.
pub fn env_actions(outs: &[CycleOutput]) -> Vec<String> {
    outs.iter()
        .flat_map(|o| o.env_actions.iter().map(|t| t.to_string()))
        .collect()
}
