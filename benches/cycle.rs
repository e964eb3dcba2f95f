//! Agent cycle benchmark: cycles per second for a BW4T-like robot agent (40 rules, 200
//! beliefs, 20 percepts changing per cycle) and for an idle agent. Target: 20,000 cycles/s for
//! the robot (issue 16: under 25 µs of CPU per cycle). Run with `cargo bench --bench cycle`
//! (`CYCLE_BENCH_QUICK=1` for a short run; `CYCLE_BENCH_ROWS=robot,idle` runs only the rows whose
//! names start so). CPU time (this thread's) is printed beside wall time:
//! on a shared machine wall time varies with other load, CPU time much less.

#[path = "cycle/robot.rs"]
mod robot;

use goal::agent::{Agent, AgentConfig, Program, TraceLevel};
use std::time::Instant;

fn agent(src: &str, trace: TraceLevel) -> Agent {
    let p = match Program::from_source("bench.goal", src) {
        Ok(p) => p,
        Err(d) => panic!("{}", d.iter().map(|x| x.render(src)).collect::<String>()),
    };
    let cfg = AgentConfig {
        seed: 1,
        trace,
        // `CYCLE_BENCH_KR=scryer` measures the scryer engine.
        kr: match std::env::var("CYCLE_BENCH_KR").as_deref() {
            Ok("scryer") => goal::kr::KrKind::Scryer,
            _ => goal::kr::KrKind::Native,
        },
        ..AgentConfig::default()
    };
    Agent::new(p, "robot", cfg)
}

/// CPU time this thread has used, in seconds.
fn thread_cpu() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a valid pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 / 1e9
}

/// Cycles per second (wall), CPU µs per cycle and the number of environment actions.
fn measure(src: &str, with_percepts: bool, trace: TraceLevel, cycles: u64) -> (f64, f64, usize) {
    let mut a = agent(src, trace);
    let batches: Vec<_> = (0..64).map(robot::percepts).collect();
    let mut actions = 0;
    // Warm up.
    for n in 0..100u64 {
        let p = if with_percepts {
            &batches[(n % 64) as usize][..]
        } else {
            &[]
        };
        a.step(p, &[]);
    }
    let start = Instant::now();
    let cpu = thread_cpu();
    for n in 0..cycles {
        let p = if with_percepts {
            &batches[(n % 64) as usize][..]
        } else {
            &[]
        };
        let out = a.step(p, &[]);
        actions += out.env_actions.len();
        assert!(out.stopped.is_none(), "agent stopped: {:?}", out.stopped);
    }
    let cpu = thread_cpu() - cpu;
    let secs = start.elapsed().as_secs_f64();
    (cycles as f64 / secs, cpu * 1e6 / cycles as f64, actions)
}

fn main() {
    let quick = std::env::var("CYCLE_BENCH_QUICK").is_ok();
    let n = if quick { 500 } else { 20_000 };
    let robot = robot::robot_program();
    let idle = robot::idle_program();
    println!(
        "{:<42} {:>14} {:>10} {:>8} {:>12}",
        "case", "cycles/s", "target", "ratio", "CPU µs/cycle"
    );
    let rows = [
        (
            "robot (40 rules, 200 beliefs, 20 percepts)",
            &robot,
            true,
            TraceLevel::Off,
            20_000.0,
        ),
        (
            "robot, full trace",
            &robot,
            true,
            TraceLevel::Rules,
            20_000.0,
        ),
        ("idle agent", &idle, false, TraceLevel::Off, 20_000.0),
    ];
    // `CYCLE_BENCH_ROWS=robot` runs only the rows whose name starts with one of the given
    // comma-separated prefixes (to profile one row under callgrind).
    let only = std::env::var("CYCLE_BENCH_ROWS").ok();
    let wanted = |name: &str| {
        only.as_deref()
            .is_none_or(|o| o.split(',').any(|p| name.starts_with(p)))
    };
    for (name, src, percepts, trace, target) in rows {
        if !wanted(name) {
            continue;
        }
        let (cps, cpu_us, actions) = measure(src, percepts, trace, n);
        println!(
            "{:<42} {:>14.0} {:>10.0} {:>7.2}x {:>12.1}   ({} env actions)",
            name,
            cps,
            target,
            cps / target,
            cpu_us,
            actions
        );
    }
}
