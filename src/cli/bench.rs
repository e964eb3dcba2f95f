//! `goal bench [NAME|all|list] [--param k=v]...`: run the benchmarks of `goal::bench` and print
//! their figures; the exit code is 0 only when every run finished correctly.

use goal::bench::{self, Params};
use std::process::ExitCode;

/// Arguments of `goal bench`.
#[derive(clap::Args)]
pub struct Args {
    /// ring1, ring50, fib, knowledge, percepts, agents, `all` (every benchmark in its standard
    /// configuration) or `list`.
    pub name: String,
    /// A parameter of the benchmark, e.g. `--param hops=10000` (repeatable).
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub params: Vec<String>,
    /// Worker threads for the agents (default 2, the machines the targets are set for).
    #[arg(long, default_value_t = 2)]
    pub workers: usize,
    /// Runs of each benchmark; the report shows the run with the median run time (`agents`
    /// always runs once: its memory figure is the growth of a fresh process).
    #[arg(long, default_value_t = 1)]
    pub runs: usize,
}

/// Runs `goal bench`.
pub fn main(args: Args) -> ExitCode {
    if args.name == "list" {
        for (n, d) in bench::BENCHMARKS {
            println!("{n:<10} {d}");
        }
        return ExitCode::SUCCESS;
    }
    let params = match Params::parse(&args.params) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let names: Vec<&str> = if args.name == "all" {
        bench::BENCHMARKS.iter().map(|(n, _)| *n).collect()
    } else {
        vec![args.name.as_str()]
    };
    let mut ok = true;
    for name in names {
        let mut reports = Vec::new();
        // Memory per idle agent is RSS growth: only a first run in the process measures it.
        let runs = if name == "agents" {
            1
        } else {
            args.runs.max(1)
        };
        for _ in 0..runs {
            match bench::run(name, &params, args.workers) {
                Ok(r) => reports.push(r),
                Err(e) => {
                    eprintln!("error: {name}: {e}");
                    return ExitCode::from(2);
                }
            }
        }
        let failed = reports.iter().filter(|r| !r.ok()).count();
        reports.sort_by_key(|r| r.run);
        let median = &reports[reports.len() / 2];
        print!("{}", median.render());
        if reports.len() > 1 {
            let times: Vec<String> = reports
                .iter()
                .map(|r| format!("{:.3}", r.run.as_secs_f64()))
                .collect();
            println!(
                "runs        {} (run times, s: {}), {failed} failed",
                reports.len(),
                times.join(" ")
            );
        }
        println!();
        if failed > 0 {
            ok = false;
        }
    }
    let unused = params.unused();
    if !unused.is_empty() {
        eprintln!("error: unknown parameter(s): {}", unused.join(", "));
        return ExitCode::from(2);
    }
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
