//! Memory under belief churn: resident set size after 1 M and after 10 M belief updates by an
//! agent that replaces a counter and a few facts keyed by it every cycle (issue 16 target: RSS
//! after 10 M within 10% of RSS after 1 M). Run with `cargo bench --bench memory`
//! (`MEMORY_BENCH_QUICK=1`: 100 k and 1 M updates).

use goal::agent::{Agent, AgentConfig, Program, TraceLevel};
use std::time::Instant;

/// Six updates per cycle: the counter is replaced, a fact keyed by it moves, and a window of
/// the last 64 `seen/1` facts slides by one (the belief base stays at 66 facts).
const PROGRAM: &str = "
init module { beliefs { count(0). } }
main module {
    program {
        if bel(count(N), N1 is N + 1, K is N mod 97, K1 is N1 mod 97, Old is N1 - 64)
            then delete(count(N)) + insert(count(N1)) + delete(item(K, N)) + insert(item(K1, N1))
                + delete(seen(Old)) + insert(seen(N1)).
    }
}";

/// Resident set size of this process in KiB (VmRSS), 0 when unavailable.
fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|n| n.parse().ok()))
        })
        .unwrap_or(0)
}

fn main() {
    let program = match Program::from_source("memory.goal", PROGRAM) {
        Ok(p) => p,
        Err(d) => panic!(
            "{}",
            d.iter().map(|x| x.render(PROGRAM)).collect::<String>()
        ),
    };
    let cfg = AgentConfig {
        seed: 1,
        trace: TraceLevel::Off,
        ..AgentConfig::default()
    };
    let mut agent = Agent::new(program, "churn", cfg);
    let quick = std::env::var("MEMORY_BENCH_QUICK").is_ok();
    let (first, last): (u64, u64) = if quick {
        (100_000, 1_000_000)
    } else {
        (1_000_000, 10_000_000)
    };
    let start = Instant::now();
    let mut updates = 0u64;
    let mut at_first = None;
    while updates < last {
        let out = agent.step(&[], &[]);
        assert!(out.stopped.is_none(), "agent stopped: {:?}", out.stopped);
        updates += 6;
        if at_first.is_none() && updates >= first {
            at_first = Some(rss_kib());
        }
    }
    let at_last = rss_kib();
    let at_first = at_first.unwrap_or(0);
    let ratio = at_last as f64 / at_first.max(1) as f64;
    println!(
        "RSS after {first} belief updates: {at_first} KiB; after {last}: {at_last} KiB \
         ({:+.1}%, target within 10%); {:.1} s",
        (ratio - 1.0) * 100.0,
        start.elapsed().as_secs_f64()
    );
    if ratio > 1.10 {
        eprintln!("memory grew by more than 10% between {first} and {last} updates");
        std::process::exit(1);
    }
}
