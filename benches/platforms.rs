//! The platform-comparison benchmarks of `goal bench` as one table: token rings, reasoning,
//! percept load and idle agents, with the project's targets and the ratio to them. Run with
//! `cargo bench --bench platforms` (`PLATFORMS_QUICK=1`: small configurations;
//! `PLATFORMS_FULL=1`: ring50 with the full 500,000 hops per token instead of 20,000).

use goal::bench::{self, report::si, Params};

fn main() {
    let quick = std::env::var_os("PLATFORMS_QUICK").is_some();
    let full = std::env::var_os("PLATFORMS_FULL").is_some();
    let runs: Vec<(&str, Vec<(&str, u64)>)> = if quick {
        vec![
            ("ring1", vec![("hops", 20_000)]),
            ("ring50", vec![("hops", 2_000)]),
            ("fib", vec![("reps", 50)]),
            ("knowledge", vec![("queries", 10)]),
            ("percepts", vec![("cycles", 10)]),
            ("agents", vec![]),
        ]
    } else {
        vec![
            ("ring1", vec![]),
            ("ring50", if full { vec![] } else { vec![("hops", 20_000)] }),
            ("fib", vec![]),
            ("knowledge", vec![]),
            ("percepts", vec![]),
            ("agents", vec![]),
        ]
    };
    println!(
        "| benchmark | config | ok | create s | run s | rate | peak RSS MiB | target | ratio |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, params) in runs {
        let p = Params::of(&params);
        match bench::run(name, &p, 2) {
            Ok(r) => {
                let targets: Vec<String> = r
                    .targets
                    .iter()
                    .map(|t| {
                        format!(
                            "{} {} {}",
                            t.what,
                            if t.lower_is_better { "<" } else { ">" },
                            t.target
                        )
                    })
                    .collect();
                let ratios: Vec<String> = r
                    .targets
                    .iter()
                    .map(|t| format!("x{:.3}", t.ratio()))
                    .collect();
                println!(
                    "| {name} | {} | {} | {:.3} | {:.3} | {} {}/s | {:.1} | {} | {} |",
                    r.config,
                    if r.ok() { "yes" } else { "NO" },
                    r.create.as_secs_f64(),
                    r.run.as_secs_f64(),
                    si(r.rate()),
                    r.unit,
                    r.peak_rss_kib.unwrap_or(0) as f64 / 1024.0,
                    targets.join(", "),
                    ratios.join(", ")
                );
            }
            Err(e) => println!("| {name} | error: {e} | | | | | | | |"),
        }
    }
}
