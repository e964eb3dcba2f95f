//! Every benchmark of `goal bench` once in a tiny configuration, so none of them can rot: the
//! runs must finish correctly (every token arrived, every value right). No times are asserted.

use goal::bench::{self, Params, Report};

fn run(name: &str, params: &[(&str, u64)], workers: usize) -> Report {
    let p = Params::of(params);
    let r = bench::run(name, &p, workers).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(p.unused().is_empty(), "{name}: unused {:?}", p.unused());
    assert!(r.ok(), "{name} failed:\n{}", r.render());
    r
}

#[test]
fn ring1_passes_one_token_around_a_small_ring() {
    let r = run("ring1", &[("agents", 5), ("hops", 50)], 2);
    assert_eq!(r.count, 50);
    // 5 ring agents and the counter.
    assert_eq!(r.agents, 6);
    assert!(r.render().contains("result      ok"));
}

#[test]
fn ring50_passes_every_token_on_one_and_two_threads() {
    for workers in [1, 2] {
        let r = run(
            "ring50",
            &[("agents", 10), ("tokens", 5), ("hops", 40)],
            workers,
        );
        assert_eq!(r.count, 5 * 40);
        assert_eq!(r.workers, workers);
        // Two workers run a second time on one to show the speed-up.
        assert_eq!(r.render().contains("1 worker"), workers == 2);
    }
    // `compare=0` leaves the second run out.
    let r = run(
        "ring50",
        &[("agents", 10), ("tokens", 5), ("hops", 40), ("compare", 0)],
        2,
    );
    assert!(!r.render().contains("1 worker"), "{}", r.render());
}

#[test]
fn fib_computes_every_round() {
    let r = run("fib", &[("top", 8), ("reps", 3)], 1);
    assert_eq!(r.count, 3 * 9);
    assert!(r.cycles >= r.count);
}

#[test]
fn knowledge_counts_all_ancestors() {
    let r = run("knowledge", &[("size", 64), ("queries", 2)], 1);
    // Nodes 2..64: 2 at depth 1, 4 at 2, 8 at 3, 16 at 4, 32 at 5, and node 64 at 6.
    assert_eq!(r.count, 2 * (2 + 8 + 24 + 64 + 160 + 6));
}

#[test]
fn percept_load_sees_every_batch() {
    let r = run("percepts", &[("size", 200), ("cycles", 4)], 1);
    assert_eq!(r.count, 4 * 200);
}

#[test]
fn idle_agents_are_created_and_stepped() {
    let r = run("agents", &[("agents", 50)], 2);
    assert_eq!(r.agents, 50);
}

#[test]
fn bad_parameters_and_names_are_errors() {
    assert!(bench::run("nosuch", &Params::default(), 1).is_err());
    let p = Params::of(&[("agents", 2), ("tokens", 3)]);
    assert!(
        bench::run("ring50", &p, 1).is_err(),
        "more tokens than agents"
    );
    let p = Params::of(&[("top", 95)]);
    assert!(bench::run("fib", &p, 1).is_err(), "fib(95) overflows");
}
