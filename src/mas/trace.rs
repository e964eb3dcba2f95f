//! The run trace: JSON lines, one object per line, format documented in
//! `docs/trace-format.md`. Every record carries a `type`; records of a round carry `round` and
//! `tick`. Nothing timing-dependent (wall time, worker count) is written.

use crate::agent::{Event, Message};
use crate::env::ActionResult;
use crate::mas::vocabulary;
use serde_json::{json, Map, Value};
use std::collections::BTreeMap;
use std::io::Write;

/// The trace format's name and version (in the header line).
pub const FORMAT: &str = "goal-trace";
/// Bumped on any incompatible change of field names or meanings.
pub const VERSION: u32 = 2;

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
    /// The world as last written (flattened), so `world` records carry only changes.
    scene: BTreeMap<String, Value>,
}

/// Levels of a scene flattened into paths (`robots/Bot1/pos`): deeper values are written whole.
const SCENE_DEPTH: usize = 3;

/// `v` flattened into `out` as `path -> leaf` (objects down to [`SCENE_DEPTH`] levels; arrays
/// and scalars are leaves). Iterative: the stack holds at most `SCENE_DEPTH` levels of objects.
fn flatten(v: &Value, out: &mut BTreeMap<String, Value>) {
    let mut stack: Vec<(String, &Value, usize)> = vec![(String::new(), v, 0)];
    while let Some((path, v, depth)) = stack.pop() {
        match v {
            Value::Object(o) if depth < SCENE_DEPTH => {
                for (k, x) in o {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}/{k}")
                    };
                    stack.push((p, x, depth + 1));
                }
            }
            _ => {
                out.insert(path, v.clone());
            }
        }
    }
}

impl TraceWriter {
    /// A writer to `out` (buffer it: a record is one `write` call per line).
    pub fn new(out: Box<dyn Write + Send>) -> TraceWriter {
        TraceWriter {
            out,
            error: None,
            scene: BTreeMap::new(),
        }
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

    /// The header: format, version, system file, environment, seed, map, agents, and the run
    /// options a rerun needs (`RunOptions::replay_json`).
    pub fn header(
        &mut self,
        file: &str,
        env: Option<&str>,
        seed: u64,
        map: Option<&str>,
        agents: &[AgentInfo],
        options: Value,
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
            "options": options,
        }));
    }

    /// The environment's fixed layout (the map), once, after the header.
    pub fn map(&mut self, layout: Value) {
        self.line(json!({"type": "map", "layout": layout}));
    }

    /// The world at the start of tick `tick` (after round `round`; round 0: the initial world):
    /// only what changed since the last `world` record, as `set` (path to new value) and
    /// `unset` (paths gone). Nothing is written when nothing changed.
    pub fn world(&mut self, round: u64, tick: u64, scene: &Value) {
        let mut now = BTreeMap::new();
        flatten(scene, &mut now);
        let mut set = Map::new();
        for (k, v) in &now {
            if self.scene.get(k) != Some(v) {
                set.insert(k.clone(), v.clone());
            }
        }
        let unset: Vec<&String> = self
            .scene
            .keys()
            .filter(|k| !now.contains_key(*k))
            .collect();
        if set.is_empty() && unset.is_empty() {
            return;
        }
        let v = json!({
            "type": "world",
            "round": round,
            "tick": tick,
            "set": set,
            "unset": unset,
        });
        self.line(v);
        self.scene = now;
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

    /// A person's request for an entity, taken before the environment's tick of round
    /// `round`: applied (`ok`) or refused (with the environment's reason).
    pub fn input(
        &mut self,
        round: u64,
        tick: u64,
        input: &crate::mas::input::Input,
        result: &Result<(), String>,
    ) {
        let (r, reason) = match result {
            Ok(()) => ("ok", None),
            Err(m) => ("refused", Some(m.as_str())),
        };
        self.line(json!({
            "type": "input",
            "round": round,
            "tick": tick,
            "entity": input.entity,
            "request": input.request_text(),
            "result": r,
            "reason": reason,
        }));
    }

    /// A message routed to its receiver (delivered at the next round).
    pub fn message(&mut self, round: u64, tick: u64, m: &Message, delivered: bool) {
        let r = vocabulary::read(m.sender.name(), &m.content);
        self.line(json!({
            "type": "message",
            "round": round,
            "tick": tick,
            "from": m.sender.name(),
            "to": m.receiver.name(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::{Arc, Mutex};

    #[derive(Clone, Default)]
    struct Sink(Arc<Mutex<Vec<u8>>>);
    impl Write for Sink {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn world_records_carry_only_changes() {
        let sink = Sink::default();
        let mut t = TraceWriter::new(Box::new(sink.clone()));
        let a = json!({"robots": {"Bot1": {"pos": [1.0, 2.0], "path": [[3.0, 4.0]]}},
                       "blocks": {"7": {"color": "Red"}}, "sequence_index": 0});
        t.world(0, 0, &a);
        t.world(1, 1, &a);
        let b = json!({"robots": {"Bot1": {"pos": [1.5, 2.0], "path": [[3.0, 4.0]]}},
                       "blocks": {}, "sequence_index": 1});
        t.world(2, 2, &b);
        t.finish().unwrap();
        let text = String::from_utf8(sink.0.lock().unwrap().clone()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2, "an unchanged world writes nothing: {text}");
        assert_eq!(
            lines[0],
            r#"{"round":0,"set":{"blocks/7/color":"Red","robots/Bot1/path":[[3.0,4.0]],"robots/Bot1/pos":[1.0,2.0],"sequence_index":0},"tick":0,"type":"world","unset":[]}"#
        );
        assert_eq!(
            lines[1],
            r#"{"round":2,"set":{"robots/Bot1/pos":[1.5,2.0],"sequence_index":1},"tick":2,"type":"world","unset":["blocks/7/color"]}"#
        );
    }
}
