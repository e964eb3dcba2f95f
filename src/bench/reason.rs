//! Single-agent reasoning benchmarks: `fib` (achievement sub-goals, after Jason's so-fib) and
//! `knowledge` (recursive rules over 1,000 beliefs). The agent is stepped directly, without
//! the multi-agent runtime; output is checked against values computed here.

use super::{file, rss, set_fact, Params, Report};
use crate::agent::{Agent, AgentConfig, PerceptTypes, Program, TraceLevel};
use std::sync::Arc;
use std::time::Instant;

/// Compiles `text` and creates one agent named `name` that records no trace.
pub fn agent(
    file_name: &str,
    text: &str,
    name: &str,
    percept_types: Arc<PerceptTypes>,
) -> Result<Agent, String> {
    let prog = Program::from_source(file_name, text)
        .map_err(|ds| ds.iter().map(|d| d.render(text)).collect::<String>())?;
    let config = AgentConfig {
        seed: 1,
        trace: TraceLevel::Off,
        percept_types,
        ..AgentConfig::default()
    };
    Ok(Agent::new(prog, name, config))
}

/// Steps `agent` without input until it stops or `max` cycles ran; the printed lines, the
/// number of cycles and an error text when the agent failed or did not stop.
fn run_alone(agent: &mut Agent, max: u64) -> (Vec<String>, u64, Option<String>) {
    let mut printed = Vec::new();
    for n in 1..=max {
        let out = agent.step(&[], &[]);
        printed.extend(out.printed);
        if let Some(reason) = out.stopped {
            let failure = match reason {
                crate::agent::StopReason::MainExited => None,
                crate::agent::StopReason::Error(e) => Some(format!("runtime error: {e}")),
            };
            return (printed, n, failure);
        }
    }
    (
        printed,
        max,
        Some(format!("did not stop within {max} cycles")),
    )
}

/// `fib(top)` with 64-bit wrap-around (the agent's integers overflow into errors long before).
fn fib_value(n: u64) -> i64 {
    let (mut a, mut b) = (0i64, 1i64);
    for _ in 0..n {
        let c = a.wrapping_add(b);
        a = b;
        b = c;
    }
    a
}

/// `fib`: `top` (default 30) and `reps` (default 1,000) rounds of Fibonacci sub-goals.
pub fn fib(params: &Params) -> Result<Report, String> {
    let top = params.get("top", 30)?;
    let reps = params.get("reps", 1000)?;
    if top > 90 {
        return Err("top must be at most 90 (fib(91) overflows 64 bits)".into());
    }
    let t0 = Instant::now();
    let text = set_fact(file("fib.goal")?, "top(30)", &format!("top({top})"))?;
    let text = set_fact(&text, "reps(1000)", &format!("reps({reps})"))?;
    let text = set_fact(&text, "round(1001)", &format!("round({})", reps + 1))?;
    let mut a = agent("agents/bench/fib.goal", &text, "fib", Arc::default())?;
    let create = t0.elapsed();
    let t1 = Instant::now();
    // Each round adopts and achieves top + 1 goals in about two cycles each.
    let (printed, cycles, mut failure) = run_alone(&mut a, reps * (4 * top + 10) + 100);
    let run = t1.elapsed();
    let v = fib_value(top);
    let wanted: Vec<String> = (1..=reps).map(|r| format!("fib({r},{top},{v})")).collect();
    if failure.is_none() && printed != wanted {
        let first = printed.first().cloned().unwrap_or_default();
        failure = Some(format!(
            "printed {} lines (first `{first}`), expected {} lines `fib(R,{top},{v})`",
            printed.len(),
            reps
        ));
    }
    let goals = reps * (top + 1);
    Ok(Report {
        name: "fib".into(),
        config: format!("top={top} reps={reps}"),
        failure,
        agents: 1,
        workers: 1,
        create,
        run,
        count: goals,
        unit: "sub-goals",
        cycles,
        cpu: None,
        peak_rss_kib: rss::peak_kib(),
        extra: vec![(
            "per goal".into(),
            format!("{:.3} µs", run.as_secs_f64() * 1e6 / goals.max(1) as f64),
        )],
        targets: Vec::new(),
    })
}

/// The number of `ancestor(X, A)` answers for `parent(I, I // 2)`, I = 2..size.
fn ancestor_count(size: u64) -> u64 {
    (2..=size).map(|i| u64::from(63 - i.leading_zeros())).sum()
}

/// `knowledge`: `queries` (default 100) evaluations of every ancestor over `size` (default
/// 1,000) facts.
pub fn knowledge(params: &Params) -> Result<Report, String> {
    let size = params.get("size", 1000)?;
    let queries = params.get("queries", 100)?;
    let t0 = Instant::now();
    let text = set_fact(
        file("knowledge.goal")?,
        "size(1000)",
        &format!("size({size})"),
    )?;
    let text = set_fact(&text, "queries(100)", &format!("queries({queries})"))?;
    let mut a = agent(
        "agents/bench/knowledge.goal",
        &text,
        "knowledge",
        Arc::default(),
    )?;
    let create = t0.elapsed();
    let t1 = Instant::now();
    let (printed, cycles, mut failure) = run_alone(&mut a, queries + 10);
    let run = t1.elapsed();
    let n = ancestor_count(size);
    let wanted = vec![format!("ancestors([{n}])")];
    if failure.is_none() && printed != wanted {
        failure = Some(format!("printed {printed:?}, expected {wanted:?}"));
    }
    let answers = queries * n;
    Ok(Report {
        name: "knowledge".into(),
        config: format!("size={size} queries={queries}"),
        failure,
        agents: 1,
        workers: 1,
        create,
        run,
        count: answers,
        unit: "answers",
        cycles,
        cpu: None,
        peak_rss_kib: rss::peak_kib(),
        extra: vec![(
            "per query".into(),
            format!(
                "{:.3} ms (all ancestors of {size} nodes)",
                run.as_secs_f64() * 1e3 / queries as f64
            ),
        )],
        targets: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_values() {
        assert_eq!(fib_value(10), 55);
        assert_eq!(fib_value(30), 832_040);
        // 2,3 -> 1 each; 4..7 -> 2 each; 8 -> 3.
        assert_eq!(ancestor_count(8), 2 + 8 + 3);
    }
}
