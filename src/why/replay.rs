//! Rerunning a system up to a tick with a recorder in one agent: an [`Observer`] creates that
//! agent with a [`Recorder`], tells the recorder each round's tick, and releases the run once
//! the tick asked about is over. Everything else runs as in the original run.

use super::{WhyError, WhyReport};
use crate::agent::why::Recorder;
use crate::agent::{Agent, AgentConfig, Program};
use crate::mas::input::{Input, InputLog};
use crate::mas::run::{Observer, RunOptions};
use crate::mas::{EndReason, MasSystem};
use std::sync::Arc;

struct Replay {
    target: String,
    until: u64,
    recorder: Recorder,
    /// Every launched agent's name.
    known: Vec<String>,
    /// The target's program, once it was launched.
    program: Option<Arc<Program>>,
    over: bool,
    warnings: Vec<String>,
    /// People's requests of the run, applied again at their rounds.
    inputs: InputLog,
}

impl Observer for Replay {
    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_string());
    }

    fn agent(
        &mut self,
        _i: usize,
        name: &str,
        program: &Arc<Program>,
        config: &AgentConfig,
    ) -> Option<Agent> {
        self.known.push(name.to_string());
        if name != self.target {
            return None;
        }
        self.program = Some(program.clone());
        let mut a = Agent::new(program.clone(), name, config.clone());
        a.set_why(Some(self.recorder.clone()));
        Some(a)
    }

    fn pace(&mut self, _round: u64, tick: u64) {
        self.recorder.set_tick(tick);
        self.over = tick > self.until;
    }

    fn inputs(&mut self, round: u64) -> Vec<Input> {
        self.inputs.at(round)
    }

    fn done(&self) -> bool {
        self.program.is_none() || self.over
    }
}

/// Reruns `system` up to tick `tick` (with people's requests `inputs` at their rounds) and
/// explains agent `agent`'s cycle there.
pub(super) fn explain(
    system: &MasSystem,
    opts: &RunOptions,
    inputs: &InputLog,
    agent: &str,
    tick: u64,
) -> Result<WhyReport, WhyError> {
    let mut replay = Replay {
        target: agent.to_string(),
        until: tick,
        recorder: Recorder::new(),
        known: Vec::new(),
        program: None,
        over: false,
        warnings: Vec::new(),
        inputs: inputs.clone(),
    };
    let opts = RunOptions {
        max_ticks: opts.max_ticks.min(tick.saturating_add(1)),
        workers: 1,
        realtime: None,
        time_limit: None,
        interrupt: None,
        trace_rules: false,
        ..opts.clone()
    };
    let (summary, _) = crate::mas::run(system, &opts, None, &mut replay)
        .map_err(|ps| WhyError::Load(ps.iter().map(|p| p.render()).collect::<Vec<_>>().join("")))?;
    let Some(program) = replay.program.clone() else {
        return Err(WhyError::UnknownAgent {
            agent: agent.to_string(),
            known: replay.known,
        });
    };
    if summary.end == EndReason::Failure {
        return Err(WhyError::Run(format!(
            "the rerun failed: {}",
            replay.warnings.join("; ")
        )));
    }
    if summary.ticks <= tick {
        return Err(WhyError::PastEnd {
            tick,
            ticks: summary.ticks,
        });
    }
    let stats = summary.agents.get(agent).cloned().unwrap_or_default();
    let stop = stats.stopped.then(|| {
        stats
            .error
            .clone()
            .map_or("its main module exited".to_string(), |e| {
                format!("runtime error: {e}")
            })
    });
    let Some(record) = replay.recorder.latest() else {
        return Err(WhyError::NotRunning {
            agent: agent.to_string(),
            tick,
            why: "it ran no cycle up to that tick".into(),
        });
    };
    let mut note = None;
    if record.tick < tick {
        if let Some(why) = &stop {
            return Err(WhyError::NotRunning {
                agent: agent.to_string(),
                tick,
                why: format!("it stopped at tick {} ({why})", record.tick),
            });
        }
        note = Some(format!(
            "{agent} ran no cycle at tick {tick}: it was waiting for new percepts or messages \
             since its cycle at tick {}, which is explained here (a cycle without new input \
             would do the same)",
            record.tick
        ));
    }
    let (module, rules) = record.explain(&program);
    Ok(WhyReport {
        agent: agent.to_string(),
        tick,
        cycle: record.cycle,
        module,
        rules,
        ran_at: record.tick,
        file: program.file.clone(),
        note,
        stopped: stop,
        matches_trace: None,
        fired: record.fired,
    })
}
