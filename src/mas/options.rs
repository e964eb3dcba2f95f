//! How to run a system: the options of `goal run` and `goal test` that reach the round driver.

use std::sync::atomic::AtomicUsize;
use std::sync::Arc;
use std::time::Duration;

/// Simulated seconds per tick: what `get_time/1` advances by per tick in lock-step runs (the
/// BW4T server's default step delay), so runs are reproducible.
pub const TICK_SECONDS: f64 = 0.01;

/// How to run a system.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The run seed (overrides the MAS file's `seed`); default: the file's, else 0.
    pub seed: Option<u64>,
    /// A map (built-in name or file) replacing the MAS file's.
    pub map: Option<String>,
    /// Number of robots in the environment.
    pub robots: Option<usize>,
    /// Number of HumanBots (robots people play from the browser view; BW4T's `humancount`).
    pub humans: Option<usize>,
    /// Stop after this many ticks (rounds without an environment).
    pub max_ticks: u64,
    /// Worker threads for the agents.
    pub workers: usize,
    /// Do not step agents that have nothing new (the trace is the same either way).
    pub skip_idle: bool,
    /// Pace the rounds to this many per second (for watching); `None`: as fast as possible.
    pub realtime: Option<f64>,
    /// Stop after this much wall time.
    pub time_limit: Option<Duration>,
    /// Record every rule evaluation (needed for a full trace); otherwise only changes.
    pub trace_rules: bool,
    /// Set to a signal number (non-zero) to stop the run after the round under way.
    pub interrupt: Option<Arc<AtomicUsize>>,
    /// Stop the run when the process's resident memory exceeds this many bytes.
    pub max_memory: Option<u64>,
    /// Wall time one cycle of an agent may take (a longer cycle is cut: runtime error).
    pub cycle_time: Option<Duration>,
    /// Most facts an agent's belief base may hold (more: runtime error of that agent).
    pub max_beliefs: usize,
    /// Most messages waiting for an agent in one round; more are dropped and reported.
    pub max_mailbox: usize,
    /// Most messages one agent may send in one cycle (more: runtime error of that agent).
    pub max_sent: usize,
    /// The transport and session options (CLAMR); default: in-process, nothing followed.
    pub comm: crate::clamr::CommOptions,
    /// The KR engine of agents whose `.mas2g` entry does not choose one (`language`).
    pub kr: crate::kr::KrKind,
}

/// Default of [`RunOptions::max_memory`]: 4 GiB.
pub const DEFAULT_MAX_MEMORY: u64 = 4 << 30;
/// Default of [`RunOptions::max_mailbox`].
pub const DEFAULT_MAX_MAILBOX: usize = 100_000;

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            seed: None,
            map: None,
            robots: None,
            humans: None,
            max_ticks: 10_000,
            workers: std::thread::available_parallelism().map_or(1, |n| n.get()),
            skip_idle: true,
            realtime: None,
            time_limit: None,
            trace_rules: true,
            interrupt: None,
            max_memory: Some(DEFAULT_MAX_MEMORY),
            cycle_time: Some(crate::agent::DEFAULT_CYCLE_TIME),
            max_beliefs: crate::agent::DEFAULT_MAX_BELIEFS,
            max_mailbox: DEFAULT_MAX_MAILBOX,
            max_sent: DEFAULT_MAX_MAILBOX,
            comm: crate::clamr::CommOptions::default(),
            kr: crate::kr::KrKind::Native,
        }
    }
}

impl RunOptions {
    /// The options that change what happens in a run besides its system, seed and map, as the
    /// trace header records them (`options`), so that `goal why` can rerun it exactly.
    pub fn replay_json(&self) -> serde_json::Value {
        let mut v = serde_json::json!({
            "robots": self.robots,
            "max_beliefs": self.max_beliefs,
            "max_mailbox": self.max_mailbox,
            "max_sent": self.max_sent,
        });
        // Only runs with `--humans` say so: the headers of all other runs stay as they were.
        if let Some(h) = self.humans {
            v["humans"] = h.into();
        }
        v
    }

    /// These options with those of a trace header's `options` (missing fields keep their
    /// value: traces written before the field existed).
    pub fn with_replay(mut self, v: &serde_json::Value) -> RunOptions {
        let get = |k: &str| v.get(k).and_then(serde_json::Value::as_u64);
        let size = |n: u64| usize::try_from(n).unwrap_or(usize::MAX);
        if let Some(r) = get("robots") {
            self.robots = Some(size(r));
        }
        if let Some(h) = get("humans") {
            self.humans = Some(size(h));
        }
        if let Some(n) = get("max_beliefs") {
            self.max_beliefs = size(n);
        }
        if let Some(n) = get("max_mailbox") {
            self.max_mailbox = size(n);
        }
        if let Some(n) = get("max_sent") {
            self.max_sent = size(n);
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rerun_gets_the_humans_of_the_run_and_other_headers_stay_as_they_were() {
        let plain = RunOptions::default().replay_json();
        assert!(plain.get("humans").is_none(), "{plain}");
        let run = RunOptions {
            humans: Some(2),
            robots: Some(1),
            ..RunOptions::default()
        };
        let rerun = RunOptions::default().with_replay(&run.replay_json());
        assert_eq!((rerun.humans, rerun.robots), (Some(2), Some(1)));
        assert_eq!(RunOptions::default().with_replay(&plain).humans, None);
    }
}
