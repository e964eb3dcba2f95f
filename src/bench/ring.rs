//! The token rings `ring1` and `ring50`: `agents/bench/ring.goal` agents named ring1 .. ringN
//! pass tokens to their successor; the agent receiving a token's last hop tells the counter
//! agent, which prints `all_arrived(T)` once every token has arrived. Run through the ordinary
//! runtime (`mas::run`): lock-step rounds, worker pool, idle-agent skipping.

use super::instructions::Counter;
use super::report::si;
use super::report::Target;
use super::{file, rss, set_fact, Params, Report};
use crate::agent::Message;
use crate::mas::run::{run as run_mas, Observer, RunOptions};
use crate::mas::system::{from_mas_text, Origin};
use crate::mas::EndReason;
use std::time::Instant;

/// Records what the run does that the benchmark checks.
#[derive(Default)]
struct Watch {
    started: Option<Instant>,
    /// The process's instruction count when the run started (creation left out).
    counter: Option<(Counter, Option<u64>)>,
    workers: usize,
    printed: Vec<String>,
    warnings: Vec<String>,
}

impl Observer for Watch {
    fn printed(&mut self, _agent: &str, line: &str) {
        self.printed.push(line.to_string());
    }
    fn message(&mut self, _round: u64, _m: &Message, _delivered: bool) {}
    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_string());
    }
    fn started(&mut self, _agents: usize, workers: usize) {
        self.workers = workers;
        if let Some((c, at)) = self.counter.as_mut() {
            *at = c.read();
        }
        self.started = Some(Instant::now());
    }
}

/// The ring programs for `size` agents, `tokens` tokens and `hops` hops per token, as files
/// (leaked once per run: `Origin::Embedded` wants static text).
fn files(
    size: u64,
    tokens: u64,
    hops: u64,
) -> Result<&'static [(&'static str, &'static str)], String> {
    let ring = file("ring.goal")?;
    let ring = set_fact(ring, "ring_size(500)", &format!("ring_size({size})"))?;
    let ring = set_fact(&ring, "tokens(1)", &format!("tokens({tokens})"))?;
    let ring = set_fact(&ring, "hops(500000)", &format!("hops({hops})"))?;
    let counter = set_fact(
        file("counter.goal")?,
        "tokens(1)",
        &format!("tokens({tokens})"),
    )?;
    let leak = |s: String| -> &'static str { Box::leak(s.into_boxed_str()) };
    let v = vec![("ring.goal", leak(ring)), ("counter.goal", leak(counter))];
    Ok(Box::leak(v.into_boxed_slice()))
}

/// Runs a token ring: `agents` (default 500) ring agents, `tokens` (default `tokens`) tokens,
/// `hops` (default 500,000) hops per token.
pub fn run(name: &str, params: &Params, workers: usize, tokens: u64) -> Result<Report, String> {
    let size = params.get("agents", 500)?;
    let tokens = params.get("tokens", tokens)?;
    let hops = params.get("hops", 500_000)?;
    if tokens > size {
        return Err(format!(
            "{tokens} tokens need at least as many agents (got {size})"
        ));
    }
    let t0 = Instant::now();
    let mas = set_fact(file("ring.mas2g")?, "ring[500]", &format!("ring[{size}]"))?;
    let system = from_mas_text(
        "agents/bench/ring.mas2g",
        &mas,
        Origin::Embedded(files(size, tokens, hops)?),
    )
    .map_err(|ps| ps.iter().map(|p| p.render()).collect::<String>())?;
    let opts = RunOptions {
        workers,
        max_ticks: u64::MAX,
        trace_rules: false,
        ..RunOptions::default()
    };
    let mut watch = Watch {
        // Started before the worker threads, so that it counts theirs too.
        counter: Counter::start().map(|c| (c, None)),
        ..Watch::default()
    };
    let (summary, _) = run_mas(&system, &opts, None, &mut watch)
        .map_err(|ps| ps.iter().map(|p| p.render()).collect::<String>())?;
    let end = Instant::now();
    let instructions = watch
        .counter
        .as_ref()
        .and_then(|(c, at)| Some(c.read()?.saturating_sub((*at)?)));
    let started = watch.started.unwrap_or(end);
    let expected = tokens * hops;
    // Every hop is one message, plus one `finished(T)` per token to the counter.
    let hop_messages = summary.messages.saturating_sub(tokens);
    let done_line = format!("all_arrived({tokens})");
    let mut failure = None;
    if !watch.printed.contains(&done_line) {
        failure = Some(format!("the counter did not print {done_line}"));
    } else if hop_messages != expected {
        failure = Some(format!("{hop_messages} hops instead of {expected}"));
    } else if !matches!(summary.end, EndReason::Idle | EndReason::AllStopped) {
        failure = Some(format!("run ended: {}", summary.end.describe()));
    } else if let Some(w) = watch.warnings.first() {
        failure = Some(format!("warning: {w}"));
    }
    let run = end - started;
    let cycles = summary.agents.values().map(|a| a.cycles).sum();
    let mut report = Report {
        name: name.to_string(),
        config: format!("agents={size} tokens={tokens} hops={hops}"),
        failure,
        agents: summary.agents.len(),
        workers: watch.workers,
        create: started - t0,
        run,
        count: hop_messages,
        unit: "hops",
        cycles,
        cpu: None,
        peak_rss_kib: rss::peak_kib(),
        extra: vec![
            ("rounds".into(), summary.rounds.to_string()),
            (
                "per hop".into(),
                format!(
                    "{:.3} µs",
                    run.as_secs_f64() * 1e6 / hop_messages.max(1) as f64
                ),
            ),
        ],
        targets: Vec::new(),
    };
    let per_hop = instructions.map(|n| n as f64 / hop_messages.max(1) as f64);
    report.extra.push((
        "instr".into(),
        match (instructions, per_hop) {
            (Some(n), Some(h)) => format!("{} in the run ({h:.0} per hop)", si(n as f64)),
            _ => "no hardware counter here (count with valgrind --tool=callgrind)".into(),
        },
    ));
    let standard = size == 500 && hops == 500_000;
    if standard && tokens == 1 {
        report.targets.push(Target {
            what: "run time",
            value: run.as_secs_f64(),
            target: 0.5,
            unit: "s",
            lower_is_better: true,
        });
        if let Some(h) = per_hop {
            report.targets.push(Target {
                what: "instructions/hop",
                value: h,
                target: 9000.0,
                unit: "",
                lower_is_better: true,
            });
        }
    }
    if tokens > 1 || standard {
        report.targets.push(Target {
            what: "hops/s",
            value: report.rate(),
            target: 1e6,
            unit: "",
            lower_is_better: false,
        });
    }
    Ok(report)
}

/// ring50 on `workers` threads and again on one: the speed-up of the extra threads, compared
/// with the target of 1.6 for two (shown on the first report). With `compare=0` the second run
/// is left out.
pub fn ring50(params: &Params, workers: usize) -> Result<Report, String> {
    let compare = params.flag("compare", true)? && workers > 1;
    // Each run's own CPU time: the process total would count the comparison run too.
    let before = super::cpu::process_time();
    let mut report = run("ring50", params, workers, 50)?;
    report.cpu = super::cpu::since(before);
    if !compare || !report.ok() {
        return Ok(report);
    }
    let before = super::cpu::process_time();
    let one = run("ring50", params, 1, 50)?;
    let one_cpu = super::cpu::since(before);
    if let Some(f) = one.failure {
        report.failure = Some(format!("on 1 worker: {f}"));
        return Ok(report);
    }
    let speedup = report.rate() / one.rate().max(1e-9);
    report.extra.push((
        "1 worker".into(),
        match one_cpu {
            Some(cpu) => format!(
                "{}/s, run {:.3} s, cpu {:.3} s",
                si(one.rate()),
                one.run.as_secs_f64(),
                cpu.as_secs_f64()
            ),
            None => format!("{}/s, run {:.3} s", si(one.rate()), one.run.as_secs_f64()),
        },
    ));
    report.targets.push(Target {
        what: "speed-up over 1 worker",
        value: speedup,
        target: 0.8 * workers as f64,
        unit: "x",
        lower_is_better: false,
    });
    Ok(report)
}
