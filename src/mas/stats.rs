//! Run statistics: per agent and for the whole run, serializable for `--stats FILE`.

use serde::Serialize;
use std::collections::BTreeMap;

/// Figures of one agent.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct AgentStats {
    /// The entity the agent controls, if any.
    pub entity: Option<String>,
    /// Reasoning cycles run.
    pub cycles: u64,
    /// Real actions performed (built-in, messaging and environment actions).
    pub actions: u64,
    /// Environment actions handed to the environment.
    pub env_actions: u64,
    /// Rounds in which the agent had nothing new and was not stepped (or did nothing).
    pub idle_ticks: u64,
    /// Messages sent (one per receiver).
    pub messages_sent: u64,
    /// Messages to this agent dropped because its mailbox was full (`--max-mailbox`).
    #[serde(skip_serializing_if = "is_zero")]
    pub messages_dropped: u64,
    /// Why the agent stopped, when it stopped on a runtime error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// True when the agent stopped (main exited or an error).
    pub stopped: bool,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

/// Blocks delivered in the drop zone.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Deliveries {
    /// Blocks of the colour needed next.
    pub right: u64,
    /// Blocks of another colour (lost).
    pub wrong: u64,
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndReason {
    /// The environment's task is complete (the whole sequence was delivered).
    Completed,
    /// Every agent stopped.
    AllStopped,
    /// No environment, and no agent has anything left to do.
    Idle,
    /// The tick limit was hit.
    TickLimit,
    /// No environment, and the cycle (round) limit was hit.
    CycleLimit,
    /// The wall-time limit was hit.
    TimeLimit,
    /// The process used more memory than the run's cap (`--max-memory`).
    MemoryLimit,
    /// Interrupted by a signal (Ctrl-C, SIGTERM); the round under way was finished.
    Interrupted,
    /// The observer steering the run (a test controller) had what it needed.
    Released,
    /// The environment or a worker thread failed.
    Failure,
}

impl EndReason {
    /// A short English description.
    pub fn describe(self) -> &'static str {
        match self {
            EndReason::Completed => "sequence delivered",
            EndReason::AllStopped => "all agents stopped",
            EndReason::Idle => "no agent has anything left to do",
            EndReason::TickLimit => "tick limit reached",
            EndReason::CycleLimit => "cycle limit reached",
            EndReason::TimeLimit => "time limit reached",
            EndReason::MemoryLimit => "memory cap exceeded",
            EndReason::Interrupted => "interrupted",
            EndReason::Released => "the tests are over",
            EndReason::Failure => "runtime failure",
        }
    }
}

/// The summary of a run (also the `--stats` JSON).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunSummary {
    /// True when the environment's whole task was done (BW4T: the sequence delivered).
    pub completed: bool,
    pub end: EndReason,
    /// Environment ticks (rounds when there is no environment).
    pub ticks: u64,
    /// Lock-step rounds run.
    pub rounds: u64,
    pub deliveries: Deliveries,
    /// Messages delivered or dropped (one per receiver).
    pub messages: u64,
    pub seed: u64,
    pub map: Option<String>,
    /// Per agent, by name.
    pub agents: BTreeMap<String, AgentStats>,
    /// The environment's own statistics, if there is one.
    pub env: Option<serde_json::Value>,
    /// Conversations, when followed (`--stats`, `--comm`, `--trace-sessions`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sessions: Option<crate::clamr::session::SessionStats>,
    /// The transport's figures (messages lost, frames), when not the plain in-process one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub comm: Option<serde_json::Value>,
}

impl RunSummary {
    /// The summary as JSON (for `--stats`).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }

    /// The part of the summary that does not depend on stepping idle agents (for the trace).
    pub fn trace_json(&self) -> serde_json::Value {
        let errors: BTreeMap<&String, &String> = self
            .agents
            .iter()
            .filter_map(|(n, a)| a.error.as_ref().map(|e| (n, e)))
            .collect();
        serde_json::json!({
            "completed": self.completed,
            "end": self.end,
            "ticks": self.ticks,
            "rounds": self.rounds,
            "deliveries": self.deliveries,
            "messages": self.messages,
            "errors": errors,
        })
    }
}
