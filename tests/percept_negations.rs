//! Negated percepts as programs for BW4T clients up to 3.8 read them: in the cycle a `not(p)`
//! arrives, `bel(percept(not(p)))` holds and binds variables; `newpercept/1` reads the raw batch.

mod agent_support;
use agent_support::*;

#[test]
fn a_negated_percept_deletes_a_belief_in_the_cycle_it_arrives() {
    let mut a = agent(
        "main module { program { if bel(never) then print(never). } }
         event module { program {
            forall bel(percept(in(R))) do insert(in(R)).
            forall bel(percept(not(in(R)))) do delete(in(R)) + print(left(R)).
         } }",
    );
    step(&mut a, &["in(room1)"], &[]);
    assert!(
        beliefs(&a).contains(&"in(room1)".to_string()),
        "{:?}",
        beliefs(&a)
    );
    let out = step(&mut a, &["not(in(room1))"], &[]);
    assert_eq!(out.printed, ["left(room1)"]);
    assert!(!beliefs(&a).contains(&"in(room1)".to_string()));
    // The negation belongs to its own cycle only.
    assert!(step(&mut a, &["tick"], &[]).printed.is_empty());
}

#[test]
fn newpercept_reads_the_raw_batch_negations_included() {
    let mut a = agent(
        "main module { program { if bel(never) then print(never). } }
         event module { program { forall bel(newpercept(P)) do print(P). } }",
    );
    let out = step(&mut a, &["in(room1)", "not(atBlock(3))"], &[]);
    assert_eq!(out.printed, ["in(room1)", "not(atBlock(3))"]);
}
