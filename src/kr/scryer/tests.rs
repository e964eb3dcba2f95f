//! Tests of the scryer engine through the `Engine` trait.

use super::*;
use crate::kr::{FactBase, Knowledge, KrError};
use crate::syntax::prolog::Reader;
use std::time::Instant;

fn terms(text: &str) -> Vec<Term> {
    let mut r = Reader::new("test");
    let (clauses, errs) = r.clauses(text, 0);
    assert!(errs.is_empty(), "{errs:?}");
    clauses.into_iter().map(|c| c.term).collect()
}

fn term(text: &str) -> Term {
    Reader::new("test").term(text, 0).unwrap().term
}

fn shown(answers: &[Subst]) -> Vec<String> {
    answers
        .iter()
        .map(|s| {
            s.iter()
                .map(|(v, t)| format!("{}={}", v.name(), t))
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect()
}

#[test]
fn answers_beliefs_and_knowledge() {
    let clauses = terms("clear(X) :- block(X), \\+ on(_, X).");
    let kn = Knowledge::load(&clauses).unwrap();
    let mut e = ScryerEngine::new(&clauses).unwrap();
    let mut b = FactBase::new();
    for f in ["block(a)", "block(b)", "on(a, b)"] {
        b.insert(term(f));
    }
    let bases = [&b];
    let view = View::beliefs(&kn, &bases);
    assert_eq!(shown(&e.query(&view, &term("clear(X)")).unwrap()), ["X=a"]);
    b.delete(&term("on(a, b)"));
    let bases = [&b];
    let view = View::beliefs(&kn, &bases);
    assert_eq!(
        shown(&e.query(&view, &term("clear(X)")).unwrap()),
        ["X=a", "X=b"]
    );
    // A goal view does not see the beliefs.
    let g = [term("block(c)")];
    let goal = View::goal(&kn, &g);
    assert_eq!(shown(&e.query(&goal, &term("clear(X)")).unwrap()), ["X=c"]);
    assert!(e.holds(&view, &term("block(b)")).unwrap());
    assert!(!e.holds(&view, &term("block(c)")).unwrap());
}

#[test]
fn catch_throw_and_dcg() {
    let clauses = terms(
        "greeting --> [hello], name.\nname --> [world].\nname --> [bob].\n\
         safe_div(X, Y, Z) :- catch(Z is X / Y, error(E, _), (Z = E)).\n\
         boom(X) :- throw(oops(X)).",
    );
    let kn = Knowledge::load_as(&clauses, &crate::kr::choice::native_stand_ins(&clauses)).unwrap();
    let mut e = ScryerEngine::new(&clauses).unwrap();
    let view = View::beliefs(&kn, &[]);
    let q = |e: &mut ScryerEngine, s: &str| e.query(&view, &term(s));
    assert_eq!(
        shown(&q(&mut e, "phrase(greeting, [hello, bob])").unwrap()),
        [""]
    );
    assert!(q(&mut e, "phrase(greeting, [hello, alice])")
        .unwrap()
        .is_empty());
    assert_eq!(
        shown(&q(&mut e, "safe_div(1, 0, Z)").unwrap()),
        ["Z=evaluation_error(zero_divisor)"]
    );
    assert_eq!(shown(&q(&mut e, "safe_div(6, 3, Z)").unwrap()), ["Z=2"]);
    assert_eq!(
        q(&mut e, "boom(1)").unwrap_err(),
        KrError::Uncaught(term("oops(1)"))
    );
}

#[test]
fn budget_errors_and_output() {
    let clauses = terms("loop :- loop.\nsay(X) :- write(X), nl.");
    let kn = Knowledge::load(&clauses).unwrap();
    let mut e = ScryerEngine::new(&clauses).unwrap();
    e.limits.max_inferences = 10_000;
    let view = View::beliefs(&kn, &[]);
    assert!(matches!(
        e.query(&view, &term("loop")),
        Err(KrError::Budget { .. })
    ));
    let err = e.query(&view, &term("X is foo + 1")).unwrap_err();
    assert!(err.to_string().contains("type_error"), "{err}");
    e.query(&view, &term("say(hi)")).unwrap();
    assert_eq!(e.take_output(), "hi\n");
    // Variables bound to each other, and unbound ones.
    assert_eq!(
        shown(&e.query(&view, &term("X = Y, Z = f(_W), V = g(_)")).unwrap()),
        ["Y=X,Z=f(_W),V=g(_G1)"]
    );
}

#[test]
fn sandbox_refuses_files_processes_and_the_database() {
    let clauses =
        terms("opener(G) :- call(G).\nmk(G) :- G =.. [open, '/tmp/goal_scryer_x', write, _S].");
    let kn = Knowledge::load(&clauses).unwrap();
    let mut e = ScryerEngine::new(&clauses).unwrap();
    let view = View::beliefs(&kn, &[]);
    for q in [
        "mk(G), opener(G)",
        "mk(G), call(G)",
        "G = halt, call(G)",
        "G = assertz(x), findall(x, G, _)",
        "G = shell(ls), opener(G)",
        "maplist(open('/tmp/goal_scryer_x', write), [_])",
        "X = consult, G =.. [X, foo], \\+ G",
    ] {
        let err = e.query(&view, &term(q)).unwrap_err();
        assert!(err.to_string().contains("permission_error"), "{q}: {err}");
    }
    assert!(!std::path::Path::new("/tmp/goal_scryer_x").exists());
    // Written as goals, they never reach scryer.
    assert!(ScryerEngine::new(&terms("p :- open(f, write, _).")).is_err());
    assert!(e.query(&view, &term("halt")).is_err());
}

#[test]
fn belief_churn_rebuilds_the_machine() {
    let kn = Knowledge::load(&[]).unwrap();
    let mut e = ScryerEngine::new(&[]).unwrap();
    e.rebuild_after = 100;
    let mut b = FactBase::new();
    b.insert(term("block(a)"));
    for i in 0..250 {
        b.delete(&Term::compound("at", vec![Term::Int(i - 1)]));
        b.insert(Term::compound("at", vec![Term::Int(i)]));
        let bases = [&b, &b];
        let view = View::beliefs(&kn, &bases);
        let a = e.query(&view, &term("at(X), block(B)")).unwrap();
        assert_eq!(shown(&a), vec![format!("X={i},B=a"); 4], "update {i}");
    }
    // Two retractions per update: a rebuild after every 50 updates.
    assert_eq!(e.rebuilds, 4);
}

#[test]
fn a_query_past_its_time_is_interrupted_and_no_other_starts_until_it_ends() {
    let clauses = terms("count(0) :- !. count(N) :- M is N - 1, count(M).");
    let kn = Knowledge::load(&clauses).unwrap();
    let limits = Limits {
        max_inferences: 1 << 60,
        ..Limits::default()
    };
    let mut e = ScryerEngine::new(&clauses).unwrap().with_limits(limits);
    let mut b = FactBase::new();
    b.insert(term("b(1)"));
    let bases = [&b];
    let view = View::beliefs(&kn, &bases);
    let beliefs = |e: &mut ScryerEngine| e.query(&view, &term("b(X)")).map(|a| shown(&a));
    // The thread is up and holds the belief before the query that outlives its time.
    assert_eq!(beliefs(&mut e).unwrap(), ["X=1"]);
    // Seconds of work in scryer: far longer than the 50 ms allowed, and it does end.
    e.backstop = Duration::from_millis(50);
    match e.query(&view, &term("count(100000)")) {
        Err(KrError::Interrupted { .. }) => {}
        other => panic!("expected an interrupted query, got {other:?}"),
    }
    // scryer cannot stop it: while it runs, no second thread starts beside it.
    e.backstop = BACKSTOP;
    match beliefs(&mut e) {
        Err(err) => assert!(err.to_string().contains("still runs"), "{err}"),
        Ok(a) => panic!("a query started beside the stuck one: {a:?}"),
    }
    let end = Instant::now() + Duration::from_secs(300);
    while !e.stuck.as_ref().is_none_or(|w| w.finished()) {
        assert!(Instant::now() < end, "the stuck query never ended");
        std::thread::sleep(Duration::from_millis(20));
    }
    // Once it ended, the next query gets a new thread, given the beliefs afresh.
    assert_eq!(beliefs(&mut e).unwrap(), ["X=1"]);
}

#[test]
fn lists_of_characters_and_operators_come_back_whole() {
    let kn = Knowledge::load(&[]).unwrap();
    let mut e = ScryerEngine::new(&[]).unwrap();
    let view = View::beliefs(&kn, &[]);
    for (q, want) in [
        ("atom_chars(abc, L)", "L=[a,b,c]"),
        ("select(X, [a, b], R), !", "X=a,R=[b]"),
        ("X is 5 xor 3", "X=6"),
        ("X = f((a :- b), -, 'it''s')", "X=f((a:-b),-,'it\\'s')"),
        ("msort([2, 1.0, b, 1], L)", "L=[1.0,1,2,b]"),
        ("number_codes(N, \"42\")", "N=42"),
    ] {
        assert_eq!(shown(&e.query(&view, &term(q)).unwrap()), [want], "{q}");
    }
}
