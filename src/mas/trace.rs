//! The run trace: JSON lines, one object per line, format documented in
//! `docs/trace-format.md`. Every record carries a `type`; records of a round carry `round` and
//! `tick`. Nothing timing-dependent (wall time, worker count) is written.

use crate::agent::{Event, Message};
use crate::env::ActionResult;
use crate::mas::vocabulary;
use serde_json::{json, Value};
use std::io::Write;

/// The trace format's name and version (in the header line).
pub const FORMAT: &str = "goal-trace";
/// Bumped on any incompatible change of field names or meanings.
pub const VERSION: u32 = 1;

/// One launched agent as listed in the header.
#[derive(Clone, Debug)]
pub struct AgentInfo {
    pub name: String,
    pub file: String,
    pub entity: Option<String>,
}

/// Writes trace records to a sink; write errors are remembered and reported once at the end.
pub struct TraceWriter {
    out: Box<dyn Write + Send>,
    error: Option<String>,
}

impl TraceWriter {
    /// A writer to `out` (buffer it: a record is one `write` call per line).
    pub fn new(out: Box<dyn Write + Send>) -> TraceWriter {
        TraceWriter { out, error: None }
    }

    fn line(&mut self, v: Value) {
        if self.error.is_some() {
            return;
        }
        let mut s = v.to_string();
        s.push('\n');
        if let Err(e) = self.out.write_all(s.as_bytes()) {
            self.error = Some(e.to_string());
        }
    }

    /// The header: format, version, system file, environment, seed, map and agents.
    pub fn header(
        &mut self,
        file: &str,
        env: Option<&str>,
        seed: u64,
        map: Option<&str>,
        agents: &[AgentInfo],
    ) {
        let agents: Vec<Value> = agents
            .iter()
            .map(|a| json!({"name": a.name, "file": a.file, "entity": a.entity}))
            .collect();
        self.line(json!({
            "type": "header",
            "format": FORMAT,
            "version": VERSION,
            "file": file,
            "env": env,
            "seed": seed,
            "map": map,
            "agents": agents,
        }));
    }

    /// One agent cycle's events (the `cycle_start` marker is left out: cycle numbers depend on
    /// whether idle agents are stepped).
    pub fn cycle(&mut self, round: u64, tick: u64, agent: &str, events: &[Event]) {
        let events: Vec<Value> = events
            .iter()
            .filter(|e| !matches!(e, Event::CycleStart { .. }))
            .map(|e| serde_json::to_value(e).unwrap_or(Value::Null))
            .collect();
        self.line(json!({
            "type": "cycle",
            "round": round,
            "tick": tick,
            "agent": agent,
            "events": events,
        }));
    }

    /// An environment action handed to the environment and its result.
    pub fn action(
        &mut self,
        round: u64,
        tick: u64,
        agent: &str,
        entity: &str,
        action: &str,
        result: &ActionResult,
    ) {
        let (r, reason) = match result {
            ActionResult::Ok => ("ok", None),
            ActionResult::Failed(m) => ("failed", Some(m.as_str())),
        };
        self.line(json!({
            "type": "action",
            "round": round,
            "tick": tick,
            "agent": agent,
            "entity": entity,
            "action": action,
            "result": r,
            "reason": reason,
        }));
    }

    /// A message routed to its receiver (delivered at the next round).
    pub fn message(&mut self, round: u64, tick: u64, m: &Message, delivered: bool) {
        let r = vocabulary::read(&m.sender, &m.content);
        self.line(json!({
            "type": "message",
            "round": round,
            "tick": tick,
            "from": m.sender,
            "to": m.receiver,
            "content": r.logical_form,
            "act": r.act,
            "english": r.english,
            "delivered": delivered,
        }));
    }

    /// A runtime warning about an agent (e.g. an action without an entity).
    pub fn warning(&mut self, round: u64, tick: u64, agent: &str, message: &str) {
        self.line(json!({
            "type": "warning",
            "round": round,
            "tick": tick,
            "agent": agent,
            "message": message,
        }));
    }

    /// A record of another kind (`session`, `network`: see `docs/trace-format.md`) with `fields`.
    pub fn record(&mut self, kind: &str, round: u64, tick: u64, fields: Value) {
        let mut v = json!({"type": kind, "round": round, "tick": tick});
        if let (Some(o), Value::Object(f)) = (v.as_object_mut(), fields) {
            o.extend(f);
        }
        self.line(v);
    }

    /// The last line: why the run ended and its summary.
    pub fn end(&mut self, summary: Value) {
        let mut v = json!({"type": "end"});
        if let (Some(o), Value::Object(s)) = (v.as_object_mut(), summary) {
            o.extend(s);
        }
        self.line(v);
    }

    /// Flushes and returns the first write error, if any.
    pub fn finish(mut self) -> Result<(), String> {
        if self.error.is_none() {
            if let Err(e) = self.out.flush() {
                self.error = Some(e.to_string());
            }
        }
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}
