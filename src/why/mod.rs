//! `goal why`: for an agent at a tick, what each rule of the modules it ran in that cycle did —
//! fired (with bindings), the first condition literal that failed (with the bindings up to
//! it), the action whose precondition failed, or not evaluated. Runs are deterministic, so the
//! system is rerun up to that tick with a recorder in the one agent (`agent::why`) instead of
//! storing every evaluation in the trace. See `docs/why.md`.

mod replay;
mod source;
pub mod text;

pub use crate::agent::why::{LiteralWhy, Outcome, RuleWhy};
use crate::mas::input::InputLog;
use crate::mas::run::RunOptions;
use crate::mas::MasSystem;
use serde::Serialize;
use source::TraceRun;
use std::fmt;
use std::path::Path;

/// What the rules of one agent did in one cycle. The JSON field names are shared with the
/// browser view: new fields may be added, these are never renamed.
#[derive(Clone, Debug, Serialize)]
pub struct WhyReport {
    pub agent: String,
    /// The tick asked about.
    pub tick: u64,
    /// The agent's cycle explained (1 = its first).
    pub cycle: u64,
    /// The module the cycle ended in (its main phase), e.g. `main`.
    pub module: String,
    /// Every rule of every module and nested block run in the cycle, grouped by module in the
    /// order they were entered, each module's rules in source order.
    pub rules: Vec<RuleWhy>,
    /// The tick the explained cycle ran at: `tick`, or earlier when the agent was waiting
    /// for new input at `tick` (see `note`).
    pub ran_at: u64,
    /// The agent's program file.
    pub file: String,
    /// Something to know about the answer (e.g. the agent was waiting at `tick`).
    pub note: Option<String>,
    /// The agent stopped in this cycle, and why.
    pub stopped: Option<String>,
    /// Whether the rerun fired the same rules with the same bindings as the trace recorded
    /// for this cycle (`None`: no trace, or it recorded no rules).
    pub matches_trace: Option<bool>,
    /// Every firing of the cycle in order (rule label, bindings), as a trace records them.
    #[serde(skip)]
    fired: Vec<(String, String)>,
}

/// Why a question could not be answered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WhyError {
    /// No agent of that name was launched.
    UnknownAgent { agent: String, known: Vec<String> },
    /// The run ended before the tick (`ticks`: how many it ran).
    PastEnd { tick: u64, ticks: u64 },
    /// The agent did not run at that tick (it had stopped).
    NotRunning {
        agent: String,
        tick: u64,
        why: String,
    },
    /// The trace cannot be read or is not a `goal` trace of a known version.
    Trace(String),
    /// The system cannot be loaded (diagnostics rendered).
    Load(String),
    /// The rerun failed (environment or worker failure).
    Run(String),
}

impl fmt::Display for WhyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WhyError::UnknownAgent { agent, known } => write!(
                f,
                "no agent named {agent} in this run (its agents: {})",
                known.join(", ")
            ),
            WhyError::PastEnd { tick, ticks } => write!(
                f,
                "tick {tick} is past the end of the run: it ran ticks 0 to {}",
                ticks.saturating_sub(1)
            ),
            WhyError::NotRunning { agent, tick, why } => {
                write!(f, "{agent} was not running at tick {tick}: {why}")
            }
            WhyError::Trace(m) | WhyError::Load(m) | WhyError::Run(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for WhyError {}

/// What to say when [`WhyReport::matches_trace`] is false.
pub const MISMATCH: &str = "the rerun fired other rules than the trace recorded for this \
     cycle: the agent files (or the map) changed since the trace was written, so this report \
     may not be about the recorded run";

/// Explains what agent `agent`'s rules did at tick `tick` of the run of `system` with `opts`
/// (rerunning it up to that tick).
pub fn explain(
    system: &MasSystem,
    opts: &RunOptions,
    agent: &str,
    tick: u64,
) -> Result<WhyReport, WhyError> {
    replay::explain(system, opts, &InputLog::new(), agent, tick)
}

/// Answers why-questions about one run, again and again (the view server holds one).
pub struct Why {
    system: MasSystem,
    opts: RunOptions,
    trace: Option<TraceRun>,
    /// People's requests of the run (from the trace, or growing with a live run).
    inputs: InputLog,
}

impl Why {
    /// The run recorded in the trace at `path` (its header names the system, seed, map and
    /// options; the system's files are read again, from where the run was started).
    pub fn for_trace(path: &Path) -> Result<Why, WhyError> {
        let trace = TraceRun::open(path)?;
        let (system, opts) = trace.system()?;
        Ok(Why {
            system,
            opts,
            inputs: trace.inputs.clone(),
            trace: Some(trace),
        })
    }

    /// The run of `system` with `opts` (seed, map, robots, quotas).
    pub fn for_system(system: MasSystem, opts: RunOptions) -> Why {
        Why {
            system,
            opts,
            trace: None,
            inputs: InputLog::new(),
        }
    }

    /// The same, with the people's requests of the run (a live run's log, which grows).
    pub fn with_inputs(mut self, inputs: InputLog) -> Why {
        self.inputs = inputs;
        self
    }

    /// What agent `agent`'s rules did at tick `tick`.
    pub fn report(&self, agent: &str, tick: u64) -> Result<WhyReport, WhyError> {
        if let Some(t) = &self.trace {
            t.check(agent, tick)?;
        }
        let mut report = replay::explain(&self.system, &self.opts, &self.inputs, agent, tick)?;
        if let Some(t) = &self.trace {
            report.matches_trace = t.matches(agent, report.ran_at, &report.fired)?;
        }
        Ok(report)
    }

    /// [`Why::report`] as JSON, the error as its message (what the view's `WhyProvider` asks).
    pub fn why(&self, agent: &str, tick: u64) -> Result<serde_json::Value, String> {
        let r = self.report(agent, tick).map_err(|e| e.to_string())?;
        serde_json::to_value(&r).map_err(|e| e.to_string())
    }
}

impl crate::view::WhyProvider for Why {
    fn why(&self, agent: &str, tick: u64) -> Result<serde_json::Value, String> {
        Why::why(self, agent, tick)
    }
}
