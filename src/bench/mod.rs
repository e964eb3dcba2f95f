//! Benchmarks against other agent platforms (`goal bench`): token rings, goal-heavy and
//! knowledge-heavy reasoning, percept load and idle-agent memory. Each benchmark runs ordinary
//! GOAL programs from `agents/bench/` (built into the binary) and returns a [`Report`] with
//! creation time, run time, throughput, peak RSS and whether the run finished correctly.

pub mod bufenv;
pub mod cpu;
pub mod idle;
pub mod instructions;
pub mod params;
pub mod reason;
pub mod report;
pub mod ring;
pub mod rss;

pub use params::Params;
pub use report::Report;

/// The benchmarks: name and one-line description, in the order `goal bench all` runs them.
pub const BENCHMARKS: &[(&str, &str)] = &[
    (
        "ring1",
        "500 agents in a ring, one token passed 500,000 times",
    ),
    (
        "ring50",
        "500 agents in a ring, 50 tokens passed 500,000 times each",
    ),
    (
        "fib",
        "one agent computing Fibonacci numbers through sub-goals (adopt/achieve)",
    ),
    (
        "knowledge",
        "one agent querying recursive rules over 1,000 facts",
    ),
    (
        "percepts",
        "one agent whose environment replaces 5,000 percepts per cycle",
    ),
    (
        "agents",
        "10,000 idle agents: creation time and memory per agent",
    ),
];

/// The agent files of the benchmarks (path under `agents/bench/`, text).
pub const FILES: &[(&str, &str)] = &[
    ("ring.goal", include_str!("../../agents/bench/ring.goal")),
    (
        "counter.goal",
        include_str!("../../agents/bench/counter.goal"),
    ),
    ("ring.mas2g", include_str!("../../agents/bench/ring.mas2g")),
    ("fib.goal", include_str!("../../agents/bench/fib.goal")),
    (
        "knowledge.goal",
        include_str!("../../agents/bench/knowledge.goal"),
    ),
    (
        "percepts.goal",
        include_str!("../../agents/bench/percepts.goal"),
    ),
    ("idle.goal", include_str!("../../agents/bench/idle.goal")),
];

/// The text of a benchmark agent file.
pub fn file(name: &str) -> Result<&'static str, String> {
    FILES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| format!("no benchmark file {name}"))
}

/// Replaces the single fact `old` (e.g. `hops(500000)`) of a program text; an error when the
/// text does not contain it exactly once (so a program edit cannot silently ignore a parameter).
pub fn set_fact(text: &str, old: &str, new: &str) -> Result<String, String> {
    match text.matches(old).count() {
        1 => Ok(text.replacen(old, new, 1)),
        n => Err(format!(
            "benchmark program: expected `{old}` once, found it {n} times"
        )),
    }
}

/// Runs benchmark `name` with `params` on `workers` worker threads; the report carries the
/// CPU time the process spent on it (unless the benchmark measured its own, as one that also
/// runs a comparison does).
pub fn run(name: &str, params: &Params, workers: usize) -> Result<Report, String> {
    let before = cpu::process_time();
    let mut report = run_named(name, params, workers)?;
    if report.cpu.is_none() {
        report.cpu = cpu::since(before);
    }
    Ok(report)
}

fn run_named(name: &str, params: &Params, workers: usize) -> Result<Report, String> {
    match name {
        "ring1" => ring::run("ring1", params, workers, 1),
        "ring50" => ring::ring50(params, workers),
        "fib" => reason::fib(params),
        "knowledge" => reason::knowledge(params),
        "percepts" => bufenv::run(params),
        "agents" => idle::run(params, workers),
        _ => Err(format!(
            "unknown benchmark `{name}`; known: {}",
            BENCHMARKS
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}
