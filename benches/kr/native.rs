//! The native engine's figures for `benches/kr.rs`: beliefs (`fact/2`, `on/2`) live in a
//! `FactBase` as an agent's beliefs do; the rules and the nrev program are knowledge.

use super::{micros, quick, rss_bytes, time_per_op, Queries, NREV30_LI};
use goal::kr::{Engine, FactBase, Knowledge, Limits, NativeEngine, View};
use goal::term::{Sym, Term};
use std::time::Duration;

/// True for the clauses that are beliefs in an agent (ground `fact/2` and `on/2` facts).
fn is_belief(c: &Term) -> bool {
    c.is_ground() && (c.is_functor(Sym::intern("fact"), 2) || c.is_functor(Sym::intern("on"), 2))
}

/// The native figures in table order (`None` = not measured), then `holds()` on a ground fact.
pub fn figures(clauses: &[Term], q: &Queries, pairs: usize) -> ([Option<f64>; 7], f64) {
    let (facts, rules): (Vec<Term>, Vec<Term>) = clauses.iter().cloned().partition(is_belief);
    let knowledge = match Knowledge::load(&rules) {
        Ok(k) => k,
        Err(e) => {
            eprintln!("native engine rejected the benchmark program: {e}");
            return ([None; 7], 0.0);
        }
    };
    let mut beliefs = FactBase::new();
    for f in facts {
        beliefs.insert(f);
    }
    let mut engine = NativeEngine::new(1).with_limits(Limits {
        max_inferences: u64::MAX / 2,
        ..Limits::default()
    });
    let budget = Duration::from_millis(400);
    let mut run = |beliefs: &FactBase, t: &Term| {
        let bases = [beliefs];
        let view = View::beliefs(&knowledge, &bases);
        match engine.query(&view, t) {
            Ok(a) => a.len(),
            Err(e) => panic!("native engine failed on {t}: {e}"),
        }
    };
    assert_eq!(run(&beliefs, &q.fact), 1, "fact query should succeed");
    let fact = time_per_op(
        || {
            let _ = run(&beliefs, &q.fact);
        },
        budget,
    );
    let naf = time_per_op(
        || {
            let _ = run(&beliefs, &q.naf);
        },
        budget,
    );
    let findall = time_per_op(
        || {
            let _ = run(&beliefs, &q.findall);
        },
        budget,
    );
    let clear = time_per_op(
        || {
            let _ = run(&beliefs, &q.clear);
        },
        budget,
    );
    let n = if quick() { 2 } else { 2000 };
    let nrev_goal = Term::compound(Sym::intern("bench_nrev"), vec![Term::Int(n)]);
    let nrev = time_per_op(
        || {
            let _ = run(&beliefs, &nrev_goal);
        },
        budget,
    );
    let lips = NREV30_LI * n as f64 / nrev.as_secs_f64();

    let mut holds_engine = NativeEngine::new(2);
    let holds = {
        let bases = [&beliefs];
        let view = View::beliefs(&knowledge, &bases);
        time_per_op(
            || {
                let _ = holds_engine.holds(&view, &q.fact);
            },
            budget,
        )
    };

    let belief = q.belief.clone();
    let pair = time_per_op(
        || {
            beliefs.insert(belief.clone());
            beliefs.delete(&belief);
        },
        budget,
    );
    let before = rss_bytes();
    let bel = Sym::intern("bel");
    for k in 0..pairs {
        let f = Term::compound(bel, vec![Term::Int(k as i64)]);
        beliefs.insert(f.clone());
        beliefs.delete(&f);
    }
    let grown = rss_bytes().saturating_sub(before);
    (
        [
            Some(micros(fact)),
            Some(micros(pair)),
            Some(micros(naf)),
            Some(micros(findall)),
            Some(lips / 1e6),
            Some(micros(clear)),
            Some(grown as f64 / pairs.max(1) as f64),
        ],
        micros(holds),
    )
}
