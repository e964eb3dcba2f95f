//! The query fast paths added for the benchmarks give the engine's answers: a condition whose
//! first literal names a predicate without facts fails at once unless a built-in or a knowledge
//! rule answers it; goal queries over a goal's own facts bind the same variables.

use goal::agent::{Agent, AgentConfig, Program, TraceLevel};

fn printed(src: &str, cycles: usize) -> Vec<String> {
    let p = Program::from_source("t.goal", src)
        .unwrap_or_else(|d| panic!("{}", d.iter().map(|x| x.render(src)).collect::<String>()));
    let cfg = AgentConfig {
        trace: TraceLevel::Off,
        ..AgentConfig::default()
    };
    let mut a = Agent::new(p, "t", cfg);
    let mut out = Vec::new();
    for _ in 0..cycles {
        out.extend(a.step(&[], &[]).printed);
    }
    out
}

#[test]
fn absent_facts_fail_but_rules_and_builtins_answer() {
    let out = printed(
        "init module { knowledge { derived(X) :- base(X). base(1). } }
         main module { program [order=linearall] {
            if bel(missing(X)) then print(missing(X)).
            if bel(derived(X)) then print(derived(X)).
            if bel(member(X, [a]), X = a) then print(member(X)).
            if bel(not(missing(_))) then print(none) + exit-module.
         } }",
        6,
    );
    assert_eq!(out, ["derived(1)", "member(a)", "none"]);
}

#[test]
fn facts_inserted_later_are_found() {
    let out = printed(
        "main module { program [order=linearall] {
            if bel(seen(X)) then print(seen(X)) + exit-module.
            if bel(not(seen(_))) then insert(seen(1)).
         } }",
        3,
    );
    assert_eq!(out, ["seen(1)"]);
}

#[test]
fn goal_queries_bind_like_the_engine() {
    let out = printed(
        "init module { goals { at(a, 1), at(b, 2). want(c). } }
         main module { program [order=linearall] {
            forall a-goal(at(X, N)) do print(g(X, N)).
            if goal(want(W)), not(goal(want(d))) then print(w(W)).
            if goal(at(a, _)) then print(yes) + exit-module.
         } }",
        6,
    );
    assert_eq!(out, ["g(a,1)", "g(b,2)", "w(c)", "yes"]);
}

#[test]
fn goal_fact_answers_keep_goal_order_and_drop_repeats() {
    // Goals of one fact and conjunctions sharing a fact (`fib(1)` twice): answers in adoption
    // order, each once; a believed fact answers `goal-a` and not `a-goal`.
    let out = printed(
        "init module {
            beliefs { fib(0). }
            goals { fib(3). fib(2), fib(1). fib(1). fib(0), fib(4). fib(5). }
         }
         main module { program [order=linearall] {
            forall a-goal(fib(N)) do print(a(N)).
            forall goal-a(fib(N)) do print(b(N)).
            forall a-goal(fib(1)) do print(c(1)).
         } }",
        3,
    );
    assert_eq!(
        out,
        ["a(3)", "a(2)", "a(1)", "a(4)", "a(5)", "b(0)", "c(1)"]
    );
}

#[test]
fn goals_of_one_fact_answer_once_each_in_adoption_order() {
    let out = printed(
        "init module { beliefs { fib(2). } goals { fib(4). fib(1). fib(2). fib(3). } }
         main module { program [order=linearall] {
            forall a-goal(fib(N)) do print(a(N)).
            forall goal-a(fib(N)) do print(b(N)).
            if true then exit-module.
         } }",
        3,
    );
    assert_eq!(out, ["a(4)", "a(1)", "a(3)"]);
}

#[test]
fn goal_facts_inserted_in_the_cycle_are_no_a_goals() {
    // Goals known not believed since the last goal check skip the belief lookup: an inserted
    // fact achieves its one-fact goal, and in a goal of two facts it is a `goal-a` fact (not an
    // `a-goal` one) while the goal stays.
    let src = "init module { goals { fib(1). fib(2). (fib(3), fib(4)). fib(5). } }
         main module { program [order=linearall] {
            if a-goal(fib(2)) then insert(fib(2)) + insert(fib(4)).
            forall a-goal(fib(N)) do print(a(N)).
            forall goal-a(fib(N)) do print(b(N)).
         } }";
    let p = Program::from_source("t.goal", src).expect("program");
    let cfg = AgentConfig {
        trace: TraceLevel::Off,
        ..AgentConfig::default()
    };
    let mut a = Agent::new(p, "t", cfg);
    let out: Vec<Vec<String>> = (0..3).map(|_| a.step(&[], &[]).printed).collect();
    // One rule acts per cycle here: the insert, then the two `forall` rules.
    assert_eq!(out, [vec![], vec!["a(1)", "a(3)", "a(5)"], vec!["b(4)"]]);
}
