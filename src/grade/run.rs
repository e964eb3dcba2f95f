//! One graded run: a submission's `.mas2g` on one map, robot count and seed, as a child
//! `goal run ... --stats FILE` process, and what its exit code and statistics say.

use super::child::{self, ChildEnd, ChildLimits};
use super::GradeOptions;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One run to do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunSpec {
    /// Index of the submission in the class.
    pub submission: usize,
    pub map: String,
    pub robots: usize,
    pub seed: u64,
}

/// How a run ended, from the child's exit code (docs/exit-codes.md) and statistics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The sequence was delivered (exit 0).
    Completed,
    /// Ended by itself without completing, e.g. every agent stopped (exit 0).
    Ended,
    /// Hit the tick or time limit (exit 3).
    Limit,
    /// An agent stopped on a runtime error (exit 4).
    AgentError,
    /// Over the memory cap (exit 5, or out of address space).
    Memory,
    /// The system could not be loaded or the environment failed (exit 1).
    Failed,
    /// Still running after the time limit and the grace period: killed.
    Killed,
    /// Ended by a signal or an unknown exit code, without statistics.
    Crashed,
}

impl Outcome {
    /// The name used in tables (`agent_error`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::Ended => "ended",
            Outcome::Limit => "limit",
            Outcome::AgentError => "agent_error",
            Outcome::Memory => "memory",
            Outcome::Failed => "failed",
            Outcome::Killed => "killed",
            Outcome::Crashed => "crashed",
        }
    }
}

/// The figures of one finished run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunResult {
    pub submission: String,
    pub map: String,
    pub robots: usize,
    pub seed: u64,
    pub outcome: Outcome,
    /// The child's exit code (`None`: ended by a signal).
    pub exit_code: Option<i32>,
    pub ticks: u64,
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
    pub messages: u64,
    /// Agents that stopped on a runtime error.
    pub agent_errors: u64,
    /// The first error (an agent's, or the first line of the child's error output).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Team deliveries (tournament matches only): `(right, wrong)` per team.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub teams: Vec<(u64, u64)>,
    /// Wall time in seconds: depends on the machine, never part of compared tables.
    pub wall_seconds: f64,
}

/// The child's command line options shared by runs and matches.
pub fn limit_args(cmd: &mut Command, spec: &RunSpec, opts: &GradeOptions, stats: &Path) {
    cmd.arg("--map")
        .arg(map_arg(&spec.map))
        .arg("--robots")
        .arg(spec.robots.to_string())
        .arg("--seed")
        .arg(spec.seed.to_string())
        .arg("--max-ticks")
        .arg(opts.max_ticks.to_string())
        .arg("--time-limit")
        .arg(opts.time_limit.as_secs_f64().to_string())
        .arg("--max-memory")
        .arg(opts.max_memory_mib.to_string())
        .arg("--stats")
        .arg(stats);
}

/// The map as the child (running in the submission's directory) must be told it: a map
/// file named relative to the working directory becomes absolute; built-in names stay.
fn map_arg(map: &str) -> std::ffi::OsString {
    if crate::bw4t::map::builtin(map).is_some() {
        return map.into();
    }
    match std::fs::canonicalize(map) {
        Ok(p) if p.is_file() => p.into_os_string(),
        _ => map.into(),
    }
}

/// The limits of a child that runs for at most `time` (its own limit) plus the grace period.
pub fn child_limits(opts: &GradeOptions, time: std::time::Duration) -> ChildLimits {
    let mib = opts.max_memory_mib.saturating_mul(1 << 20);
    ChildLimits {
        kill_after: time + opts.grace,
        // Headroom over the run's own cap: thread stacks and allocator arenas are reserved
        // address space, not used memory.
        address_space: Some(mib.saturating_mul(2).max(mib.saturating_add(1 << 30))),
    }
}

/// Runs `mas` as `spec` says and reads the result.
pub fn run_one(
    name: &str,
    mas: &Path,
    dir: &Path,
    spec: &RunSpec,
    opts: &GradeOptions,
    stats: PathBuf,
) -> RunResult {
    let mut cmd = Command::new(&opts.program);
    cmd.current_dir(dir)
        .arg("run")
        .arg(mas)
        .arg("--workers")
        .arg("1");
    limit_args(&mut cmd, spec, opts, &stats);
    finish(name, spec, cmd, opts, &stats)
}

/// Runs `cmd` under the limits and turns its end and its statistics file into a result.
pub fn finish(
    name: &str,
    spec: &RunSpec,
    cmd: Command,
    opts: &GradeOptions,
    stats: &Path,
) -> RunResult {
    let end = child::run(cmd, &child_limits(opts, opts.time_limit));
    let json = std::fs::read_to_string(stats)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok());
    let _ = std::fs::remove_file(stats);
    let mut r = RunResult {
        submission: name.to_string(),
        map: spec.map.clone(),
        robots: spec.robots,
        seed: spec.seed,
        outcome: Outcome::Crashed,
        exit_code: None,
        ticks: 0,
        deliveries_right: 0,
        deliveries_wrong: 0,
        messages: 0,
        agent_errors: 0,
        note: None,
        teams: Vec::new(),
        wall_seconds: 0.0,
    };
    match end {
        Ok(end) => {
            r.exit_code = end.code;
            r.wall_seconds = end.wall.as_secs_f64();
            r.outcome = outcome(&end, json.is_some());
            if let Some(j) = &json {
                read_stats(&mut r, j);
            }
            if r.note.is_none() && r.outcome != Outcome::Completed {
                r.note = first_error(&end);
            }
        }
        Err(e) => r.note = Some(e),
    }
    r
}

/// The outcome an exit says (see docs/exit-codes.md).
fn outcome(end: &ChildEnd, has_stats: bool) -> Outcome {
    if end.killed {
        return Outcome::Killed;
    }
    match end.code {
        Some(0) if has_stats => Outcome::Ended,
        Some(3) => Outcome::Limit,
        Some(4) => Outcome::AgentError,
        Some(5) => Outcome::Memory,
        Some(1) => Outcome::Failed,
        // An allocation refused under the address-space limit aborts the process.
        None if end.stderr.contains("memory allocation") => Outcome::Memory,
        _ => Outcome::Crashed,
    }
}

/// Copies the figures of a `--stats` summary into `r`.
fn read_stats(r: &mut RunResult, j: &serde_json::Value) {
    let n = |v: &serde_json::Value| v.as_u64().unwrap_or(0);
    r.ticks = n(&j["ticks"]);
    r.deliveries_right = n(&j["deliveries"]["right"]);
    r.deliveries_wrong = n(&j["deliveries"]["wrong"]);
    r.messages = n(&j["messages"]);
    if j["completed"].as_bool() == Some(true) && r.outcome == Outcome::Ended {
        r.outcome = Outcome::Completed;
    }
    if let Some(agents) = j["agents"].as_object() {
        let errors: Vec<String> = agents
            .iter()
            .filter_map(|(name, a)| a["error"].as_str().map(|e| format!("{name}: {e}")))
            .collect();
        r.agent_errors = errors.len() as u64;
        r.note = errors.into_iter().next().map(|e| one_line(&e));
    }
    if let Some(teams) = j["env"]["teams"].as_array() {
        r.teams = teams
            .iter()
            .map(|t| (n(&t["deliveries_right"]), n(&t["deliveries_wrong"])))
            .collect();
    }
}

/// The first line of the child's standard error that says `error`, else (for a run that
/// was killed or crashed) its last line.
fn first_error(end: &ChildEnd) -> Option<String> {
    let mut lines = end.stderr.lines().map(str::trim).filter(|l| !l.is_empty());
    let error = lines.clone().find(|l| l.starts_with("error"));
    let line = match error {
        Some(l) => l,
        None if end.killed || end.code.is_none() => lines.next_back()?,
        None => return None,
    };
    Some(one_line(line))
}

/// `text` on one line, at most 200 characters.
fn one_line(text: &str) -> String {
    let flat: String = text
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    match flat.char_indices().nth(200) {
        Some((i, _)) => format!("{}...", &flat[..i]),
        None => flat,
    }
}
