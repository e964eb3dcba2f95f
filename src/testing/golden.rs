//! Golden traces: a `goal run --trace` file kept as the expected behaviour of a system. A check
//! runs the system again with the settings recorded in the trace's header (seed, map, and the
//! tick limit when the recorded run hit it) and compares the traces record by record; the
//! first difference is described in words (round, agent, expected, actual).

use crate::mas::run::{Quiet, RunOptions};
use crate::mas::trace::TraceWriter;
use crate::mas::{system, MasSystem};
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// How to run the system of a golden trace (each field overrides the header's value).
#[derive(Clone, Debug, Default)]
pub struct GoldenOptions {
    /// The `.mas2g` or `.goal` file; default: the file named in the header.
    pub system: Option<PathBuf>,
    pub seed: Option<u64>,
    pub map: Option<String>,
    pub robots: Option<usize>,
    pub max_ticks: Option<u64>,
}

/// The first difference between a golden trace and a new run.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// 1-based line of the trace.
    pub line: usize,
    pub round: Option<u64>,
    pub agent: Option<String>,
    pub expected: String,
    pub actual: String,
}

impl Difference {
    /// The difference in readable form.
    pub fn to_text(&self) -> String {
        let mut at = format!("line {}", self.line);
        if let Some(r) = self.round {
            at.push_str(&format!(", round {r}"));
        }
        if let Some(a) = &self.agent {
            at.push_str(&format!(", agent {a}"));
        }
        format!(
            "the run differs from the golden trace at {at}:\n  expected: {}\n  actual:   {}\n",
            self.expected, self.actual
        )
    }
}

/// A `Write` into shared memory (the trace of a run made for comparison).
#[derive(Clone, Default)]
struct Buffer(Arc<Mutex<Vec<u8>>>);

impl Write for Buffer {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Runs `system` as `goal run --trace` would and returns the trace text.
pub fn record(system: &MasSystem, opts: &RunOptions) -> Result<String, String> {
    let buf = Buffer::default();
    let writer = TraceWriter::new(Box::new(buf.clone()));
    let opts = RunOptions {
        trace_rules: true,
        ..opts.clone()
    };
    let (_, err) = crate::mas::run(system, &opts, Some(writer), &mut Quiet)
        .map_err(|ps| ps.iter().map(|p| p.render()).collect::<String>())?;
    if let Some(e) = err {
        return Err(e);
    }
    let bytes = buf.0.lock().unwrap_or_else(|e| e.into_inner()).clone();
    String::from_utf8(bytes).map_err(|e| e.to_string())
}

fn load(path: &Path) -> Result<MasSystem, String> {
    let single = path.extension().and_then(|e| e.to_str()) == Some("goal");
    let loaded = if single {
        system::load_agent(path)
    } else {
        system::load_mas(path)
    };
    loaded.map_err(|ps| ps.iter().map(|p| p.render()).collect())
}

/// Checks a new run against the golden trace `golden`: `Ok(None)` when they are the same.
pub fn check(golden: &Path, opts: &GoldenOptions) -> Result<Option<Difference>, String> {
    let expected = std::fs::read_to_string(golden)
        .map_err(|e| format!("cannot read {}: {e}", golden.display()))?;
    let header: Value = expected
        .lines()
        .next()
        .and_then(|l| serde_json::from_str(l).ok())
        .filter(|h: &Value| h["type"] == "header")
        .ok_or_else(|| format!("{} is not a goal trace (no header line)", golden.display()))?;
    let path = match (&opts.system, header["file"].as_str()) {
        (Some(p), _) => p.clone(),
        (None, Some(f)) => PathBuf::from(f),
        (None, None) => return Err("the trace header names no system file".into()),
    };
    let sys = load(&path)?;
    let end = expected
        .lines()
        .last()
        .and_then(|l| serde_json::from_str::<Value>(l).ok());
    let recorded_limit = end
        .as_ref()
        .filter(|e| e["end"] == "tick_limit")
        .and_then(|e| e["ticks"].as_u64());
    let base = RunOptions::default();
    let run = RunOptions {
        seed: opts.seed.or(header["seed"].as_u64()),
        map: opts
            .map
            .clone()
            .or(header["map"].as_str().map(str::to_string))
            .filter(|_| sys.env.is_some()),
        robots: opts.robots,
        max_ticks: opts.max_ticks.or(recorded_limit).unwrap_or(base.max_ticks),
        ..base
    };
    let actual = record(&sys, &run)?;
    Ok(compare(&expected, &actual))
}

/// The header without file paths (they depend on where the run was started).
fn header_key(v: &Value) -> Value {
    let agents: Vec<Value> = v["agents"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|x| serde_json::json!([x["name"], x["entity"]]))
                .collect()
        })
        .unwrap_or_default();
    serde_json::json!([
        v["format"],
        v["version"],
        v["env"],
        v["seed"],
        v["map"],
        agents
    ])
}

/// Compares two traces record by record; the first difference, if any.
pub fn compare(expected: &str, actual: &str) -> Option<Difference> {
    let mut e_lines = expected.lines();
    let mut a_lines = actual.lines();
    let mut line = 0;
    loop {
        line += 1;
        let (e, a) = (e_lines.next(), a_lines.next());
        let (e, a) = match (e, a) {
            (None, None) => return None,
            (e, a) => (
                e.map(|l| serde_json::from_str::<Value>(l).unwrap_or(Value::String(l.into()))),
                a.map(|l| serde_json::from_str::<Value>(l).unwrap_or(Value::String(l.into()))),
            ),
        };
        let same = match (&e, &a) {
            (Some(x), Some(y)) if line == 1 => header_key(x) == header_key(y),
            (Some(x), Some(y)) => x == y,
            _ => false,
        };
        if !same {
            return Some(describe_difference(line, e.as_ref(), a.as_ref()));
        }
    }
}

fn describe_difference(line: usize, e: Option<&Value>, a: Option<&Value>) -> Difference {
    let first = e.or(a).cloned().unwrap_or(Value::Null);
    let round = first["round"].as_u64();
    let agent = first["agent"]
        .as_str()
        .or(first["from"].as_str())
        .map(str::to_string);
    let (expected, actual) = match (e, a) {
        (Some(x), Some(y))
            if x["type"] == "cycle" && y["type"] == "cycle" && x["agent"] == y["agent"] =>
        {
            cycle_difference(x, y)
        }
        _ => (
            e.map_or("the end of the trace".into(), describe_record),
            a.map_or("the end of the trace".into(), describe_record),
        ),
    };
    Difference {
        line,
        round,
        agent,
        expected,
        actual,
    }
}

/// The first differing event of two cycles of the same agent.
fn cycle_difference(x: &Value, y: &Value) -> (String, String) {
    let empty = Vec::new();
    let xs = x["events"].as_array().unwrap_or(&empty);
    let ys = y["events"].as_array().unwrap_or(&empty);
    let i = xs.iter().zip(ys).take_while(|(p, q)| p == q).count();
    let show = |v: Option<&Value>| match v {
        Some(ev) => format!("event {}: {}", i + 1, describe_event(ev)),
        None => format!("no event {} (the cycle ends there)", i + 1),
    };
    if xs.get(i).is_none() && ys.get(i).is_none() {
        // Same events: the round or tick differs.
        return (describe_record(x), describe_record(y));
    }
    (show(xs.get(i)), show(ys.get(i)))
}

fn describe_event(ev: &Value) -> String {
    let f = |k: &str| ev[k].as_str().unwrap_or("?").to_string();
    match ev["event"].as_str() {
        Some("rule_fired") => return format!("rule {} fired with {}", f("rule"), f("bindings")),
        Some("rule_evaluated") => {
            return format!("rule {} evaluated: {} answers", f("rule"), ev["answers"])
        }
        _ => {}
    }
    let name = ev["event"].as_str().unwrap_or("?").replace('_', " ");
    let fields: Vec<String> = ev
        .as_object()
        .map(|o| {
            o.iter()
                .filter(|(k, _)| *k != "event")
                .map(|(_, v)| match v {
                    Value::String(s) => s.clone(),
                    other => other.to_string(),
                })
                .collect()
        })
        .unwrap_or_default();
    if fields.is_empty() {
        name
    } else {
        format!("{name} {}", fields.join(" "))
    }
}

fn describe_record(v: &Value) -> String {
    let s = |k: &str| v[k].as_str().unwrap_or("?").to_string();
    let at = match (v["round"].as_u64(), v["tick"].as_u64()) {
        (Some(r), Some(t)) => format!(" (round {r}, tick {t})"),
        _ => String::new(),
    };
    match v["type"].as_str() {
        Some("cycle") => {
            let n = v["events"].as_array().map_or(0, Vec::len);
            format!("a cycle of {} with {n} events{at}", s("agent"))
        }
        Some("action") => format!("{} does {} ({}){at}", s("agent"), s("action"), s("result")),
        Some("message") => format!("{} sends {} to {}{at}", s("from"), s("content"), s("to")),
        Some("warning") => format!("warning for {}: {}{at}", s("agent"), s("message")),
        Some("end") => format!(
            "the run ends ({}) after {} ticks",
            s("end"),
            v["ticks"].as_u64().unwrap_or(0)
        ),
        _ => v.to_string(),
    }
}
