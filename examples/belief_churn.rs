//! Memory after belief churn on a KR engine: `cargo run --release --example belief_churn --
//! [native|scryer] [UPDATES]` applies UPDATES belief updates (each deletes one `at/2` fact and
//! inserts another; default 1,000,000), querying the belief view after every update (so each update reaches the engine), and
//! prints the resident memory before and after.

use goal::kr::{AgentEngine, Engine, FactBase, Knowledge, KrKind, Limits, View};
use goal::mas::memory::resident_bytes;
use goal::term::Term;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let kind = match args.get(1).map(String::as_str) {
        Some("scryer") => KrKind::Scryer,
        _ => KrKind::Native,
    };
    let updates: u64 = args
        .get(2)
        .and_then(|n| n.parse().ok())
        .unwrap_or(1_000_000);
    let kn = Knowledge::load(&[]).expect("empty knowledge");
    let mut engine = AgentEngine::new(kind, &kn, 0, Limits::default()).expect("engine");
    let mut beliefs = FactBase::new();
    for i in 0..100 {
        beliefs.insert(Term::compound("block", vec![Term::Int(i)]));
    }
    let query = Term::compound("at", vec![Term::var("X"), Term::var("Y")]);
    let warm = |engine: &mut AgentEngine, b: &FactBase| {
        let bases = [b];
        engine
            .query(&View::beliefs(&kn, &bases), &query)
            .expect("query")
            .len()
    };
    warm(&mut engine, &beliefs);
    let before = resident_bytes().unwrap_or(0);
    let start = Instant::now();
    let at = |i: u64| Term::compound("at", vec![Term::Int((i % 7) as i64), Term::Int(i as i64)]);
    beliefs.insert(at(0));
    for i in 1..=updates {
        beliefs.delete(&at(i - 1));
        beliefs.insert(at(i));
        assert_eq!(warm(&mut engine, &beliefs), 1);
    }
    let after = resident_bytes().unwrap_or(0);
    println!(
        "{} engine: {updates} belief updates in {:.1} s; resident memory {:.1} MB before, {:.1} MB after",
        kind.name(),
        start.elapsed().as_secs_f64(),
        before as f64 / 1e6,
        after as f64 / 1e6
    );
}
