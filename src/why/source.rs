//! A recorded run as `goal why` reads it: the trace header (system file, seed, map, agents,
//! options), how many ticks the run lasted (its end record), and one cycle's recorded firings
//! to check the rerun against.

use super::WhyError;
use crate::mas::environment::env_params;
use crate::mas::input::InputLog;
use crate::mas::run::{Quiet, RunOptions};
use crate::mas::trace::{FORMAT, VERSION};
use crate::mas::{default_team, system, MasSystem};
use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};

/// The system file a trace of the built-in default team names.
const BUILT_IN: &str = "<built-in>/bw4t.mas2g";

/// A trace file and what its header and end record say.
pub(super) struct TraceRun {
    path: PathBuf,
    header: Value,
    agents: Vec<String>,
    /// Ticks the run lasted (from the end record; `None` when the run did not finish writing).
    ticks: Option<u64>,
    /// People's requests the run took (its `input` records).
    pub(super) inputs: InputLog,
}

fn bad(path: &Path, what: &str) -> WhyError {
    WhyError::Trace(format!("{}: {what}", path.display()))
}

/// The lines of the trace at `path`.
fn lines(path: &Path) -> Result<impl Iterator<Item = std::io::Result<String>>, WhyError> {
    let f = std::fs::File::open(path).map_err(|e| bad(path, &format!("cannot read it: {e}")))?;
    Ok(BufReader::new(f).lines())
}

impl TraceRun {
    /// Reads the header and the end record of the trace at `path`.
    pub(super) fn open(path: &Path) -> Result<TraceRun, WhyError> {
        let mut header: Option<Value> = None;
        let mut last = String::new();
        let inputs = InputLog::new();
        for (n, line) in lines(path)?.enumerate() {
            let line = line.map_err(|e| bad(path, &format!("cannot read it: {e}")))?;
            if line.contains("\"type\":\"input\"") {
                let v: Value = serde_json::from_str(&line).unwrap_or(Value::Null);
                inputs
                    .add_record(&v)
                    .map_err(|e| bad(path, &format!("line {}: {e}", n + 1)))?;
            }
            if header.is_none() {
                let v: Value = serde_json::from_str(&line)
                    .map_err(|_| bad(path, "not a goal trace (its first line is not JSON)"))?;
                header = Some(v);
            } else if !line.trim().is_empty() {
                last = line;
            }
        }
        let header = header.ok_or_else(|| bad(path, "the file is empty, not a goal trace"))?;
        if header["type"] != "header" || header["format"] != FORMAT {
            return Err(bad(path, "not a goal trace (no goal-trace header line)"));
        }
        let version = header["version"].as_u64().unwrap_or(0);
        if version == 0 || version > u64::from(VERSION) {
            return Err(bad(
                path,
                &format!(
                    "trace format version {version}; this goal reads versions 1 to {VERSION} \
                     (rerun the system with this goal to make a new trace)"
                ),
            ));
        }
        let agents = header["agents"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|x| x["name"].as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default();
        let end: Value = serde_json::from_str(&last).unwrap_or(Value::Null);
        let ticks = (end["type"] == "end")
            .then(|| end["ticks"].as_u64())
            .flatten();
        Ok(TraceRun {
            path: path.to_path_buf(),
            header,
            agents,
            ticks,
            inputs,
        })
    }

    /// The system the header names, loaded again, and the options of the run.
    pub(super) fn system(&self) -> Result<(MasSystem, RunOptions), WhyError> {
        let file = self.header["file"].as_str().unwrap_or_default();
        let loaded = if file == BUILT_IN {
            default_team::system()
        } else if file.ends_with(".goal") {
            system::load_agent(Path::new(file))
        } else {
            system::load_mas(Path::new(file))
        };
        let sys = loaded.map_err(|ps| {
            let text: String = ps.iter().map(|p| p.render()).collect();
            WhyError::Load(format!(
                "{text}the system of trace {} ({file}) cannot be loaded; run goal why from the \
                 directory the run was started in",
                self.path.display()
            ))
        })?;
        let mut opts = RunOptions {
            seed: self.header["seed"].as_u64(),
            // The end record tells where the run ended.
            max_ticks: u64::MAX,
            ..RunOptions::default()
        }
        .with_replay(&self.header["options"]);
        // The map as the header names it, unless the system's own (a path relative to where
        // the run was started would not be found from elsewhere).
        let own = sys
            .env
            .as_ref()
            .map(|s| env_params(s, &RunOptions::default(), &mut Quiet).2);
        if let Some(m) = self.header["map"].as_str() {
            if own.as_deref() != Some(m) {
                opts.map = Some(m.to_string());
            }
        }
        Ok((sys, opts))
    }

    /// Checks the question against the header and end record (no rerun needed to refuse).
    pub(super) fn check(&self, agent: &str, tick: u64) -> Result<(), WhyError> {
        if !self.agents.iter().any(|a| a == agent) {
            return Err(WhyError::UnknownAgent {
                agent: agent.to_string(),
                known: self.agents.clone(),
            });
        }
        match self.ticks {
            Some(ticks) if tick >= ticks => Err(WhyError::PastEnd { tick, ticks }),
            _ => Ok(()),
        }
    }

    /// Whether the trace's cycle of `agent` at `tick` fired the same rules with the same
    /// bindings as `fired` (`None` when the trace recorded no rule events for it).
    pub(super) fn matches(
        &self,
        agent: &str,
        tick: u64,
        fired: &[(String, String)],
    ) -> Result<Option<bool>, WhyError> {
        let name = serde_json::to_string(agent).unwrap_or_default();
        for line in lines(&self.path)? {
            let Ok(line) = line else { break };
            if !line.contains("\"cycle\"") || !line.contains(&name) {
                continue;
            }
            let Ok(v) = serde_json::from_str::<Value>(&line) else {
                continue;
            };
            if v["type"] != "cycle" || v["agent"] != agent || v["tick"].as_u64() != Some(tick) {
                continue;
            }
            let events = v["events"].as_array().cloned().unwrap_or_default();
            if !events.iter().any(|e| e["event"] == "rule_evaluated") {
                return Ok(None);
            }
            let recorded: Vec<(String, String)> = events
                .iter()
                .filter(|e| e["event"] == "rule_fired")
                .map(|e| {
                    let s = |k: &str| e[k].as_str().unwrap_or_default().to_string();
                    (s("rule"), s("bindings"))
                })
                .collect();
            return Ok(Some(recorded == fired));
        }
        // The trace has no cycle of the agent at that tick, the rerun has one.
        Ok(Some(false))
    }
}
