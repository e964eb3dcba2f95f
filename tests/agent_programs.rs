//! Small agent programs run against scripted environment stubs; traces are snapshotted.

mod agent_support;
use agent_support::*;
use goal::agent::{Agent, AgentConfig, CycleOutput, Message, Program, TraceLevel};
use goal::term::Term;
use std::sync::Arc;

fn fixture(name: &str) -> Arc<Program> {
    let path = format!("{}/tests/fixtures/agent/{name}", env!("CARGO_MANIFEST_DIR"));
    let src = std::fs::read_to_string(&path).expect("fixture");
    match Program::from_source(name, &src) {
        Ok(p) => p,
        Err(d) => panic!("{}", d.iter().map(|x| x.render(&src)).collect::<String>()),
    }
}

fn make(prog: &str, name: &str, others: &[&str], seed: u64, trace: TraceLevel) -> Agent {
    let cfg = AgentConfig {
        seed,
        agents: others.iter().map(|s| s.to_string()).collect(),
        trace,
        ..AgentConfig::default()
    };
    Agent::new(fixture(prog), name, cfg)
}

/// The events of some outputs as JSON lines.
fn trace(outs: &[CycleOutput]) -> String {
    let mut s = String::new();
    for o in outs {
        for e in &o.events {
            s.push_str(&serde_json::to_string(e).expect("json"));
            s.push('\n');
        }
    }
    s
}

/// A scripted blocks world: percepts `on(X,Y)` every tick, `move(X,Y)` actions.
fn run_stacker(seed: u64) -> (Vec<CycleOutput>, Agent) {
    let mut world: Vec<(String, String)> = [("a", "table"), ("b", "a"), ("c", "table")]
        .iter()
        .map(|(x, y)| (x.to_string(), y.to_string()))
        .collect();
    let mut agent = make("stacker.goal", "stacker", &[], seed, TraceLevel::Rules);
    let mut outs = Vec::new();
    for _ in 0..30 {
        let percepts: Vec<Term> = world
            .iter()
            .map(|(x, y)| t(&format!("on({x},{y})")))
            .collect();
        let out = agent.step(&percepts, &[]);
        for a in &out.env_actions {
            let args: Vec<String> = a.args().iter().map(|x| x.to_string()).collect();
            world.retain(|(x, _)| *x != args[0]);
            world.push((args[0].clone(), args[1].clone()));
        }
        let stop = out.stopped.is_some();
        outs.push(out);
        if stop {
            break;
        }
    }
    world.sort();
    assert_eq!(
        world,
        [("a", "b"), ("b", "c"), ("c", "table")].map(|(x, y)| (x.to_string(), y.to_string()))
    );
    (outs, agent)
}

#[test]
fn blocks_world_stacker_reaches_its_goal() {
    let (outs, agent) = run_stacker(1);
    assert!(
        agent.stopped().is_some(),
        "main exits when the goal is achieved"
    );
    insta::assert_snapshot!("stacker_trace", trace(&outs));
}

#[test]
fn same_seed_same_trace() {
    assert_eq!(trace(&run_stacker(5).0), trace(&run_stacker(5).0));
}

#[test]
fn counter_to_100() {
    let run = |seed| {
        let mut a = make("counter.goal", "counter", &[], seed, TraceLevel::Changes);
        let outs: Vec<CycleOutput> = (0..150).map(|_| a.step(&[], &[])).collect();
        (outs, a)
    };
    let (outs, a) = run(1);
    assert_eq!(printed(&outs), ["done"]);
    assert_eq!(beliefs(&a), ["count(100)"]);
    assert_eq!(a.cycles(), 101, "one increment per cycle, then the exit");
    // No randomness in this program: another seed gives the same trace.
    assert_eq!(trace(&outs), trace(&run(99).0));
    let full = trace(&outs);
    let tail: Vec<&str> = full
        .lines()
        .rev()
        .take(8)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    insta::assert_snapshot!("counter_tail", tail.join("\n"));
}

#[test]
fn ping_pong_pair_exchanges_moods() {
    let mut alice = make("ping.goal", "alice", &["bob"], 1, TraceLevel::Changes);
    let mut bob = make("pong.goal", "bob", &["alice"], 2, TraceLevel::Changes);
    let (mut to_alice, mut to_bob): (Vec<Message>, Vec<Message>) = (Vec::new(), Vec::new());
    let mut log = String::new();
    for round in 1..=30 {
        let oa = alice.step(&[], &std::mem::take(&mut to_alice));
        let ob = bob.step(&[], &std::mem::take(&mut to_bob));
        for (who, o) in [("alice", &oa), ("bob", &ob)] {
            for m in &o.messages {
                log.push_str(&format!(
                    "round {round}: {who} -> {}: {}\n",
                    m.receiver, m.content
                ));
            }
            for p in &o.printed {
                log.push_str(&format!("round {round}: {who} prints {p}\n"));
            }
        }
        for m in oa.messages.into_iter().chain(ob.messages) {
            match m.receiver.name() {
                "alice" => to_alice.push(m),
                _ => to_bob.push(m),
            }
        }
        if alice.stopped().is_some() {
            log.push_str(&format!("round {round}: alice stopped\n"));
            break;
        }
    }
    assert!(alice.stopped().is_some());
    assert!(log.contains("bob -> alice: int(score(3))"));
    assert!(log.contains("alice -> bob: imp(play(3))"));
    insta::assert_snapshot!("ping_pong", log);
}

#[test]
fn module_focus_example() {
    let mut a = make("focus.goal", "walker", &[], 3, TraceLevel::Changes);
    let mut outs = Vec::new();
    for _ in 0..20 {
        let o = a.step(&[], &[]);
        let stop = o.stopped.is_some();
        outs.push(o);
        if stop {
            break;
        }
    }
    assert!(a.stopped().is_some(), "all goals achieved");
    let acts = env_actions(&outs);
    assert_eq!(acts.len(), 2, "{acts:?}");
    assert_eq!(printed(&outs), ["carry(box1)"]);
    insta::assert_snapshot!("focus_trace", trace(&outs));
}
