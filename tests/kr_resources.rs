//! No query can take the process down (issue 11, resources): every query runs under memory,
//! answer, output and text budgets beside the inference budget; built-ins detect cyclic
//! input; backtracking loops count as inferences; a deadline or cancel flag stops a query;
//! ISO exceptions (`catch/3`, `throw/1`); protected predicates say why they fail; walks over
//! million-element and million-deep terms neither recurse nor take quadratic time.

use goal::kr::error::Interrupt;
use goal::kr::{Engine, Knowledge, KrError, Limits, NativeEngine, View};
use goal::syntax::prolog::Reader;
use goal::term::{Subst, Sym, Term};
use std::time::{Duration, Instant};

fn read(text: &str) -> Term {
    Reader::new("test")
        .term(text, 0)
        .unwrap_or_else(|d| panic!("{text}: {}", d.message))
        .term
}

fn load(program: &str) -> std::sync::Arc<Knowledge> {
    let (clauses, errors) = Reader::new("test").clauses(program, 0);
    assert!(errors.is_empty(), "{errors:?}");
    let terms: Vec<Term> = clauses.into_iter().map(|c| c.term).collect();
    Knowledge::load(&terms).unwrap_or_else(|e| panic!("{e}"))
}

const PROGRAM: &str = "
dbl(A, 0, A) :- !.
dbl(A, N, B) :- atom_concat(A, A, C), N1 is N - 1, dbl(C, N1, B).
grow(L) :- grow([a|L]).
loopw :- repeat, write(xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx), fail.
count(0) :- !.
count(N) :- N1 is N - 1, count(N1).
";

/// All answers of `query` against [`PROGRAM`] under `limits`.
fn run_with(query: &str, limits: Limits) -> Result<Vec<Subst>, KrError> {
    let kn = load(PROGRAM);
    let mut e = NativeEngine::new(0).with_limits(limits);
    e.query(&View::beliefs(&kn, &[]), &read(query))
}

fn run(query: &str) -> Result<Vec<Subst>, KrError> {
    run_with(query, Limits::default())
}

/// The error of `query`, as the term a user sees.
fn error_of(query: &str) -> String {
    match run(query) {
        Err(e) => e.to_term().to_string(),
        Ok(a) => panic!("{query}: expected an error, got {} answers", a.len()),
    }
}

fn binding(a: &Subst, var: &str) -> String {
    a.get(Sym::intern(var))
        .map(|t| t.to_string())
        .unwrap_or_default()
}

#[test]
fn cyclic_terms_given_to_builtins_are_errors() {
    for q in [
        "X = [a|X], length(X, N)",
        "X = [a|X], reverse(X, Y)",
        "X = [a|X], msort(X, Y)",
        "X = f(X), Y is X",
        "C = f(C), 1 < C",
        "C = f(C), tab(C)",
        "X = [a|X], memberchk(b, X)",
        "X = [a|X], nth1(100000000, X, E)",
        "X = f(X), term_variables(X, V)",
        "X = f(X), copy_term(X, Y)",
    ] {
        let e = error_of(q);
        assert!(e.contains("representation_error(cyclic_term)"), "{q}: {e}");
    }
}

#[test]
fn backtracking_loops_meet_the_inference_budget() {
    let small = Limits {
        max_inferences: 100_000,
        ..Limits::default()
    };
    // `member/2` on a cyclic list never calls a predicate: each step is a backtrack.
    for q in [
        "X = [a|X], member(b, X)",
        "repeat, fail",
        "between(1, inf, X), X < 0",
    ] {
        match run_with(q, small) {
            Err(KrError::Budget { limit, .. }) => assert_eq!(limit, 100_000, "{q}"),
            other => panic!("{q}: {other:?}"),
        }
    }
}

#[test]
fn single_inferences_that_would_take_gigabytes_are_resource_errors() {
    for (q, resource) in [
        ("numlist(1, 100000000, L)", "memory"),
        ("length(L, 100000000)", "memory"),
        ("dbl(a, 40, B)", "text"),
        (
            "atom_length(A, 1), dbl(abcdefgh, 22, B), atom_concat(X, Y, B)",
            "text",
        ),
        ("grow([])", "memory"),
        ("findall(X, between(1, inf, X), L)", "memory"),
        ("loopw", "output"),
    ] {
        match run(q) {
            Err(KrError::Resource { resource: r, .. }) => assert_eq!(r, resource, "{q}"),
            Err(KrError::Budget { .. }) if q.starts_with("findall") => {}
            Err(KrError::Iso(t)) if q.starts_with("atom_length") => {
                assert!(t.to_string().contains("instantiation_error"))
            }
            other => panic!("{q}: {other:?}"),
        }
    }
    let shown = error_of("numlist(1, 100000000, L)");
    assert_eq!(shown, "error(resource_error(memory),'numlist/3')");
}

#[test]
fn answers_are_bounded_in_number_and_size() {
    match run("between(1, inf, X)") {
        Err(KrError::Resource {
            resource, limit, ..
        }) => {
            assert_eq!(resource, "answers");
            assert_eq!(limit, Limits::default().max_answers);
        }
        other => panic!("{other:?}"),
    }
    // Ever longer answers: their total size meets the memory budget long before the count.
    match run("length(L, N)") {
        Err(KrError::Resource { resource, .. }) => assert_eq!(resource, "memory"),
        other => panic!("{other:?}"),
    }
    // A caller that stops early is not limited.
    let kn = load(PROGRAM);
    let mut e = NativeEngine::new(0);
    let first = e
        .query_first(&View::beliefs(&kn, &[]), &read("between(1, inf, X)"))
        .unwrap()
        .unwrap();
    assert_eq!(binding(&first, "X"), "1");
}

#[test]
fn a_long_deterministic_countdown_stops_at_the_memory_budget_not_the_machine() {
    let limits = Limits {
        max_heap_cells: 1 << 20,
        ..Limits::default()
    };
    match run_with("count(3000000)", limits) {
        Err(KrError::Resource {
            resource, limit, ..
        }) => {
            assert_eq!(resource, "memory");
            assert_eq!(limit, 1 << 20);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(run_with("count(10000)", limits).unwrap().len(), 1);
}

#[test]
fn a_cancel_flag_or_a_deadline_interrupts_a_query() {
    let flag = Interrupt::new();
    let limits = Limits {
        max_inferences: u64::MAX / 2,
        cancel: flag,
        ..Limits::default()
    };
    // Set from another thread while the query runs forever.
    let setter = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(50));
        flag.set();
    });
    match run_with("repeat, fail", limits) {
        Err(KrError::Interrupted { predicate }) => assert_eq!(predicate, "repeat/0"),
        other => panic!("{other:?}"),
    }
    setter.join().unwrap();
    let limits = Limits {
        max_inferences: u64::MAX / 2,
        deadline: Some(Instant::now()),
        ..Limits::default()
    };
    let e = run_with("count(-1)", limits).unwrap_err();
    assert!(matches!(e, KrError::Interrupted { .. }), "{e:?}");
    assert!(e.to_string().contains("interrupted"), "{e}");
}

#[test]
fn catch_and_throw_follow_iso() {
    let a = run("catch(X is foo + 1, error(E, _), true)").unwrap();
    assert_eq!(binding(&a[0], "E"), "type_error(evaluable,foo/0)");
    let a = run("catch(throw(my(ball)), my(B), true)").unwrap();
    assert_eq!(binding(&a[0], "B"), "ball");
    // Bindings made before the throw are undone; the recovery goal runs.
    let a = run("catch((X = 1, throw(t)), t, Y = 2)").unwrap();
    assert_eq!(
        (binding(&a[0], "X"), binding(&a[0], "Y")),
        ("".into(), "2".into())
    );
    // A catcher that does not match lets the ball through to an outer catch.
    let a = run("catch(catch(throw(inner), other, true), inner, R = outer)").unwrap();
    assert_eq!(binding(&a[0], "R"), "outer");
    // The goal's answers stay available on backtracking.
    assert_eq!(
        run("catch(member(X, [1, 2, 3]), _, true)").unwrap().len(),
        3
    );
    // Once the goal has exited, an error in the continuation is not caught by it.
    match run("catch(true, _, true), X is foo + 1") {
        Err(KrError::Iso(t)) => assert!(t.to_string().contains("evaluable"), "{t}"),
        other => panic!("{other:?}"),
    }
    // Uncaught balls are errors naming the ball.
    match run("throw(oops)") {
        Err(e @ KrError::Uncaught(_)) => assert_eq!(e.to_string(), "unhandled exception: oops"),
        other => panic!("{other:?}"),
    }
    assert!(error_of("throw(_)").contains("instantiation_error"));
    // Budgets cannot be caught: a program must not loop on them.
    let small = Limits {
        max_inferences: 10_000,
        ..Limits::default()
    };
    match run_with("catch((repeat, fail), _, true)", small) {
        Err(KrError::Budget { .. }) => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn protected_predicates_say_why_they_fail() {
    let e = error_of("assert(foo)");
    assert!(
        e.contains("permission_error(access,private_procedure,assert/1)"),
        "{e}"
    );
    assert!(e.contains("insert/1 and delete/1"), "{e}");
    let e = error_of("G = retract(foo(_)), call(G)");
    assert!(e.contains("retract/1"), "{e}");
}

/// `f(f(...f(z)...))`, `depth` deep.
fn deep(depth: usize) -> Term {
    let mut t = Term::atom("z");
    for _ in 0..depth {
        t = Term::compound("f", vec![t]);
    }
    t
}

/// `z+z+...+z` (left-nested, as the reader builds it), with `n` operators.
fn left_nested(n: usize) -> Term {
    let mut t = Term::atom("z");
    for _ in 0..n {
        t = Term::compound("+", vec![t, Term::atom("z")]);
    }
    t
}

#[test]
fn walks_over_million_deep_terms_do_not_recurse() {
    for t in [deep(1_000_000), left_nested(1_000_000)] {
        let u = t.clone();
        let copy = {
            // A structurally equal term that shares nothing with `t`.
            let mut s = Subst::new();
            s.bind(Sym::intern("X"), t.clone());
            s.apply(&Term::compound("g", vec![Term::var("X")]))
        };
        assert!(t.is_ground());
        assert_eq!(t, u);
        assert_eq!(copy.args()[0], t);
        assert_eq!(t.compare(&copy.args()[0]), std::cmp::Ordering::Equal);
        let mut set = std::collections::HashSet::new();
        set.insert(t.clone());
        assert!(set.contains(&copy.args()[0]));
        assert_eq!(t.depth(), 1_000_001);
        // Error texts stay short whatever the culprit.
        let text =
            KrError::Iso(Term::compound("error", vec![t.clone(), Term::atom("x")])).to_string();
        assert!(text.len() < 3_000, "{}", text.len());
    }
    // Through the engine: a million-deep term as input and as answer.
    let kn = load(PROGRAM);
    let mut e = NativeEngine::new(0);
    let t = deep(1_000_000);
    let q = Term::compound(
        ",",
        vec![
            Term::compound("=", vec![Term::var("X"), t.clone()]),
            Term::compound("copy_term", vec![Term::var("X"), Term::var("Y")]),
        ],
    );
    let a = e.query(&View::beliefs(&kn, &[]), &q).unwrap();
    assert!(a[0].get(Sym::intern("Y")) == Some(&t));
}

#[test]
fn answers_with_many_unbound_variables_convert_in_linear_time() {
    // 200,000 distinct unbound variables in one answer: each is named once (hashing).
    let a = run("length(L, 200000)").unwrap();
    let l = a[0].get(Sym::intern("L")).unwrap();
    assert_eq!(l.list_items().unwrap().len(), 200_000);
}

/// The atom budget of the engine `e`'s queries: the error of `query`, if any.
fn atoms_error(e: &mut NativeEngine, query: &str) -> Option<KrError> {
    let kn = load(PROGRAM);
    e.query(&View::beliefs(&kn, &[]), &read(query)).err()
}

/// True when `r` is the atom budget's error.
fn is_atoms_error(r: &Option<KrError>) -> bool {
    matches!(
        r,
        Some(KrError::Resource {
            resource: "atoms",
            ..
        })
    )
}

#[test]
fn queries_creating_atoms_without_end_meet_the_engines_atom_budget() {
    let small = Limits {
        max_new_atoms: 1000,
        ..Limits::default()
    };
    for q in [
        "between(1, inf, X), atom_number(A, X), X < 0",
        "between(1, inf, X), atom_concat(kr_atoms_concat_, X, A), fail",
        "between(1, inf, X), format(atom(A), 'kr_atoms_format_~w', [X]), fail",
        "between(1, inf, X), atomic_list_concat([kr_atoms_list_, X], A), fail",
    ] {
        let mut e = NativeEngine::new(0).with_limits(small);
        match atoms_error(&mut e, q) {
            Some(KrError::Resource {
                resource: "atoms",
                limit: 1000,
                predicate,
            }) => assert!(!predicate.is_empty(), "{q}"),
            other => panic!("{q}: {other:?}"),
        }
        // The budget is the engine's, over all its queries: a new atom is refused at once;
        // queries that make no atom still run.
        let again = atoms_error(&mut e, "atom_concat(kr_atoms_once_, more, A)");
        assert!(is_atoms_error(&again), "{again:?}");
        assert_eq!(atoms_error(&mut e, "X = 1"), None);
    }
}

#[test]
fn atoms_made_again_do_not_count_against_the_budget() {
    let small = Limits {
        max_new_atoms: 1000,
        ..Limits::default()
    };
    let mut e = NativeEngine::new(0).with_limits(small);
    // 600 atoms, then the same 600 made again and again: never more than the budget.
    let same = "between(1, 600, X), atom_concat(kr_atoms_again_, X, A), atom_length(A, _), fail";
    for _ in 0..20 {
        assert_eq!(atoms_error(&mut e, same), None);
    }
    // A second engine has a budget of its own.
    let mut other = NativeEngine::new(0).with_limits(small);
    let q = "between(1, 900, X), atom_concat(kr_atoms_other_, X, A), fail";
    assert_eq!(atoms_error(&mut other, q), None);
    // The first engine has 400 atoms left.
    let q = "between(1, 401, X), atom_concat(kr_atoms_rest_, X, A), fail";
    assert!(is_atoms_error(&atoms_error(&mut e, q)));
    // Atoms it made before can still be made. Atoms that exist but that it never made count
    // too, so that its count never depends on what other engines made.
    assert_eq!(atoms_error(&mut e, same), None);
    let q = "atom_concat(kr_atoms_other_, 1, A)";
    assert!(is_atoms_error(&atoms_error(&mut e, q)));
}
