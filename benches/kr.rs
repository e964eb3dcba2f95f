//! KR benchmark: the native engine and scryer-prolog 0.10 side by side in one run, printed as a
//! table with ratios (issue 3: the target figures are in the README).
//!
//! Run with `cargo bench --bench kr`. `KR_BENCH_QUICK=1` runs every case a few times only (the
//! smoke test in `tests/kr_diff_bench_smoke.rs` does that).

#[path = "../tests/kr_diff/build.rs"]
mod build;
#[path = "kr/native.rs"]
mod native;
#[path = "../tests/kr_diff/scryer.rs"]
mod scryer;

use build::*;
use goal::term::Term;
use std::time::{Duration, Instant};

/// Naive reverse of a 30-element list: 496 logical inferences.
pub const NREV30_LI: f64 = 496.0;
/// Insert/delete pairs for the memory figure (native).
const NATIVE_PAIRS: usize = 1_000_000;
/// Insert/delete pairs for scryer: capped because every retracted clause leaks about 4 KB and a
/// pair costs 40-100 µs (a million would take minutes and gigabytes).
const SCRYER_PAIRS: usize = 20_000;

pub fn quick() -> bool {
    std::env::var("KR_BENCH_QUICK").is_ok()
}

/// Resident set size of this process in bytes (from /proc/self/statm), 0 when unavailable.
pub fn rss_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| {
            s.split_whitespace()
                .nth(1)
                .and_then(|p| p.parse::<u64>().ok())
        })
        .map(|pages| pages * 4096)
        .unwrap_or(0)
}

/// Mean time per call of `f`, running it repeatedly for about `budget` (after a warm-up).
pub fn time_per_op(mut f: impl FnMut(), budget: Duration) -> Duration {
    let (budget, min_runs) = if quick() {
        (Duration::from_millis(1), 2)
    } else {
        (budget, 10)
    };
    for _ in 0..min_runs.min(100) {
        f();
    }
    let start = Instant::now();
    let mut runs = 0u64;
    while runs < min_runs || start.elapsed() < budget {
        f();
        runs += 1;
    }
    start.elapsed() / runs as u32
}

/// The programs every case loads: facts, `clear/1` over `on/2`, naive reverse.
pub fn bench_clauses() -> Vec<Term> {
    let mut cl = Vec::new();
    for k in 0..1000 {
        cl.push(c("fact", vec![a(&format!("k{k}")), a(&format!("v{k}"))]));
    }
    // 100 `on/2` facts: ten towers of ten blocks.
    for k in 0..100 {
        let below = if (k + 1) % 10 == 0 {
            a("table")
        } else {
            a(&format!("b{}", k + 1))
        };
        cl.push(c("on", vec![a(&format!("b{k}")), below]));
    }
    cl.push(rule(
        c("clear", vec![v("X")]),
        vec![
            c("on", vec![v("X"), v("_")]),
            naf(c("on", vec![v("_"), v("X")])),
        ],
    ));
    cl.push(c("app", vec![list(vec![]), v("L"), v("L")]));
    cl.push(rule(
        c(
            "app",
            vec![
                Term::cons(v("H"), v("T")),
                v("L"),
                Term::cons(v("H"), v("R")),
            ],
        ),
        vec![c("app", vec![v("T"), v("L"), v("R")])],
    ));
    cl.push(c("nrev", vec![list(vec![]), list(vec![])]));
    cl.push(rule(
        c("nrev", vec![Term::cons(v("H"), v("T")), v("R")]),
        vec![
            c("nrev", vec![v("T"), v("RT")]),
            c("app", vec![v("RT"), list(vec![v("H")]), v("R")]),
        ],
    ));
    cl.push(c("list30", vec![list((1..=30).map(i).collect())]));
    cl.push(rule(
        c("bench_nrev", vec![v("N")]),
        vec![
            c("list30", vec![v("L")]),
            c("between", vec![i(1), v("N"), v("_")]),
            c("nrev", vec![v("L"), v("_")]),
            a("fail"),
        ],
    ));
    cl.push(c("bench_nrev", vec![v("_")]));
    cl.extend(query_predicates());
    cl
}

/// The query of each case (the same on both engines).
pub struct Queries {
    pub fact: Term,
    pub naf: Term,
    pub findall: Term,
    pub clear: Term,
    pub belief: Term,
}

pub fn queries() -> Queries {
    Queries {
        fact: c("fact", vec![a("k500"), a("v500")]),
        naf: c("q_naf", vec![]),
        findall: c("q_findall", vec![v("L")]),
        clear: c("q_clear", vec![v("L")]),
        belief: c("bel", vec![a("k1")]),
    }
}

/// The benchmark queries with control constructs, as predicates: scryer compiles control
/// constructs written in query text on every query (about 1 ms), which would measure its
/// compiler rather than its engine.
fn query_predicates() -> Vec<Term> {
    vec![
        rule(
            c("q_naf", vec![]),
            vec![naf(c("fact", vec![a("k500"), a("nope")]))],
        ),
        rule(
            c("q_findall", vec![v("L")]),
            vec![c(
                "findall",
                vec![v("X"), c("fact", vec![v("X"), v("_")]), v("L")],
            )],
        ),
        rule(
            c("q_clear", vec![v("L")]),
            vec![c("findall", vec![v("X"), c("clear", vec![v("X")]), v("L")])],
        ),
    ]
}

/// One row of the table.
struct Row {
    name: &'static str,
    unit: &'static str,
    native: Option<f64>,
    scryer: Option<f64>,
    /// True when a larger figure is better (inferences per second).
    higher_is_better: bool,
    target: &'static str,
}

fn fmt(x: Option<f64>) -> String {
    match x {
        Some(x) if x >= 100.0 => format!("{x:.0}"),
        Some(x) => format!("{x:.2}"),
        None => "n/a".into(),
    }
}

fn print_table(rows: &[Row]) {
    println!();
    println!(
        "{:<34} {:>14} {:>14} {:>9}  target",
        "case", "native", "scryer", "ratio"
    );
    println!("{}", "-".repeat(96));
    for r in rows {
        let ratio = match (r.native, r.scryer) {
            (Some(n), Some(s)) if n < 0.01 && s >= 0.01 && r.unit == "bytes" => "flat".into(),
            (Some(n), Some(s)) if n > 0.0 && s > 0.0 => {
                let x = if r.higher_is_better { n / s } else { s / n };
                format!("{x:.1}x")
            }
            _ => "n/a".into(),
        };
        println!(
            "{:<34} {:>14} {:>14} {:>9}  {}",
            format!("{} ({})", r.name, r.unit),
            fmt(r.native),
            fmt(r.scryer),
            ratio,
            r.target
        );
    }
    println!("ratio: how many times better the native engine is (>1 = native faster/smaller)");
}

pub fn micros(d: Duration) -> f64 {
    d.as_secs_f64() * 1e6
}

/// Scryer's figures, in table order.
fn scryer_figures(q: &Queries) -> [Option<f64>; 7] {
    let mut s = scryer::Scryer::new();
    s.load(&bench_clauses());
    s.load_text(":- dynamic(bel/1).\n");
    let budget = Duration::from_millis(400);
    let run = |s: &mut scryer::Scryer, t: &Term| {
        let _ = s.solutions(t);
    };
    let fact = time_per_op(|| run(&mut s, &q.fact), budget);
    let assert = c("assertz", vec![q.belief.clone()]);
    let retract = c("retract", vec![q.belief.clone()]);
    let pair = time_per_op(
        || {
            run(&mut s, &assert);
            run(&mut s, &retract);
        },
        budget,
    );
    let naf = time_per_op(|| run(&mut s, &q.naf), budget);
    let findall = time_per_op(|| run(&mut s, &q.findall), budget);
    let clear = time_per_op(|| run(&mut s, &q.clear), budget);
    let n = if quick() { 2 } else { 2000 };
    let nrev_goal = c("bench_nrev", vec![i(n)]);
    let nrev = time_per_op(|| run(&mut s, &nrev_goal), budget);
    let lips = NREV30_LI * n as f64 / nrev.as_secs_f64();
    let pairs = if quick() { 200 } else { SCRYER_PAIRS };
    let before = rss_bytes();
    for k in 0..pairs {
        let b = c("bel", vec![i(k as i64)]);
        run(&mut s, &c("assertz", vec![b.clone()]));
        run(&mut s, &c("retract", vec![b]));
    }
    let grown = rss_bytes().saturating_sub(before);
    [
        Some(micros(fact)),
        Some(micros(pair)),
        Some(micros(naf)),
        Some(micros(findall)),
        Some(lips / 1e6),
        Some(micros(clear)),
        Some(grown as f64 / pairs.max(1) as f64),
    ]
}

pub fn main() {
    let q = queries();
    // Native first: its memory figure must not include scryer's machine.
    let (n, native_holds) = native::figures(
        &bench_clauses(),
        &q,
        if quick() { 1000 } else { NATIVE_PAIRS },
    );
    let s = scryer_figures(&q);
    let scryer_pairs = if quick() { 200 } else { SCRYER_PAIRS };
    let native_pairs = if quick() { 1000 } else { NATIVE_PAIRS };
    let rows = [
        Row {
            name: "ground fact query",
            unit: "µs",
            native: n[0],
            scryer: s[0],
            higher_is_better: false,
            target: "~1 µs, 10x+ faster than scryer",
        },
        Row {
            name: "belief insert+delete",
            unit: "µs/pair",
            native: n[1],
            scryer: s[1],
            higher_is_better: false,
            target: "~1 µs, 10x+ faster than scryer",
        },
        Row {
            name: "\\+ query",
            unit: "µs",
            native: n[2],
            scryer: s[2],
            higher_is_better: false,
            target: "fast",
        },
        Row {
            name: "findall over 1,000 facts",
            unit: "µs",
            native: n[3],
            scryer: s[3],
            higher_is_better: false,
            target: "fast",
        },
        Row {
            name: "nrev30",
            unit: "M LIPS",
            native: n[4],
            scryer: s[4],
            higher_is_better: true,
            target: ">= scryer",
        },
        Row {
            name: "findall clear/1, 100 on/2",
            unit: "µs",
            native: n[5],
            scryer: s[5],
            higher_is_better: false,
            target: "~10 µs",
        },
        Row {
            name: "RSS growth per insert/delete",
            unit: "bytes",
            native: n[6],
            scryer: s[6],
            higher_is_better: false,
            target: "flat",
        },
    ];
    print_table(&rows);
    println!("native holds() on the ground fact (the agents' yes/no check): {native_holds:.2} µs");
    let mb = |per_pair: Option<f64>, pairs: usize| per_pair.unwrap_or(0.0) * pairs as f64 / 1e6;
    println!(
        "RSS growth: native {:.1} MB after {native_pairs} insert/delete pairs on a belief base; \
         scryer {:.1} MB after {scryer_pairs} assertz/retract pairs (capped: each pair costs tens \
         of µs and leaks ~4 KB, so a million would take minutes and about {:.1} GB).",
        mb(n[6], native_pairs),
        mb(s[6], scryer_pairs),
        s[6].unwrap_or(0.0) * 1e6 / 1e9
    );
}
