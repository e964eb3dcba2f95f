//! A BW4T-like robot agent for the cycle benchmark: 40 rules, 200 initial beliefs, and 20
//! percepts that change every cycle.
#![allow(dead_code)]

use goal::term::Term;

/// The robot program text: 10 event rules, 30 main rules (one of which acts each cycle).
pub fn robot_program() -> String {
    let mut beliefs = String::new();
    for i in 0..50 {
        beliefs.push_str(&format!("room('Room{i}'). "));
    }
    for i in 0..100 {
        beliefs.push_str(&format!("block({i}, color{}). ", i % 7));
    }
    for i in 0..50 {
        beliefs.push_str(&format!("route('Room{i}', 'Room{}'). ", (i + 1) % 50));
    }
    let mut main_rules = String::new();
    // 28 rules whose conditions fail after some work (the usual shape of a BW4T robot).
    for i in 0..28 {
        main_rules.push_str(&format!(
            "if bel(holding(B), block(B, color{c}), target(T{i})) then goTo(T{i}).\n",
            c = i % 7
        ));
    }
    main_rules.push_str("if a-goal(visited(R)), bel(at(Here), route(Here, R)) then goTo(R).\n");
    main_rules.push_str("if bel(at(Here), route(Here, Next)) then goTo(Next).\n");
    let mut event_rules = String::new();
    event_rules.push_str("forall bel(percept(at(R)), not(at(R))) do insert(at(R)).\n");
    event_rules.push_str("forall bel(at(R), not(percept(at(R)))) do delete(at(R)).\n");
    event_rules
        .push_str("forall bel(percept(seen(I, T)), not(seen(I, T))) do insert(seen(I, T)).\n");
    event_rules
        .push_str("forall bel(seen(I, T), not(percept(seen(I, T)))) do delete(seen(I, T)).\n");
    for i in 0..6 {
        event_rules.push_str(&format!(
            "forall bel(received(S, msg{i}(X))) do delete(received(S, msg{i}(X))) + insert(heard{i}(X)).\n"
        ));
    }
    format!(
        "init module {{
  knowledge {{ near(A, B) :- route(A, B). near(A, B) :- route(B, A). }}
  beliefs {{ {beliefs} at('Room0'). }}
  goals {{ visited('Room7'). }}
  actionspec {{ goTo(R) @env {{ pre {{ at(H), H \\= R }} post {{ not(at(H)), at(R) }} }} }}
}}
main module {{ program {{
{main_rules}}} }}
event module {{ program {{
{event_rules}}} }}
"
    )
}

/// An idle agent: nothing to do, no percepts.
pub fn idle_program() -> String {
    "init module { beliefs { waiting. } }
main module { program { if bel(go) then print(go). } }
event module { program { forall bel(percept(P), not(seen(P))) do insert(seen(P)). } }"
        .to_string()
}

/// The 20 percepts of cycle `n` (position of the robot and 19 `seen/2` facts that change).
pub fn percepts(n: u64) -> Vec<Term> {
    let mut v = vec![Term::compound(
        "at",
        vec![Term::atom(&format!("Room{}", n % 50))],
    )];
    for i in 0..19 {
        v.push(Term::compound(
            "seen",
            vec![Term::Int(i), Term::Int(n as i64)],
        ));
    }
    v
}
