//! One test per semantic rule of the GOAL language.

mod agent_support;
use agent_support::*;
use goal::agent::StopReason;

#[test]
fn init_beliefs_and_print() {
    let mut a = agent(
        "init module { beliefs { count(0). } }
         main module { program { if bel(count(X)) then print(X) + exit-module. } }",
    );
    let outs = run(&mut a, 3);
    assert_eq!(printed(&outs), ["0"]);
    assert_eq!(a.stopped(), Some(&StopReason::MainExited));
}

#[test]
fn conjunctive_goal_query_needs_one_goal() {
    let rules = "main module { program {
        if goal(on(a,b), on(b,c)) then print(yes) + exit-module.
        if true then print(no) + exit-module. } }";
    let mut one = agent(&format!(
        "init module {{ goals {{ on(a,b), on(b,c). }} }} {rules}"
    ));
    assert_eq!(printed(&run(&mut one, 2)), ["yes"]);
    let mut two = agent(&format!(
        "init module {{ goals {{ on(a,b). on(b,c). }} }} {rules}"
    ));
    assert_eq!(printed(&run(&mut two, 2)), ["no"]);
}

#[test]
fn goal_queries_see_knowledge_but_not_beliefs() {
    let mut a = agent(
        "init module { knowledge { above(X,Y) :- on(X,Y). }
                       beliefs { on(c,d). } goals { on(a,b). } }
         main module { program {
            if goal(above(X,Y)) then print(X-Y).
            if goal(on(c,d)) then print(wrong).
            if true then exit-module. } }",
    );
    assert_eq!(run(&mut a, 1)[0].printed, ["a-b"]);
}

#[test]
fn a_goal_and_goal_a_split_a_goal_by_belief() {
    let src = |op: &str| {
        format!(
            "init module {{ beliefs {{ on(b,c). }} goals {{ on(a,b), on(b,c). }} }}
             main module {{ program {{ forall {op}(on(X,Y)) do print(X). if true then exit-module. }} }}"
        )
    };
    assert_eq!(run(&mut agent(&src("a-goal")), 1)[0].printed, ["a"]);
    assert_eq!(run(&mut agent(&src("goal-a")), 1)[0].printed, ["b"]);
    assert_eq!(run(&mut agent(&src("goal")), 1)[0].printed, ["a", "b"]);
}

#[test]
fn not_succeeds_without_binding_and_true_holds() {
    let mut a = agent(
        "init module { beliefs { p(1). } }
         main module { program {
            if not(bel(q(_))), true, bel(p(X)) then print(X) + exit-module. } }",
    );
    assert_eq!(printed(&run(&mut a, 2)), ["1"]);
}

#[test]
fn macros_expand_with_renamed_variables() {
    let mut a = agent(
        "init module { beliefs { p(1). q(1). p(2). r(5). } }
         main module { program {
            #define both(X) bel(p(X), q(X)).
            #define other(Y) bel(r(Y)).
            if both(Y), other(X) then print(Y/X) + exit-module. } }",
    );
    assert_eq!(printed(&run(&mut a, 2)), ["1/5"]);
}

#[test]
fn linear_stops_at_first_rule_that_acts() {
    let mut a = agent(
        "init module { beliefs { p. } }
         main module { program {
            if true then adopt(p) + print(never).
            if true then print(first).
            if true then print(second). } }",
    );
    let outs = run(&mut a, 2);
    assert_eq!(outs[0].printed, ["first"]);
    assert_eq!(outs[1].printed, ["first"]);
}

#[test]
fn linearall_applies_every_rule_in_one_pass() {
    let mut a = agent(
        "event module { program {
            if true then print(one).
            if true then print(two). } }
         main module { program { if true then exit-module. } }",
    );
    assert_eq!(step(&mut a, &["tick"], &[]).printed, ["one", "two"]);
}

#[test]
fn linearall_main_starts_a_new_cycle_between_acting_rules() {
    let mut a = agent(
        "main module [exit=always] { program [order=linearall] {
            if true then print(one).
            if true then print(two). } }",
    );
    let outs = run(&mut a, 3);
    assert_eq!(outs[0].printed, ["one"]);
    assert_eq!(outs[1].printed, ["two"]);
    // The pass ends (and main exits) at the start of the following cycle.
    assert!(outs[2].stopped.is_some(), "main exits after its one pass");
}

#[test]
fn forall_computes_answers_once() {
    let mut a = agent(
        "init module { beliefs { p(1). p(2). p(3). } }
         main module { program {
            forall bel(p(X)) do delete(p(1)) + delete(p(2)) + delete(p(3)) + print(X).
            if true then exit-module. } }",
    );
    assert_eq!(run(&mut a, 1)[0].printed, ["1", "2", "3"]);
    assert!(beliefs(&a).is_empty());
}

#[test]
fn a_condition_gives_each_answer_once_when_literals_bind_different_variables() {
    // The first literal answers once with X bound and once without; the second binds X in
    // the latter to the value the former had: the same answer, which `forall` acts on once.
    let mut a = agent(
        "init module { beliefs { p(1). q(1). r(a). } }
         main module { program [order=linearall] {
            forall bel(p(X) ; true), bel(q(X)) do print(X).
            forall bel(p(X) ; r(Y)), bel(q(X), r(Y)) do print(X-Y).
            if true then exit-module. } }",
    );
    let printed: Vec<String> = run(&mut a, 3).into_iter().flat_map(|o| o.printed).collect();
    assert_eq!(printed, ["1", "1-a"]);
}

#[test]
fn listall_binds_all_answers_and_does_not_fire_on_none() {
    let mut a = agent(
        "init module { beliefs { p(1). p(2). p(3). } }
         main module { program {
            listall L <- bel(q(X)) do print(none).
            listall L <- bel(p(X)) do print(L).
            if true then exit-module. } }",
    );
    assert_eq!(run(&mut a, 1)[0].printed, ["[1,2,3]"]);
}

#[test]
fn if_picks_an_answer_whose_action_runs() {
    for seed in 0..8 {
        let mut a = agent_with(
            "init module { beliefs { p(1). p(2). p(3). ok(2). }
                           actionspec { act(X) @int { pre { ok(X) } post { done(X) } } } }
             main module { program { if bel(p(X)) then act(X). } }",
            "a",
            &[],
            seed,
        );
        run(&mut a, 1);
        assert!(beliefs(&a).contains(&"done(2)".to_string()), "seed {seed}");
    }
}

#[test]
fn if_choice_depends_on_the_seed_only() {
    let src = "init module { beliefs { p(1). p(2). p(3). p(4). p(5). p(6). } }
               main module { program { if bel(p(X)) then print(X). } }";
    let pick = |seed| printed(&run(&mut agent_with(src, "a", &[], seed), 6));
    assert_eq!(pick(7), pick(7));
    let all: std::collections::BTreeSet<Vec<String>> = (0..10).map(pick).collect();
    assert!(all.len() > 1, "different seeds give different choices");
}

#[test]
fn exit_nogoals_stops_main_when_goals_are_achieved() {
    let mut a = agent(
        "init module { goals { done. } }
         main module [exit=nogoals] { program { if a-goal(done) then insert(done). } }",
    );
    let outs = run(&mut a, 3);
    assert!(goals(&a).is_empty());
    assert!(outs[0].stopped.is_none());
    assert!(
        outs[1].stopped.is_some(),
        "exit is checked when the pass ends"
    );
}

#[test]
fn exit_noaction_and_exit_module_in_nested_block() {
    let mut a = agent(
        "init module { beliefs { n(0). } }
         main module { program {
            if bel(n(N), N < 3) then count.
            if true then blocky.
            if true then print(end) + exit-module. } }
         module count [exit=noaction] { program {
            if bel(n(N), N < 3, M is N + 1) then delete(n(N)) + insert(n(M)). } }
         module blocky { program {
            if true then { if true then log(inblock). if true then exit-module. if true then print(unreached). }
            if true then print(unreached2). } }",
    );
    let outs = run(&mut a, 20);
    assert_eq!(beliefs(&a), ["n(3)"]);
    assert_eq!(printed(&outs), ["end"]);
}

#[test]
fn focus_new_gives_a_fresh_goal_base() {
    let mut a = agent(
        "init module { goals { g(outer). } }
         main module { program { if true then sub + exit-module. } }
         module sub [focus=new] { goals { g(inner). }
            program [order=linearall] {
                forall goal(g(G)) do print(G).
                if self.goal(g(outer)) then print(top_level_seen). } }",
    );
    let outs = run(&mut a, 3);
    assert_eq!(printed(&outs), ["inner", "top_level_seen"]);
    assert_eq!(goals(&a), ["g(outer)"]);
}

#[test]
fn focus_select_focuses_on_the_goal_that_made_the_rule_true() {
    for seed in 0..6 {
        let mut a = agent_with(
            "init module { goals { item(1). item(2). item(3). } }
             main module { program { if a-goal(item(X)), bel(X > 1) then handle + exit-module. } }
             module handle [focus=select] { program { forall goal(item(Y)) do print(Y). } }",
            "a",
            &[],
            seed,
        );
        let p = printed(&run(&mut a, 2));
        assert_eq!(p.len(), 1, "one goal in focus");
        assert!(p[0] == "2" || p[0] == "3", "{p:?}");
    }
}

#[test]
fn focus_filter_keeps_the_instantiated_goal_literals() {
    let mut a = agent(
        "init module { beliefs { pick(2). } goals { item(1), item(2). item(3). } }
         main module { program { if a-goal(item(X)), bel(pick(X)) then handle + exit-module. } }
         module handle [focus=filter] { program { forall goal(item(G)) do print(G). } }",
    );
    assert_eq!(printed(&run(&mut a, 2)), ["2"]);
}

#[test]
fn module_parameters_are_visible_in_rules_and_goals_but_not_in_action_specs() {
    let mut a = agent(
        "init module { beliefs { v(1). }
            actionspec { show @int { pre { v(X) } post { seen(X) } } } }
         main module { program { if true then m(7) + exit-module. } }
         module m(X) [focus=new] { goals { want(X). }
            program [order=linearall] {
                if goal(want(Y)) then print(Y).
                if bel(X == 7) then show. } }",
    );
    let outs = run(&mut a, 4);
    assert_eq!(printed(&outs), ["7"]);
    assert!(
        beliefs(&a).contains(&"seen(1)".to_string()),
        "{:?}",
        beliefs(&a)
    );
}

#[test]
fn adopt_of_a_believed_fact_does_nothing() {
    let mut a = agent(
        "init module { beliefs { p. } }
         main module { program {
            if true then adopt(p) + print(after).
            if true then adopt(q) + adopt(q) + print(twice).
            if true then exit-module. } }",
    );
    let outs = run(&mut a, 4);
    assert!(printed(&outs).is_empty());
    assert_eq!(goals(&a), ["q"]);
}

#[test]
fn blind_commitment_removes_believed_goals() {
    let mut a = agent(
        "init module { goals { g(1), g(2). g(3). } }
         main module { program {
            if bel(true) then insert(g(1)) + insert(g(3)).
            } }",
    );
    run(&mut a, 1);
    assert_eq!(goals(&a), ["g(1),g(2)"]);
}

#[test]
fn drop_removes_every_goal_that_entails_the_query() {
    let mut a = agent(
        "init module { goals { p(1). p(2), q. r. } }
         main module { program { if true then drop(p(_)) + exit-module. } }",
    );
    run(&mut a, 1);
    assert_eq!(goals(&a), ["r"]);
}

#[test]
fn insert_and_delete_route_mail_facts_and_not_deletes() {
    let mut a = agent(
        "init module { beliefs { old. } }
         main module { program {
            if true then insert(not(old), new, received(b, hi)) + exit-module. } }",
    );
    run(&mut a, 1);
    assert_eq!(beliefs(&a), ["new"]);
    let mail: Vec<String> = a
        .mental_state()
        .mailbox
        .facts()
        .iter()
        .map(|t| t.to_string())
        .collect();
    assert_eq!(mail, ["received(b,hi)"]);
}

#[test]
fn messages_wrap_their_mood_and_arrive_next_cycle() {
    let mut a = agent_with(
        "main module { program {
            if true then (b).send(!go(1)) + (b).send(?where(X)) + (b).send(:at(r1)) + (b).send(plain) + exit-module. } }",
        "a",
        &["b"],
        1,
    );
    let out = a.step(&[], &[]);
    let contents: Vec<String> = out.messages.iter().map(|m| m.content.to_string()).collect();
    assert_eq!(contents[0], "imp(go(1))");
    assert!(contents[1].starts_with("int(where("), "{contents:?}");
    assert_eq!(&contents[2..], ["at(r1)", "plain"]);
    assert!(out
        .messages
        .iter()
        .all(|m| m.sender.name() == "a" && m.receiver.name() == "b"));
    let mut b = agent_with(
        "main module { program {
            forall bel(received(S, imp(M))) do print(S/M).
            if bel(received(a, plain)) then exit-module. } }",
        "b",
        &["a"],
        1,
    );
    let outs = vec![b.step(&[], &out.messages)];
    assert_eq!(printed(&outs), ["a/go(1)"]);
}

/// The `session/4` facts an agent holds.
fn session_facts(a: &goal::agent::Agent) -> Vec<String> {
    let facts = a.mental_state().mailbox.facts();
    let session = goal::term::Sym::intern("session");
    facts
        .iter()
        .filter(|f| f.functor().is_some_and(|(n, _)| n == session))
        .map(|f| f.to_string())
        .collect()
}

#[test]
fn session_facts_are_kept_for_programs_that_can_see_them() {
    let mut a = agent_with(
        "main module { program { if true then (b).send(!go) + exit-module. } }",
        "a",
        &["b"],
        1,
    );
    let out = a.step(&[], &[]);
    // Nothing in the sender's program can see its conversations: it does not follow them.
    assert_eq!(session_facts(&a), Vec::<String>::new());
    let mut watcher = agent_with(
        "main module { program {
            if bel(session(Id, a, request, open)) then print(Id) + exit-module. } }",
        "b",
        &["a"],
        1,
    );
    assert_eq!(printed_after(&mut watcher, &out.messages), ["a-1"]);
    assert_eq!(session_facts(&watcher), ["session(a-1,a,request,open)"]);
    // `log(mb)` shows every mail fact, so a program that logs follows its conversations too.
    let mut logger = agent_with(
        "main module { program { if true then log(mb) + exit-module. } }",
        "b",
        &["a"],
        1,
    );
    logger.step(&[], &out.messages);
    assert_eq!(session_facts(&logger), ["session(a-1,a,request,open)"]);
    let mut quiet = agent_with(
        "main module { program {
            if bel(received(a, imp(go))) then print(got) + exit-module. } }",
        "b",
        &["a"],
        1,
    );
    assert_eq!(printed_after(&mut quiet, &out.messages), ["got"]);
    assert_eq!(session_facts(&quiet), Vec::<String>::new());
}

#[test]
fn a_goal_on_a_conversation_is_achieved_when_the_answer_completes_it() {
    let mut alice = agent_with(
        "init module { goals { session(alice-1, bob, query, completed). } }
         main module { program { if bel(not(sent(bob, int(x)))) then (bob).send(?x). } }",
        "alice",
        &["bob"],
        1,
    );
    let mut bob = agent_with(
        "main module { program {
            if bel(received(alice, int(x))) then (alice).send(x) + delete(received(alice, int(x))). } }",
        "bob",
        &["alice"],
        1,
    );
    // Alice asks (her goal checks see the conversation open), Bob answers.
    let question = step(&mut alice, &[], &[]).messages;
    assert_eq!(goals(&alice), ["session(alice-1,bob,query,completed)"]);
    let answer = step(&mut bob, &[], &question).messages;
    assert_eq!(answer.len(), 1);
    // The answer completes the conversation: its `session/4` fact, which lives in the mailbox
    // and not among the beliefs, achieves Alice's goal.
    step(&mut alice, &[], &answer);
    assert_eq!(
        session_facts(&alice),
        ["session(alice-1,bob,query,completed)"]
    );
    assert_eq!(goals(&alice), Vec::<String>::new());
}

#[test]
fn sendonce_skips_receivers_already_sent_to() {
    let mut a = agent_with(
        "main module { program { if true then allother.sendonce(hello). } }",
        "a",
        &["b", "c"],
        1,
    );
    let first = a.step(&[], &[]);
    assert_eq!(
        first
            .messages
            .iter()
            .map(|m| m.receiver.name())
            .collect::<Vec<_>>(),
        ["b", "c"]
    );
    let second = a.step(&[], &[]);
    assert!(second.messages.is_empty());
}

#[test]
fn send_selectors_all_self_variables_and_lists() {
    let mut a = agent_with(
        "init module { beliefs { team([b, c]). buddy(c). } }
         main module { program {
            if bel(team(T), buddy(B)) then all.send(x) + self.send(y) + (B).send(z) + (T).send(w) + exit-module. } }",
        "a",
        &["b", "c"],
        1,
    );
    let out = a.step(&[], &[]);
    let got: Vec<String> = out
        .messages
        .iter()
        .map(|m| format!("{}:{}", m.receiver, m.content))
        .collect();
    assert_eq!(got, ["a:x", "b:x", "c:x", "a:y", "c:z", "b:w", "c:w"]);
}

#[test]
fn unknown_receivers_are_warned_about_and_dropped() {
    let mut a = agent("main module { program { if true then (nobody).send(hi) + exit-module. } }");
    let out = a.step(&[], &[]);
    assert!(out.messages.is_empty());
    assert!(out.events.iter().any(
        |e| matches!(e, goal::agent::Event::Warning { message } if message.contains("nobody"))
    ));
}

#[test]
fn event_module_runs_only_when_something_is_new() {
    let mut a = agent(
        "event module { program { if true then print(event). } }
         main module { program { if bel(percept(go)) then print(main). } }",
    );
    let o1 = step(&mut a, &["go"], &[]);
    assert_eq!(o1.printed, ["event", "main"]);
    // The last cycle acted, so event runs again.
    let o2 = step(&mut a, &["go"], &[]);
    assert_eq!(o2.printed, ["event", "main"]);
    // An empty batch removes the always-percept; event runs (acted), main does not act.
    assert_eq!(step(&mut a, &[], &[]).printed, ["event"]);
    // Nothing new now: event does not run.
    assert!(step(&mut a, &[], &[]).printed.is_empty());
}

#[test]
fn runtime_errors_name_file_line_rule_and_binding() {
    let mut a = agent(
        "init module { beliefs { p(1). } }
main module { program {
    if bel(p(X)) then insert(q(X, Y)). } }",
    );
    let out = a.step(&[], &[]);
    match out.stopped {
        Some(StopReason::Error(e)) => {
            let text = e.to_string();
            assert!(text.starts_with("test.goal:3:"), "{text}");
            assert!(text.contains("main:3"), "{text}");
            assert!(text.contains("X=1"), "{text}");
        }
        other => panic!("expected an error, got {other:?}"),
    }
    assert!(
        a.step(&[], &[]).stopped.is_some(),
        "a stopped agent stays stopped"
    );
}

#[test]
fn a_module_looping_without_progress_is_a_budget_error() {
    let cfg = goal::agent::AgentConfig {
        max_steps: 10_000,
        ..Default::default()
    };
    let p = program(
        "event module { program { if true then spin. } }
         main module { program { if true then print(x). } }
         module spin [exit=never] { program { if bel(nothing) then print(y). } }",
    );
    let mut a = goal::agent::Agent::new(p, "a", cfg);
    let out = step(&mut a, &["tick"], &[]);
    match out.stopped {
        Some(StopReason::Error(e)) => assert!(e.message.contains("budget"), "{e}"),
        other => panic!("expected a budget error, got {other:?}"),
    }
}

#[test]
fn env_actions_are_returned_and_post_updates_beliefs() {
    let mut a = agent(
        "init module { beliefs { at(r1). }
            actionspec { goTo(R) @env { pre { at(From), From \\= R } post { not(at(From)), at(R) } } } }
         main module { program { if bel(at(r1)) then goTo(r2). if true then exit-module. } }",
    );
    let outs = run(&mut a, 3);
    assert_eq!(env_actions(&outs), ["goTo(r2)"]);
    assert_eq!(beliefs(&a), ["at(r2)"]);
}

#[test]
fn combos_stop_at_the_first_action_that_did_not_run() {
    let mut a = agent(
        "init module { actionspec { blocked @int { pre { fail } post { true } } } }
         main module { program { if true then print(a) + blocked + print(b) + exit-module. } }",
    );
    let outs = run(&mut a, 3);
    assert_eq!(outs[0].printed, ["a"]);
    assert!(
        outs[2].stopped.is_none(),
        "exit-module after the failed action never runs"
    );
}

#[test]
fn typed_percepts_follow_their_declared_types() {
    use goal::agent::{Agent, AgentConfig, PerceptType as P, PerceptTypes};
    let types = PerceptTypes::new([
        (("place".to_string(), 1), P::Once),
        (("at".to_string(), 1), P::OnChange),
        (("door".to_string(), 1), P::OnChangeNeg),
        (("see".to_string(), 1), P::Always),
    ]);
    let cfg = AgentConfig {
        percept_types: std::sync::Arc::new(types),
        ..AgentConfig::default()
    };
    let mut a = Agent::new(
        program("main module { program { if bel(nothing) then print(x). } }"),
        "a",
        cfg,
    );
    let seen = |a: &Agent| {
        let mut v: Vec<String> = a
            .mental_state()
            .percepts
            .facts()
            .iter()
            .map(|t| t.args()[0].to_string())
            .collect();
        v.sort();
        v
    };
    step(
        &mut a,
        &[
            "place(r1)",
            "at(r1)",
            "door(d1)",
            "door(d2)",
            "see(b1)",
            "unknown(1)",
        ],
        &[],
    );
    assert_eq!(
        seen(&a),
        [
            "at(r1)",
            "door(d1)",
            "door(d2)",
            "place(r1)",
            "see(b1)",
            "unknown(1)"
        ]
    );
    // Once stays, on-change stays until it changes, always/unknown vanish when not sent.
    step(&mut a, &["not(door(d1))"], &[]);
    assert_eq!(seen(&a), ["at(r1)", "door(d2)", "place(r1)"]);
    step(&mut a, &["at(r2)", "door(d3)"], &[]);
    assert_eq!(seen(&a), ["at(r2)", "door(d2)", "door(d3)", "place(r1)"]);
    step(&mut a, &["not(place(r1))"], &[]);
    assert_eq!(seen(&a), ["at(r2)", "door(d2)", "door(d3)"]);
}

#[test]
fn bel_percept_reads_the_percept_base() {
    let mut a = agent("main module { program { forall bel(percept(see(X))) do print(X). } }");
    assert_eq!(
        step(&mut a, &["see(b1)", "see(b2)"], &[]).printed,
        ["b1", "b2"]
    );
}

#[test]
fn a_goal_with_a_non_ground_instance_is_a_runtime_error() {
    let mut a = agent(
        "init module { knowledge { want(_) :- true. } goals { g. } }
         main module { program { if a-goal(want(X)) then print(X). } }",
    );
    match a.step(&[], &[]).stopped {
        Some(StopReason::Error(e)) => assert!(e.message.contains("not ground"), "{e}"),
        other => panic!("expected an error, got {other:?}"),
    }
}

#[test]
fn agent_and_me_facts_are_believed() {
    let mut a = agent_with(
        "main module { program { if bel(me(M)) then print(M) + exit-module. } }
         event module { program { forall bel(agent(X)) do print(X). } }",
        "a",
        &["b"],
        1,
    );
    // agent/1 facts come in name order (one shared list for the whole system).
    assert_eq!(step(&mut a, &["tick"], &[]).printed, ["a", "b", "a"]);
}

#[test]
fn log_is_not_a_real_action() {
    let mut a = agent(
        "main module { program {
            if true then log(hello).
            if true then print(after) + exit-module. } }",
    );
    let out = a.step(&[], &[]);
    assert_eq!(out.printed, ["after"], "log does not end a linear pass");
    assert!(out
        .events
        .iter()
        .any(|e| matches!(e, goal::agent::Event::Log { text } if text == "hello")));
}

#[test]
fn ten_thousand_agents_share_one_program() {
    let p = program(
        "init module { beliefs { n(0). } }
         main module { program { if bel(n(X), Y is X + 1) then delete(n(X)) + insert(n(Y)). } }",
    );
    let mut agents: Vec<goal::agent::Agent> = (0..10_000)
        .map(|i| {
            goal::agent::Agent::new(
                p.clone(),
                &format!("bot{i}"),
                goal::agent::AgentConfig {
                    seed: i,
                    trace: goal::agent::TraceLevel::Off,
                    ..Default::default()
                },
            )
        })
        .collect();
    for a in agents.iter_mut() {
        a.step(&[], &[]);
    }
    assert_eq!(
        std::sync::Arc::strong_count(&p),
        10_001,
        "no per-agent copy of the program"
    );
    assert!(agents.iter().all(|a| beliefs(a) == ["n(1)"]));
}

#[test]
fn newpercept_holds_only_the_current_batch() {
    use goal::agent::{Agent, AgentConfig, PerceptType, PerceptTypes};
    let cfg = AgentConfig {
        percept_types: std::sync::Arc::new(PerceptTypes::new([(
            ("at".to_string(), 1),
            PerceptType::OnChange,
        )])),
        ..AgentConfig::default()
    };
    let mut a = Agent::new(
        program(
            "main module { program {
                if bel(newpercept(at(R))) then print(arrived(R)).
                if bel(percept(at(R))) then print(still(R)). } }",
        ),
        "a",
        cfg,
    );
    assert_eq!(step(&mut a, &["at(r1)"], &[]).printed, ["arrived(r1)"]);
    assert_eq!(step(&mut a, &[], &[]).printed, ["still(r1)"]);
}

#[test]
fn log_bb_writes_the_belief_base() {
    let mut a = agent(
        "init module { beliefs { p(1). q. } }
         main module { program { if true then log(bb) + exit-module. } }",
    );
    let out = a.step(&[], &[]);
    assert!(out
        .events
        .iter()
        .any(|e| matches!(e, goal::agent::Event::Log { text } if text == "p(1)\nq")));
}

#[test]
fn nested_blocks_inherit_bindings_and_run_linearall() {
    let mut a = agent(
        "init module { beliefs { p(1). p(2). q(2). r(2). } }
         event module { program {
            forall bel(p(X)) do {
                if bel(q(X)) then print(q(X)).
                if bel(r(X)) then print(r(X)).
            } } }
         main module { program { if true then exit-module. } }",
    );
    assert_eq!(step(&mut a, &["tick"], &[]).printed, ["q(2)", "r(2)"]);
}

#[test]
fn randomall_applies_every_rule_in_a_seeded_random_order() {
    let src = "event module { program [order=randomall] {
            if true then print(a). if true then print(b). if true then print(c). if true then print(d). } }
         main module { program { if true then exit-module. } }";
    let order = |seed| step(&mut agent_with(src, "x", &[], seed), &["tick"], &[]).printed;
    let mut first = order(1);
    assert_eq!(order(1), first, "same seed, same order");
    first.sort();
    assert_eq!(first, ["a", "b", "c", "d"], "every rule applies once");
    let orders: std::collections::BTreeSet<Vec<String>> = (0..10).map(order).collect();
    assert!(orders.len() > 1, "the order depends on the seed");
}

#[test]
fn random_order_applies_one_acting_rule() {
    let src = "main module { program [order=random] {
            if true then print(a). if true then print(b). if true then print(c). } }";
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..10 {
        let out = agent_with(src, "x", &[], seed).step(&[], &[]);
        assert_eq!(out.printed.len(), 1);
        seen.insert(out.printed[0].clone());
    }
    assert!(seen.len() > 1);
}

#[test]
fn adaptive_runs_as_random_with_a_warning() {
    let p = program("main module { program [order=adaptive] { if true then print(a). } }");
    assert!(p.warnings.iter().any(|w| w.message.contains("adaptive")));
    let mut a = goal::agent::Agent::new(p, "a", Default::default());
    assert_eq!(a.step(&[], &[]).printed, ["a"]);
}

#[test]
fn self_adopt_goes_to_the_top_level_goal_base() {
    let mut a = agent(
        "main module { program { if true then sub + exit-module. } }
         module sub [focus=new] { program {
            if true then self.adopt(later) + adopt(here). } }",
    );
    run(&mut a, 3);
    assert_eq!(goals(&a), ["later"], "the focused goal base was popped");
}

#[test]
fn an_unbound_variable_in_a_send_selector_is_a_runtime_error() {
    let mut a = agent("main module { program { if bel(me(M)) then (Who).send(hi). } }");
    match a.step(&[], &[]).stopped {
        Some(StopReason::Error(e)) => {
            assert!(e.message.contains("selector not bound"), "{e}")
        }
        other => panic!("expected an error, got {other:?}"),
    }
}

#[test]
fn exit_module_in_a_called_module_ends_only_that_module() {
    let mut a = agent(
        "main module { program { if true then sub + print(back). } }
         module sub [exit=never] { program { if true then exit-module. } }",
    );
    assert_eq!(a.step(&[], &[]).printed, ["back"]);
    assert!(a.stopped().is_none());
}

#[test]
fn bel_conjunctions_with_negation_keep_prolog_answers_and_order() {
    let mut a = agent(
        "init module { knowledge { odd(X) :- 1 is X mod 2. }
                       beliefs { p(4). p(1). p(3). p(2). q(2). r(3, a). s(1, b). s(4, c). } }
         event module { program {
            forall bel(p(X), not(q(X)), \\+ r(X, _), s(X, Y), not(odd(X))) do print(X/Y).
            forall bel(p(X), !, not(q(X))) do print(cut(X)). } }
         main module { program { if true then exit-module. } }",
    );
    assert_eq!(step(&mut a, &["tick"], &[]).printed, ["4/c", "cut(4)"]);
}

/// A message from `from` to agent `a` with (mood-wrapped) content `text`.
fn msg(from: &str, text: &str) -> goal::agent::Message {
    goal::agent::Message {
        sender: from.into(),
        receiver: "a".into(),
        content: t(text),
    }
}

/// Everything printed in a step with `msgs` and the cycles after it that the agent needs.
fn printed_after(a: &mut goal::agent::Agent, msgs: &[goal::agent::Message]) -> Vec<String> {
    let mut outs = vec![step(a, &[], msgs)];
    outs.extend(run(a, 6));
    printed(&outs)
}

#[test]
fn messages_update_the_mental_model_of_their_sender() {
    let src = "main module { program [order=linearall] {
        forall (b).bel(at(R)), not(bel(said(at(R)))) do print(at(R)) + insert(said(at(R))).
        forall (b).a-goal(has(X)), not(bel(said(want(X)))) do print(want(X)) + insert(said(want(X))).
        forall (b).goal-a(has(X)), not(bel(said(got(X)))) do print(got(X)) + insert(said(got(X))).
        forall not((b).bel(at(r1))), bel(said(at(r1))), not(bel(said(gone))) do print(gone) + insert(said(gone)).
    } }";
    let mut a = agent_with(src, "a", &["b"], 1);
    // Indicative: a belief; imperative: a goal of the sender (not yet achieved).
    let p = printed_after(&mut a, &[msg("b", "at(r1)"), msg("b", "imp(has(box))")]);
    assert_eq!(p, ["at(r1)", "want(box)"]);
    // Interrogative: the sender does not know it. An indicative `has(box)` achieves the goal,
    // which is then dropped from the model (blind commitment), so goal-a never holds.
    let p = printed_after(&mut a, &[msg("b", "int(at(r1))"), msg("b", "has(box)")]);
    assert_eq!(p, ["gone"]);
}

#[test]
fn an_open_question_received_is_deleted_like_any_message() {
    // An interrogative send may leave variables open; the receiver must be able to clear it.
    let src = "main module { program [order=linearall] {
        forall bel(received(X, int(M))) do delete(received(X, int(M))) + print(asked(X)).
        if bel(received(_, _)) then print(left).
    } }";
    let mut a = agent_with(src, "a", &["b"], 1);
    let p = printed_after(&mut a, &[msg("b", "int(at(_, red))")]);
    assert_eq!(p, ["asked(b)"]);
    // Any other delete with variables is still a runtime error.
    let src = "main module { program { if bel(received(_, int(M))) then delete(seen(M)). } }";
    let mut a = agent_with(src, "a", &["b"], 1);
    let o = step(&mut a, &[], &[msg("b", "int(at(_, red))")]);
    match o.stopped {
        Some(StopReason::Error(e)) => assert!(e.message.contains("is not ground"), "{e:?}"),
        other => panic!("expected a runtime error, got {other:?}"),
    }
}

#[test]
fn an_open_question_keeps_a_repeated_variable_shared() {
    // `?q(Z, Z)` asks about one thing twice: the parts a condition names stay the same
    // variable, whether a plan, the engine or a second literal reads them, and the message is
    // deleted with the variables the condition gave.
    let src = "main module { program [order=linearall] {
        if bel(received(b, int(q(X, Y))), X == Y) then print(same).
        if bel(received(b, int(q(X, Y)))), bel(X == Y) then print(again).
        if bel(received(b, int(q(X, Y)))) then delete(received(b, int(q(X, Y)))) + print(gone).
        if bel(received(_, _)) then print(left).
    } }";
    let mut a = agent_with(src, "a", &["b"], 1);
    let p = printed_after(&mut a, &[msg("b", "int(q(Z, Z))")]);
    assert_eq!(p, ["same", "again", "gone"]);
    // Two different variables are not the same.
    let mut a = agent_with(src, "a", &["b"], 1);
    let p = printed_after(&mut a, &[msg("b", "int(q(Z, W))")]);
    assert_eq!(p, ["gone"]);
}

#[test]
fn all_needs_every_model_and_some_any() {
    let src = "main module { program [order=linearall] {
        forall allother.bel(p(X)), not(bel(seen(allother(X)))) do print(allother(X)) + insert(seen(allother(X))).
        forall someother.bel(p(X)), not(bel(seen(some(X)))) do print(someother(X)) + insert(seen(some(X))).
        forall all.bel(p(X)), not(bel(seen(all(X)))) do print(all(X)) + insert(seen(all(X))).
        forall (b, c).bel(p(X)), not(bel(seen(both(X)))) do print(both(X)) + insert(seen(both(X))).
    } }";
    let mut a = agent_with(src, "a", &["b", "c"], 1);
    let mut p = printed_after(&mut a, &[msg("b", "p(1), p(2)"), msg("c", "p(2), p(3)")]);
    p.sort();
    // `all` includes `a` itself, which believes no p/1.
    assert_eq!(
        p,
        [
            "allother(2)",
            "both(2)",
            "someother(1)",
            "someother(2)",
            "someother(3)"
        ]
    );
}

#[test]
fn models_are_only_kept_by_programs_that_query_them() {
    let plain = agent_with(
        "main module { program { if bel(true) then print(x). } }",
        "a",
        &["b"],
        1,
    );
    assert!(!plain.mental_state().models.enabled);
    let mut with = agent_with(
        "main module { program { if (b).bel(q) then print(q). } }",
        "a",
        &["b"],
        1,
    );
    assert!(with.mental_state().models.enabled);
    assert_eq!(printed_after(&mut with, &[msg("b", "q")])[0], "q");
}

#[test]
fn a_cycle_that_did_nothing_leaves_the_agent_waiting_and_the_next_step_is_a_no_op() {
    let mut a = agent(
        "init module { beliefs { n(0). } }
         main module { program { if bel(n(1)) then print(one). } }",
    );
    let first = a.step(&[], &[]);
    assert!(first.waiting && !first.skipped);
    let second = a.step(&[], &[]);
    assert!(second.waiting && second.skipped);
    assert_eq!(a.cycles(), 1, "the no-op step runs no cycle");
    // Printing is an action: an agent that printed is not waiting.
    let mut p = agent("main module { program [order=linearall] { if true then print(x). } }");
    assert!(!p.step(&[], &[]).waiting);
}

/// True when the agent's step warned that an `if` condition was cut at 1,000 answers.
fn warned_cut(out: &goal::agent::CycleOutput) -> bool {
    out.events.iter().any(|e| {
        matches!(e, goal::agent::Event::Warning { message }
            if message.contains("only the first 1000 were considered"))
    })
}

#[test]
fn if_considers_the_first_thousand_answers_of_an_infinite_condition() {
    let mut a =
        agent("main module { program { if bel(between(1, inf, X)), bel(X > 5) then print(X). } }");
    let out = a.step(&[], &[]);
    let x: u64 = out.printed[0].parse().unwrap();
    assert!((6..=1000).contains(&x), "{x}");
    assert!(warned_cut(&out));
    // Warned once per rule: the next cycles only act.
    let next = a.step(&[], &[]);
    assert_eq!(next.printed.len(), 1);
    assert!(!warned_cut(&next));
}

#[test]
fn if_with_a_finite_condition_is_not_cut_and_forall_takes_every_answer() {
    let mut a = agent(
        "event module { program {
            forall bel(between(1, 1500, X)) do insert(n(X)).
            if bel(between(1, 10, X)) then print(X). } }
         main module { program { if true then exit-module. } }",
    );
    let out = step(&mut a, &["tick"], &[]);
    assert!(!warned_cut(&out));
    assert_eq!(
        beliefs(&a).iter().filter(|b| b.starts_with("n(")).count(),
        1500
    );
    assert_eq!(out.printed.len(), 1);
}

#[test]
fn goal_checks_after_updates_see_knowledge_percepts_and_conjunctions() {
    // `done` is achieved through knowledge by a fact of another predicate; `on(a,b), on(b,c)`
    // by its first fact inserted after its second; `percept(go)` by a percept, and dropped by
    // the goal check after an unrelated update. The others stay, in adoption order.
    let mut a = agent(
        "init module { knowledge { done :- count(2). }
                       beliefs { count(0). }
                       goals { keep(1). done. (on(a,b), on(b,c)). percept(go). keep(2). } }
         main module { program {
            if bel(count(N), N < 2, M is N + 1) then delete(count(N)) + insert(count(M)).
            if bel(count(2), not(on(b,c))) then insert(on(b,c)).
            if bel(count(2), not(on(a,b))) then insert(on(a,b)).
            if bel(percept(go)) then insert(seen).
         } }",
    );
    let all = [
        "keep(1)",
        "done",
        "on(a,b),on(b,c)",
        "percept(go)",
        "keep(2)",
    ];
    run(&mut a, 1);
    assert_eq!(goals(&a), all);
    run(&mut a, 1);
    let rest = ["keep(1)", "on(a,b),on(b,c)", "percept(go)", "keep(2)"];
    assert_eq!(goals(&a), rest);
    run(&mut a, 1);
    assert_eq!(goals(&a), rest);
    run(&mut a, 1);
    assert_eq!(goals(&a), ["keep(1)", "percept(go)", "keep(2)"]);
    step(&mut a, &["go"], &[]);
    assert_eq!(beliefs(&a), ["count(2)", "on(a,b)", "on(b,c)", "seen"]);
    assert_eq!(goals(&a), ["keep(1)", "keep(2)"]);
}

#[test]
fn delete_removes_the_fact_its_bindings_name_and_reports_it() {
    let mut a = agent(
        "init module { beliefs { seen(1, a). seen(2, b). seen(3, a). count(f(1)). } }
         main module { program {
            forall bel(seen(X, a)) do delete(seen(X, a)).
            if bel(count(C)) then delete(count(C)) + delete(seen(9, z)) + insert(done).
            if bel(done, seen(X, Y)) then print(X-Y) + exit-module. } }",
    );
    let outs = run(&mut a, 3);
    let shown = |o: &goal::agent::CycleOutput| format!("{:?}", o.events);
    let first = shown(&outs[0]);
    for fact in ["seen(1,a)", "seen(3,a)"] {
        assert!(first.contains(&format!("BeliefDeleted {{ fact: \"{fact}\" }}")));
        assert!(first.contains(&format!("action: \"delete({fact})\"")));
    }
    let second = shown(&outs[1]);
    assert!(second.contains("BeliefDeleted { fact: \"count(f(1))\" }"));
    // A fact not believed is no change, but the delete is performed.
    assert!(!second.contains("BeliefDeleted { fact: \"seen(9,z)\" }"));
    assert!(second.contains("action: \"delete(seen(9,z))\""));
    assert_eq!(printed(&outs), ["2-b"]);
    assert_eq!(beliefs(&a), ["done", "seen(2,b)"]);
}

#[test]
fn messages_of_this_cycle_answer_every_literal_that_reads_them() {
    let mut a = agent_with(
        "main module { program { forall bel(true) do (b).send(hello(1)) + (b).send(hello(2))
            + (b).send(hello(3)) + exit-module. } }",
        "a",
        &["b"],
        1,
    );
    let sent = step(&mut a, &[], &[]).messages;
    assert_eq!(sent.len(), 3);
    // The messages arrive in b's next cycle and wait aside until an action settles them into
    // the mailbox: a literal asked under each answer of the literal before it, a first literal
    // and a conjunct after another each see them as the cycle's first reader.
    for (rule, wanted) in [
        (
            "forall bel(x(X)), bel(received(a, hello(X))) do print(X).",
            ["1", "3"].as_slice(),
        ),
        ("if bel(received(a, hello(2))) then print(2).", &["2"]),
        (
            "forall bel(x(X), received(a, hello(X))) do print(X).",
            &["1", "3"],
        ),
    ] {
        let src = format!(
            "init module {{ beliefs {{ x(1). x(3). }} }}
             main module {{ program [order=linearall] {{ {rule} if true then exit-module. }} }}"
        );
        let mut b = agent_with(&src, "b", &["a"], 1);
        assert_eq!(printed_after(&mut b, &sent), wanted, "{rule}");
    }
}
