//! Idle-agent memory: `agents` (default 10,000) agents of `agents/bench/idle.goal` created the
//! way `goal run` creates them (every agent knows every other), handed to the worker pool and
//! stepped once (their first cycle); memory per agent is the RSS growth divided by the count.

use super::report::Target;
use super::{file, rss, Params, Report};
use crate::agent::{Agent, AgentConfig, Program, TraceLevel};
use crate::mas::scheduler::{Job, Pool};
use std::time::Instant;

/// `agents`: creation time and memory of `agents` idle agents.
pub fn run(params: &Params, workers: usize) -> Result<Report, String> {
    let n = params.get("agents", 10_000)? as usize;
    let text = file("idle.goal")?;
    let before = rss::current_kib();
    let t0 = Instant::now();
    let prog = Program::from_source("agents/bench/idle.goal", text)
        .map_err(|ds| ds.iter().map(|d| d.render(text)).collect::<String>())?;
    let names: Vec<String> = (1..=n).map(|i| format!("idle{i}")).collect();
    let directory = crate::agent::Directory::new(&names);
    let agents: Vec<Agent> = names
        .iter()
        .map(|name| {
            let config = AgentConfig {
                seed: crate::mas::launch::agent_seed(0, name),
                directory: Some(directory.clone()),
                trace: TraceLevel::Off,
                ..AgentConfig::default()
            };
            Agent::new(prog.clone(), name, config)
        })
        .collect();
    let pool = Pool::new(agents, workers).map_err(|e| e.0)?;
    let create = t0.elapsed();
    let t1 = Instant::now();
    let jobs: Vec<Job> = (0..n).map(|i| (i, Vec::new(), Vec::new())).collect();
    let outs = pool.round(jobs, None).map_err(|e| e.0)?;
    let run = t1.elapsed();
    let after = rss::current_kib();
    let mut failure = None;
    if outs.len() != n {
        failure = Some(format!(
            "{} of {n} agents ran their first cycle",
            outs.len()
        ));
    } else if let Some((i, o)) = outs.iter().find(|(_, o)| o.stopped.is_some()) {
        failure = Some(format!("agent {i} stopped: {:?}", o.stopped));
    }
    let per_agent = match (before, after) {
        (Some(b), Some(a)) => Some(a.saturating_sub(b) as f64 * 1024.0 / n as f64),
        _ => None,
    };
    let workers = pool.workers();
    drop(pool);
    let mut report = Report {
        name: "agents".into(),
        config: format!("agents={n}"),
        failure,
        agents: n,
        workers,
        create,
        run,
        count: n as u64,
        unit: "agents",
        cycles: n as u64,
        cpu: None,
        peak_rss_kib: rss::peak_kib(),
        extra: vec![(
            "per agent".into(),
            match per_agent {
                Some(b) => format!("{:.2} KiB (RSS growth / agents)", b / 1024.0),
                None => "unknown".into(),
            },
        )],
        targets: Vec::new(),
    };
    if n == 10_000 {
        report.targets.push(Target {
            what: "creation",
            value: create.as_secs_f64(),
            target: 1.0,
            unit: "s",
            lower_is_better: true,
        });
        if let Some(b) = per_agent {
            report.targets.push(Target {
                what: "memory per agent",
                value: b / 1024.0,
                target: 20.0,
                unit: "KiB",
                lower_is_better: true,
            });
        }
    }
    Ok(report)
}
