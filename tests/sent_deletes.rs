//! A `delete` of the `sent/2` fact of the send just before it in a combo (found by the mark the
//! send leaves, see `message::link_sent_deletes`) removes exactly the fact matching would: each
//! case here is one where the mark must not be used, or must be used for the right fact.

mod agent_support;
use agent_support::*;
use goal::agent::{Agent, AgentConfig, TraceLevel};

/// The mail facts of an agent `a` (knowing `b` and `c`) after one cycle of `combo`, and the
/// receivers of the messages it sent; the same with and without a trace (which settles the
/// mailbox after each action, so the marks are used only without one).
fn mail_after(combo: &str) -> (Vec<String>, Vec<String>) {
    let src = format!(
        "init module {{ beliefs {{ team([b, c]). }} }}
         main module {{ program {{ if bel(team(T)) then {combo} + exit-module. }} }}"
    );
    let run = |trace| {
        let cfg = AgentConfig {
            agents: vec!["b".into(), "c".into()],
            trace,
            ..AgentConfig::default()
        };
        let mut a = Agent::new(program(&src), "a", cfg);
        let out = a.step(&[], &[]);
        let mail = a.mental_state().mailbox.facts().iter();
        let sent = out.messages.iter();
        let sent = sent.map(|m| format!("{}:{}", m.receiver, m.content));
        (mail.map(|f| f.to_string()).collect(), sent.collect())
    };
    let quiet: (Vec<String>, Vec<String>) = run(TraceLevel::Off);
    assert_eq!(quiet, run(TraceLevel::Rules), "{combo}");
    quiet
}

#[test]
fn the_sent_fact_of_the_send_just_before_goes() {
    let (mail, sent) = mail_after("(b).send(!tok(1, 2)) + delete(sent(b, imp(tok(1, 2))))");
    assert!(mail.is_empty(), "{mail:?}");
    assert_eq!(sent, ["b:imp(tok(1,2))"]);
}

#[test]
fn a_fact_that_differs_in_a_nested_argument_stays() {
    let (mail, _) = mail_after("(b).send(!tok(1, 2)) + delete(sent(b, imp(tok(1, 3))))");
    assert_eq!(mail, ["sent(b,imp(tok(1,2)))"]);
}

#[test]
fn a_send_to_a_list_of_receivers_leaves_no_mark() {
    // The delete names `sent([b, c], w)`, which is neither fact the send held.
    let (mail, _) = mail_after("(T).send(w) + delete(sent(T, w))");
    assert_eq!(mail, ["sent(b,w)", "sent(c,w)"]);
}

#[test]
fn only_the_nearest_send_is_linked() {
    let (mail, _) = mail_after("(b).send(x) + (c).send(y) + delete(sent(b, x))");
    assert_eq!(mail, ["sent(c,y)"]);
}

#[test]
fn a_send_that_holds_nothing_forgets_the_mark_of_the_one_before() {
    // `nobody` is no agent: the second send holds no fact, and the delete finds none.
    let (mail, sent) = mail_after("(c).send(y) + (nobody).send(x) + delete(sent(nobody, x))");
    assert_eq!(mail, ["sent(c,y)"]);
    assert_eq!(sent, ["c:y"]);
}

#[test]
fn a_second_delete_of_the_same_fact_finds_nothing() {
    let (mail, _) =
        mail_after("(c).send(y) + (b).send(x) + delete(sent(b, x)) + delete(sent(b, x))");
    assert_eq!(mail, ["sent(c,y)"]);
}

#[test]
fn a_resend_of_a_held_fact_deletes_the_one_held() {
    let (mail, sent) = mail_after("(c).send(y) + (b).send(x) + (b).send(x) + delete(sent(b, x))");
    assert_eq!(mail, ["sent(c,y)"]);
    assert_eq!(sent, ["c:y", "b:x", "b:x"]);
}

#[test]
fn a_fact_deleted_and_sent_again_in_the_combo_goes_again() {
    let combo = "(b).send(x) + delete(sent(b, x)) + (c).send(y) + (b).send(x) + delete(sent(b, x))";
    let (mail, _) = mail_after(combo);
    assert_eq!(mail, ["sent(c,y)"]);
}

#[test]
fn an_action_between_that_settles_the_mailbox_makes_the_mark_stale() {
    // `insert` settles the held fact into the fact base first; the delete then matches it there.
    let (mail, _) = mail_after("(c).send(y) + (b).send(x) + insert(p) + delete(sent(b, x))");
    assert_eq!(mail, ["sent(c,y)"]);
}
