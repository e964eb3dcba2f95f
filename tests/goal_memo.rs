//! The goal memo (answers of a condition's leading `a-goal`/`goal-a` literal kept while the
//! module loop only evaluates rules that find no answers): each kind of change of the mental
//! state between two rules asking the same goal question must be seen by the second rule.

mod agent_support;
use agent_support::*;

/// What `forall <lead>, bel(true) do print(X)` prints in the event module, after a first rule
/// that asks `<lead>` and finds no answer (so its answers are kept) and a second rule that
/// performs `change`; from the belief `g(a)` and the goals `g(a), h(a)` and `g(b)`.
fn after(lead: &str, change: &str) -> Vec<String> {
    let src = format!(
        "init module {{ beliefs {{ g(a). }} goals {{ g(a), h(a). g(b). }} }}
         main module {{ program {{ if bel(stop) then exit-module. }} }}
         event module {{ program {{
            if {lead}, bel(X == none) then print(never).
            if bel(g(a)) then {change}.
            forall {lead}, bel(true) do print(X). }} }}
         module sub {{ program {{ if true then insert(g(b)). }} }}"
    );
    let mut a = agent(&src);
    // The event module runs from the second cycle on, when something arrived.
    run(&mut a, 1);
    step(&mut a, &["tick"], &[]).printed
}

#[test]
fn a_kept_goal_answer_does_not_survive_a_belief_insert() {
    assert_eq!(after("a-goal(g(X))", "insert(g(b))"), Vec::<String>::new());
}

#[test]
fn a_kept_goal_answer_does_not_survive_a_belief_delete() {
    assert_eq!(after("a-goal(g(X))", "delete(g(a))"), ["a", "b"]);
    assert_eq!(after("goal-a(g(X))", "delete(g(a))"), Vec::<String>::new());
}

#[test]
fn a_kept_goal_answer_does_not_survive_an_adopt_or_a_drop() {
    assert_eq!(after("a-goal(g(X))", "adopt(g(c))"), ["b", "c"]);
    assert_eq!(after("a-goal(g(X))", "drop(g(b))"), Vec::<String>::new());
}

#[test]
fn a_kept_goal_answer_does_not_survive_a_module_call() {
    assert_eq!(after("a-goal(g(X))", "sub"), Vec::<String>::new());
}

#[test]
fn kept_goal_answers_serve_rules_that_find_no_answer() {
    // Nothing changes between the rules: the third reads what the first found.
    assert_eq!(after("a-goal(g(X))", "print(mid)"), ["mid", "b"]);
    assert_eq!(after("goal-a(g(X))", "print(mid)"), ["mid", "a"]);
}

#[test]
fn a_kept_goal_answer_does_not_survive_a_cycle() {
    // Main's linear pass: the first rule finds no answer in each cycle, the second achieves
    // one goal a cycle; the third sees the goals of its own cycle.
    let mut a = agent(
        "init module { goals { g(a). g(b). } }
         main module { program {
            if a-goal(g(X)), bel(X == none) then print(never).
            if a-goal(g(X)), bel(X == a) then insert(g(a)) + print(done(X)).
            if a-goal(g(X)), bel(X == b) then insert(g(b)) + print(done(X)). } }",
    );
    assert_eq!(printed(&run(&mut a, 3)), ["done(a)", "done(b)"]);
}
