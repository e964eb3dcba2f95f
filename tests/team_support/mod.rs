//! A minimal lock-step driver for the BW4T team tests: one agent per robot entity, rounds of
//! "every agent runs one cycle on its percepts and messages, actions are applied in agent-name
//! order, the world ticks". It mirrors the runtime's round structure (`architecture.md`,
//! "Threads and determinism") so the team can be exercised directly through the library API.
#![allow(dead_code)]

use goal::agent::{Agent, AgentConfig, Message, PerceptType, PerceptTypes, Program, TraceLevel};
use goal::bw4t::Bw4t;
use goal::env::{self, Environment, InitParams};
use goal::term::Term;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

/// The repository's `agents/bw4t/` directory.
pub fn team_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("agents/bw4t")
}

/// Compiles an agent file of `agents/bw4t/` or panics with its diagnostics.
pub fn program(file: &str) -> Arc<Program> {
    let path = team_dir().join(file);
    let src = std::fs::read_to_string(&path).expect("agent file");
    match Program::from_source(&path.to_string_lossy(), &src) {
        Ok(p) => p,
        Err(d) => panic!(
            "{file} does not compile:\n{}",
            d.iter()
                .map(|x| x.render(&src))
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

/// Per-agent figures of a game.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct AgentFigures {
    pub cycles: u64,
    pub actions: u64,
    pub messages: u64,
    pub error: Option<String>,
}

/// The outcome of a game.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Game {
    pub map: String,
    pub robots: usize,
    pub seed: u64,
    pub completed: bool,
    pub ticks: u64,
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
    pub messages: u64,
    pub failed_actions: u64,
    pub agents: BTreeMap<String, AgentFigures>,
}

fn agent_type(t: env::PerceptType) -> PerceptType {
    match t {
        env::PerceptType::Once => PerceptType::Once,
        env::PerceptType::OnChange => PerceptType::OnChange,
        env::PerceptType::OnChangeWithNegation => PerceptType::OnChangeNeg,
        env::PerceptType::Always => PerceptType::Always,
    }
}

/// Plays `file` (one copy per robot) on `map` with `robots` robots until the sequence is done,
/// every agent stopped or `max_ticks` ticks passed.
pub fn play(file: &str, map: &str, robots: usize, seed: u64, max_ticks: u64) -> Game {
    let prog = program(file);
    let mut params = InitParams::new();
    params.insert("map".into(), Term::atom(map));
    params.insert("robots".into(), Term::Int(robots as i64));
    params.insert("seed".into(), Term::Int(seed as i64));
    let mut world = match Bw4t::from_params(&params) {
        Ok(w) => w,
        Err(d) => panic!("bad map {map}: {d:?}"),
    };
    let types = Arc::new(PerceptTypes::new(world.declarations().into_iter().map(|d| {
        ((d.name.clone(), d.arity), agent_type(d.kind))
    })));
    let mut names: Vec<String> = world.entities().into_iter().map(|e| e.name).collect();
    names.sort();
    let mut agents: Vec<Agent> = names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let cfg = AgentConfig {
                seed: seed.wrapping_mul(1000).wrapping_add(i as u64),
                agents: names.clone(),
                percept_types: types.clone(),
                trace: TraceLevel::Changes,
                ..AgentConfig::default()
            };
            Agent::new(prog.clone(), n, cfg)
        })
        .collect();
    let mut game = Game {
        map: map.to_string(),
        robots: names.len(),
        seed,
        ..Game::default()
    };
    for n in &names {
        game.agents.insert(n.clone(), AgentFigures::default());
    }
    let mut inbox: BTreeMap<String, Vec<Message>> = BTreeMap::new();
    let mut acted: BTreeMap<String, bool> = BTreeMap::new();
    let verbose = std::env::var("TEAM_VERBOSE").is_ok();
    while world.ticks() < max_ticks && !world.is_finished() {
        let mut actions: Vec<(String, Term)> = Vec::new();
        let mut outgoing: Vec<Message> = Vec::new();
        let mut alive = 0;
        for a in agents.iter_mut() {
            let name = a.name().to_string();
            let batch = world.percepts(&name);
            let msgs = inbox.remove(&name).unwrap_or_default();
            if a.stopped().is_some() {
                continue;
            }
            alive += 1;
            // Idle agents (nothing new) skip the cycle, as the runtime's scheduler does.
            if batch.is_empty() && msgs.is_empty() && !acted.get(&name).copied().unwrap_or(true) {
                continue;
            }
            let out = a.step(&batch, &msgs);
            let fig = game.agents.get_mut(&name).expect("agent");
            fig.cycles += 1;
            fig.actions += out.env_actions.len() as u64;
            fig.messages += out.messages.len() as u64;
            if verbose {
                for act in &out.env_actions {
                    eprintln!("{:>5} {name}: {act}", world.ticks());
                }
                for m in &out.messages {
                    eprintln!("{:>5} {name} -> {}: {}", world.ticks(), m.receiver, m.content);
                }
                for e in &out.events {
                    eprintln!("{:>5} {name}: {e:?}", world.ticks());
                }
            }
            if let Some(goal::agent::StopReason::Error(e)) = &out.stopped {
                fig.error = Some(e.to_string());
            }
            let did = !out.env_actions.is_empty()
                || !out.messages.is_empty()
                || out.events.iter().any(|e| {
                    matches!(
                        e,
                        goal::agent::Event::ActionPerformed { .. }
                    )
                });
            acted.insert(name.clone(), did);
            game.messages += out.messages.len() as u64;
            for act in out.env_actions {
                actions.push((name.clone(), act));
            }
            outgoing.extend(out.messages);
        }
        if alive == 0 {
            break;
        }
        for (name, act) in actions {
            let r = world.perform(&name, &act);
            if !r.is_ok() {
                game.failed_actions += 1;
                if verbose {
                    eprintln!("{:>5} {name}: {act} FAILED {r:?}", world.ticks());
                }
            }
        }
        for m in outgoing {
            inbox.entry(m.receiver.clone()).or_default().push(m);
        }
        world.tick();
    }
    let stats = world.run_stats();
    game.completed = world.is_finished();
    game.ticks = stats.finished_at_tick.unwrap_or(world.ticks());
    game.deliveries_right = stats.deliveries_right;
    game.deliveries_wrong = stats.deliveries_wrong;
    game
}
