//! One test per semantic rule of modular GOAL (A) and MARBEL (B) that differs from 2014
//! (`docs/modular-goal.md`): assembling agents from files, percept and message literals, the
//! send moods, action specification files, MARBEL's percept declarations, database and
//! environment actions, and `goal check` on projects.

use goal::agent::{Agent, AgentConfig, CycleOutput, Message};
use goal::mas::system::load_mas;
use goal::syntax::check::check_path_with_agents;
use goal::syntax::prolog::Reader;
use goal::term::Term;
use std::path::{Path, PathBuf};

/// Writes a project into a fresh directory named after the test.
fn project(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-modular-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (f, text) in files {
        std::fs::write(dir.join(f), text).expect("write");
    }
    dir
}

/// Agent `a` of definition `def` in the project's `team.mas2g`.
fn agent(dir: &Path, def: &str) -> Agent {
    let sys = load_mas(&dir.join("team.mas2g")).unwrap_or_else(|p| {
        panic!(
            "{}",
            p.iter().map(|p| p.render()).collect::<Vec<_>>().join("\n")
        )
    });
    let cfg = AgentConfig {
        seed: 1,
        agents: vec!["a".into(), "bob".into()],
        ..AgentConfig::default()
    };
    Agent::new(sys.programs[def].clone(), "a", cfg)
}

fn t(text: &str) -> Term {
    Reader::new("t").term(text, 0).expect("term").term
}

fn step(a: &mut Agent, percepts: &[&str], msgs: &[Message]) -> CycleOutput {
    let ps: Vec<Term> = percepts.iter().map(|p| t(p)).collect();
    a.step(&ps, msgs)
}

fn beliefs(a: &Agent) -> Vec<String> {
    let mut v: Vec<String> = a
        .mental_state()
        .beliefs
        .iter()
        .map(|t| t.to_string())
        .collect();
    v.sort();
    v
}

fn has(a: &Agent, fact: &str) -> bool {
    beliefs(a).iter().any(|b| b == fact)
}

const A_MAS: &str = "use \"bw4t-client-3.8.5.jar\" as environment with agentcount = \"1\".
define r as agent { use init as init module. use main as main module. use events as event module. }
launchpolicy { when * launch r. }";

const B_MAS: &str = "use \"bw4t-client-3.10.1.jar\" with agentcount = \"1\".
define r { use control for decisions. use update for updates. add zone/1. update state/1. replace in/1. }
launchpolicy { when * launch r. }";

fn a_project(name: &str, init: &str, main: &str, events: &str, extra: &[(&str, &str)]) -> Agent {
    let mut files = vec![
        ("team.mas2g", A_MAS),
        ("init.mod2g", init),
        ("main.mod2g", main),
        ("events.mod2g", events),
    ];
    files.extend_from_slice(extra);
    agent(&project(name, &files), "r")
}

const EMPTY_EVENTS: &str = "module events { if true then exit-module. }";
const IDLE_MAIN: &str = "module main { if bel(false) then exit-module. }";

#[test]
fn knowledge_beliefs_and_goals_files_fill_the_bases_once() {
    let mut a = a_project(
        "bases",
        "use k as knowledge. use b as beliefs. use g as goals.
         module init { if bel(twice(2, X)) then insert(result(X)). }",
        IDLE_MAIN,
        EMPTY_EVENTS,
        &[
            ("k.pl", ":- dynamic seen/1.\ntwice(X, Y) :- Y is 2 * X.\n"),
            ("b.pl", "colour(red).\n"),
            ("g.pl", "on(a, b), on(b, c).\n"),
        ],
    );
    step(&mut a, &[], &[]);
    assert!(has(&a, "colour(red)"));
    assert!(has(&a, "result(4)"));
    let goals: Vec<String> = a
        .mental_state()
        .attention
        .current()
        .goals()
        .iter()
        .map(|g| g.term.to_string())
        .collect();
    assert_eq!(
        goals,
        ["on(a,b),on(b,c)"],
        "one conjunctive goal per clause"
    );
}

#[test]
fn percept_literal_reads_held_percepts_and_negated_batch_items() {
    let mut a = a_project(
        "percepts",
        "module init { if true then exit-module. }",
        IDLE_MAIN,
        "module events {
            forall percept(in(R)) do insert(was(R)).
            forall percept(not(in(R))) do insert(left(R)).
            if not(percept(in(_))) then insert(outside).
        }",
        &[],
    );
    step(&mut a, &["in(r1)"], &[]);
    assert!(has(&a, "was(r1)"));
    assert!(!has(&a, "outside"));
    step(&mut a, &["not(in(r1))"], &[]);
    assert!(has(&a, "left(r1)"), "not(p) matched the batch and bound R");
    assert!(has(&a, "outside"));
}

#[test]
fn sent_literals_match_mood_and_sender_for_one_cycle() {
    let mut a = a_project(
        "sent",
        "module init { if true then exit-module. }",
        IDLE_MAIN,
        "module events {
            forall (S).sent:(hello(X)) do insert(said(S, X)).
            forall (S).sent!(go(X)) do insert(told(S, X)).
            forall (bob).sent?(where) do insert(asked).
            forall (carol).sent(hello(_)) do insert(wrong_sender).
            forall (_).sent(any) do insert(any_sender).
        }",
        &[],
    );
    let m = |content: &str| Message {
        sender: "bob".into(),
        receiver: "a".into(),
        content: t(content),
    };
    step(
        &mut a,
        &["tick"],
        &[m("hello(1)"), m("imp(go(2))"), m("int(where)"), m("any")],
    );
    for f in ["said(bob,1)", "told(bob,2)", "asked", "any_sender"] {
        assert!(has(&a, f), "{f}: {:?}", beliefs(&a));
    }
    assert!(!has(&a, "wrong_sender"));
    assert!(
        !beliefs(&a).iter().any(|b| b.starts_with("received(")),
        "messages are visible in their cycle only"
    );
}

#[test]
fn send_moods_are_in_the_keyword() {
    let mut a = a_project(
        "send",
        "module init { if true then exit-module. }",
        "module main { if true then (bob).send(p) + (bob).send:(q) + (bob).send?(r) + (bob).send!(s) + exit-module. }",
        EMPTY_EVENTS,
        &[],
    );
    let out = step(&mut a, &[], &[]);
    let sent: Vec<String> = out.messages.iter().map(|m| m.content.to_string()).collect();
    assert_eq!(sent, ["p", "q", "int(r)", "imp(s)"]);
    assert!(out.messages.iter().all(|m| m.receiver.name() == "bob"));
}

#[test]
fn action_specification_files_define_internal_and_external_actions() {
    let mut a = a_project(
        "act2g",
        "use old as beliefs. module init { if true then exit-module. }",
        "use acts as actionspec.
         module main {
            if bel(old) then note(1).
            if bel(noted(1)) then goTo(r1).
            if bel(at(r1)) then move(r1, r2).
         }",
        EMPTY_EVENTS,
        &[
            ("old.pl", "old.\n"),
            (
                "acts.act2g",
                "define note(X) as internal with pre { true } post- { old } post+ { noted(X) }
                 define goTo(P) with pre { \\+ at(_) } post { at(P) }
                 define move(X, Y) as external with pre { at(X) } post { not(at(X)), at(Y) }",
            ),
        ],
    );
    let o1 = step(&mut a, &[], &[]);
    assert!(o1.env_actions.is_empty(), "internal action not sent");
    assert!(has(&a, "noted(1)") && !has(&a, "old"));
    let o2 = step(&mut a, &[], &[]);
    assert_eq!(o2.env_actions[0].to_string(), "goTo(r1)");
    let o3 = step(&mut a, &[], &[]);
    assert_eq!(o3.env_actions[0].to_string(), "move(r1,r2)");
    assert!(has(&a, "at(r2)"));
}

#[test]
fn modules_are_called_by_declared_name_with_parameters() {
    let dir = project(
        "calls",
        &[
            ("team.mas2g", A_MAS),
            ("init.mod2g", "module init { if true then exit-module. }"),
            (
                "main.mod2g",
                "use helper as module. module main { if true then greet(bob) + exit-module. }",
            ),
            ("events.mod2g", EMPTY_EVENTS),
            (
                "helper.mod2g",
                "exit = always. module greet(X) { if true then print(X). }",
            ),
        ],
    );
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    let w: Vec<&str> = sys
        .warnings
        .iter()
        .map(|p| p.diagnostic.code.as_str())
        .collect();
    assert!(
        w.contains(&"W0603"),
        "declared name differs from file name: {w:?}"
    );
    let mut a = agent(&dir, "r");
    assert_eq!(step(&mut a, &[], &[]).printed, ["bob"]);
}

#[test]
fn marbel_percept_declarations_add_update_replace() {
    let dir = project(
        "declarations",
        &[
            ("team.mas2g", B_MAS),
            (
                "control.mod2g",
                "module control { if false then exit-module. }",
            ),
            (
                "update.mod2g",
                "module update { if true then insert(updated). }",
            ),
        ],
    );
    let mut a = agent(&dir, "r");
    step(
        &mut a,
        &["zone(z1)", "state(idle)", "in(r1)", "other(x)"],
        &[],
    );
    assert!(has(&a, "zone(z1)") && has(&a, "state(idle)") && has(&a, "in(r1)"));
    assert!(!has(&a, "other(x)"), "undeclared percepts are not stored");
    assert!(!beliefs(&a).iter().any(|b| b.starts_with("percept(")));
    // add never deletes; update replaces when new values arrive; replace mirrors what holds.
    step(&mut a, &["zone(z2)", "state(moving)", "in(r2)"], &[]);
    assert!(has(&a, "zone(z1)") && has(&a, "zone(z2)"));
    assert!(has(&a, "state(moving)") && !has(&a, "state(idle)"));
    assert!(has(&a, "in(r2)") && !has(&a, "in(r1)"));
    // No state percept: update keeps the value; no in percept: replace empties in/1.
    step(&mut a, &["tick"], &[]);
    assert!(has(&a, "state(moving)"));
    assert!(!beliefs(&a).iter().any(|b| b.starts_with("in(")));
    // A negated update percept deletes the fact.
    step(&mut a, &["not(state(moving))"], &[]);
    assert!(!has(&a, "state(moving)"));
}

#[test]
fn marbel_conditions_are_plain_literals_and_actions_go_to_the_environment() {
    let dir = project(
        "plain",
        &[
            ("team.mas2g", B_MAS),
            (
                "db.pl",
                ":- dynamic visited/1.\nvisited(start).\nnext(r1, r2).\nnear(X) :- next(_, X).\n",
            ),
            (
                "control.mod2g",
                "use db.
                 module control {
                    if in(R), next(R, N), \\+ visited(N), near(N) then goTo(N) + insert(visited(N)).
                    if visited(start), visited(r2) then delete(visited(start)) + pickUp.
                 }",
            ),
            (
                "update.mod2g",
                "module update { if true then insert(updated). }",
            ),
        ],
    );
    let mut a = agent(&dir, "r");
    let o1 = step(&mut a, &["in(r1)"], &[]);
    assert_eq!(o1.env_actions[0].to_string(), "goTo(r2)");
    let o2 = step(&mut a, &["in(r1)"], &[]);
    assert_eq!(o2.env_actions[0].to_string(), "pickUp");
    assert!(
        !has(&a, "visited(start)"),
        ".pl facts are beliefs the program may delete"
    );
}

#[test]
fn marbel_bare_use_prefers_the_knowledge_file_to_the_mas_of_the_same_name() {
    // Course projects name the MAS and the knowledge alike: `team.mas2g` beside `team.pl`.
    let dir = project(
        "samename",
        &[
            ("team.mas2g", B_MAS),
            ("team.pl", "next(r1, r2).\n"),
            (
                "control.mod2g",
                "use team.
                 module control { if in(R), next(R, N) then goTo(N). }",
            ),
            (
                "update.mod2g",
                "module update { if true then insert(updated). }",
            ),
        ],
    );
    let mut a = agent(&dir, "r");
    let o = step(&mut a, &["in(r1)"], &[]);
    assert_eq!(o.env_actions[0].to_string(), "goTo(r2)");
}

#[test]
fn marbel_exit_module_in_decisions_stops_the_agent() {
    let dir = project(
        "stop",
        &[
            ("team.mas2g", B_MAS),
            (
                "control.mod2g",
                "module control { if in(done) then exit-module. }",
            ),
            (
                "update.mod2g",
                "module update { if true then insert(updated). }",
            ),
        ],
    );
    // zone/1 and state/1 are declared but nothing reads them.
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    let w: Vec<String> = sys
        .warnings
        .iter()
        .map(|p| p.diagnostic.message.clone())
        .collect();
    assert_eq!(
        w,
        [
            "percept zone/1 is stored but never read",
            "percept state/1 is stored but never read"
        ]
    );
    let mut a = agent(&dir, "r");
    step(&mut a, &["in(start)"], &[]);
    assert!(a.stopped().is_none());
    step(&mut a, &["in(done)"], &[]);
    assert!(a.stopped().is_some());
}

#[test]
fn goal_check_reports_each_problem_in_its_own_file() {
    let dir = project(
        "check",
        &[
            ("team.mas2g", A_MAS),
            ("init.mod2g", "module init { if true then exit-module. }"),
            ("main.mod2g", "module main { if bel(a) then fly(1). }"),
            (
                "events.mod2g",
                "use missing as knowledge. use init as module. use init as module.\nmodule events { if true then exit-module. }",
            ),
        ],
    );
    let reports = check_path_with_agents(&dir);
    let problems: Vec<(String, String)> = reports
        .iter()
        .flat_map(|r| {
            let file = PathBuf::from(&r.file)
                .file_name()
                .map(|f| f.to_string_lossy().to_string())
                .unwrap_or_default();
            r.diagnostics
                .iter()
                .filter(|d| d.is_error())
                .map(move |d| (file.clone(), d.code.clone()))
        })
        .collect();
    assert!(
        problems.contains(&("events.mod2g".into(), "E0607".into())),
        "{problems:?}"
    );
    assert!(
        problems.contains(&("events.mod2g".into(), "E0612".into())),
        "{problems:?}"
    );
    // Fix the missing file: the undefined action is reported in main.mod2g.
    std::fs::write(dir.join("missing.pl"), "a.\n").expect("write");
    std::fs::write(
        dir.join("events.mod2g"),
        "use missing as knowledge. module events { if true then exit-module. }",
    )
    .expect("write");
    let reports = check_path_with_agents(&dir);
    let main = reports
        .iter()
        .find(|r| r.file.ends_with("main.mod2g"))
        .expect("main.mod2g reported");
    let d = main
        .diagnostics
        .iter()
        .find(|d| d.is_error())
        .expect("an error");
    assert_eq!(d.code, "E0104");
    assert_eq!(&main.source[d.span.clone()], "fly");
}

#[test]
fn a_module_of_another_generation_is_a_clear_error() {
    let dir = project(
        "mismatch",
        &[
            ("team.mas2g", A_MAS),
            (
                "init.mod2g",
                "main module { program { if true then exit-module. } }",
            ),
            (
                "main.mod2g",
                "use db. module main { if in(R) then goTo(R). }",
            ),
            ("db.pl", "room(r1).\n"),
            ("events.mod2g", EMPTY_EVENTS),
        ],
    );
    let p = load_mas(&dir.join("team.mas2g")).expect_err("does not load");
    let msgs: Vec<String> = p.iter().map(|p| p.diagnostic.message.clone()).collect();
    assert!(
        msgs.iter().any(|m| m.contains("is a 2014 GOAL module")),
        "{msgs:?}"
    );
    assert!(
        msgs.iter().any(|m| m.contains("is a MARBEL module")),
        "{msgs:?}"
    );
}

/// Agents `names` of definition `def` in the project's `team.mas2g`, knowing each other.
fn agents(dir: &Path, def: &str, names: &[&str]) -> Vec<Agent> {
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    let cfg = AgentConfig {
        seed: 1,
        agents: names.iter().map(|n| n.to_string()).collect(),
        ..AgentConfig::default()
    };
    names
        .iter()
        .map(|n| Agent::new(sys.programs[def].clone(), n, cfg.clone()))
        .collect()
}

/// One cycle at simulated time `ms` (what lock-step runs give the agents).
fn step_at(a: &mut Agent, ms: u64, percepts: &[&str], msgs: &[Message]) -> CycleOutput {
    a.set_clock(Some(ms as f64 / 1000.0));
    step(a, percepts, msgs)
}

#[test]
fn shutdown_module_runs_once_when_main_exits() {
    let mas = "define r as agent { use main as main module. use bye as shutdown module. }
launchpolicy { launch r. }";
    let dir = project(
        "shutdown",
        &[
            ("team.mas2g", mas),
            (
                "main.mod2g",
                "module main { if true then print(last) + exit-module. }",
            ),
            (
                "bye.mod2g",
                "module bye { if true then print(bye). if true then print(all_rules_run). }",
            ),
        ],
    );
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    assert!(
        sys.warnings.is_empty(),
        "no warning about the shutdown module"
    );
    let mut a = agent(&dir, "r");
    let out = step(&mut a, &[], &[]);
    assert_eq!(out.printed, ["last", "bye", "all_rules_run"]);
    assert!(out.stopped.is_some());
    assert!(step(&mut a, &[], &[]).printed.is_empty(), "it runs once");
}

#[test]
fn nested_blocks_inherit_the_files_order() {
    // The event module runs to completion in one cycle: what prints is what its block chose.
    let events = |order: &str| {
        format!(
            "{order} module events {{ if true then {{ if true then print(first). if true then print(second). }} }}"
        )
    };
    let run = |name: &str, order: &str| {
        let init = "module init { if true then exit-module. }";
        let mut a = a_project(name, init, IDLE_MAIN, &events(order), &[]);
        step(&mut a, &["tick"], &[]).printed
    };
    // `order = linear.` of the file: the nested block stops after its first rule that acts.
    assert_eq!(run("nested_linear", "order = linear."), ["first"]);
    // No order written: nested blocks run every rule (linearall).
    assert_eq!(run("nested_default", ""), ["first", "second"]);
}

#[test]
fn sleep_skips_cycles_by_simulated_time_and_keeps_messages() {
    let mut a = a_project(
        "sleep",
        "module init { if true then exit-module. }",
        "module main {
            if not(bel(slept)) then insert(slept) + sleep(30).
            if bel(slept), not(bel(woke)) then print(awake) + insert(woke).
         }",
        "module events { forall (S).sent(M) do print(heard(S, M)). }",
        &[],
    );
    step_at(&mut a, 0, &[], &[]);
    assert!(!a.waiting(), "a sleeping agent is stepped every round");
    let hello = Message {
        sender: "bob".into(),
        receiver: "a".into(),
        content: t("hello"),
    };
    let asleep = step_at(&mut a, 10, &["in(r1)"], &[hello]);
    assert!(
        asleep.printed.is_empty()
            && asleep
                .events
                .iter()
                .all(|e| !matches!(e, goal::agent::Event::CycleStart { .. }))
    );
    assert!(
        a.mental_state().percepts.contains(&t("in(r1)")),
        "percepts that come during sleep are taken in"
    );
    assert!(step_at(&mut a, 20, &[], &[]).printed.is_empty());
    let cycles = a.cycles();
    let woke = step_at(&mut a, 30, &[], &[]);
    assert_eq!(a.cycles(), cycles + 1, "no cycle ran while asleep");
    assert_eq!(
        woke.printed,
        ["heard(bob,hello)", "awake"],
        "the message waited for the agent"
    );
}

#[test]
fn timers_give_timer_percepts_per_interval_until_their_duration() {
    let mut a = a_project(
        "timers",
        "module init { if true then starttimer(t, 20, 50) + starttimer(stop, 10, 0). }",
        "module main { if percept(timer(stop, 2)) then canceltimer(stop). }",
        "module events { forall percept(timer(Name, N)) do print(tick(Name, N)). }",
        &[],
    );
    let mut seen = Vec::new();
    for ms in (0..=80).step_by(10) {
        seen.extend(step_at(&mut a, ms, &[], &[]).printed);
    }
    assert_eq!(
        seen,
        ["tick(stop,1)", "tick(stop,2)", "tick(t,1)", "tick(t,2)"],
        "t fires at 20 and 40 ms and ends at 50 ms; stop fires until cancelled"
    );
}

#[test]
fn channel_messages_reach_subscribers_only() {
    let dir = project(
        "channels",
        &[
            ("team.mas2g", A_MAS),
            ("init.mod2g", "module init { if bel(me(a)) then subscribe(news). }"),
            (
                "main.mod2g",
                "module main { if bel(me(bob)), not(bel(sent)) then (news).send(hello) + insert(sent). }",
            ),
            (
                "events.mod2g",
                "module events { forall (S).sent(hello) do print(heard(S)). }",
            ),
        ],
    );
    let mut ags = agents(&dir, "r", &["a", "bob"]);
    step(&mut ags[0], &[], &[]);
    let out = step(&mut ags[1], &[], &[]);
    assert!(!out.messages.is_empty());
    let to = |name: &str| -> Vec<Message> {
        out.messages
            .iter()
            .filter(|m| m.receiver.name() == name)
            .cloned()
            .collect()
    };
    let (to_a, to_bob) = (to("a"), to("bob"));
    assert_eq!(step(&mut ags[0], &[], &to_a).printed, ["heard(bob)"]);
    assert!(
        step(&mut ags[1], &[], &to_bob).printed.is_empty(),
        "bob did not subscribe"
    );
}

#[test]
fn marbel_messages_are_seen_by_the_updates_module_for_one_cycle() {
    let dir = project(
        "marbelmail",
        &[
            ("team.mas2g", B_MAS),
            (
                "control.mod2g",
                "module control { if received(_, _) then print(decisions_saw_it). }",
            ),
            (
                "update.mod2g",
                "module update { forall received(S, M) do print(got(S, M)). }",
            ),
        ],
    );
    let mut a = agent(&dir, "r");
    let m = Message {
        sender: "bob".into(),
        receiver: "a".into(),
        content: t("imp(goTo(r1))"),
    };
    assert_eq!(step(&mut a, &[], &[m]).printed, ["got(bob,imp(goTo(r1)))"]);
    assert!(
        step(&mut a, &["tick"], &[]).printed.is_empty(),
        "gone the next cycle"
    );
}

#[test]
fn modular_test_files_watch_the_tested_module() {
    use goal::testing::runner::{run_file, TestOptions};
    use goal::testing::Outcome;
    let mas = "define r as agent { use main as main module. }\nlaunchpolicy { launch r. }";
    let main = "use k as beliefs. module main {
        if bel(count(N), N < 3, M is N + 1) then delete(count(N)) + insert(count(M)).
        if bel(count(3)) then exit-module. }";
    let test = |cond: &str| {
        format!(
            "use team as mas.\ntimeout = 10.\ntest main with\n pre {{ bel(count(0)) }}\n in {{ {cond}. \
             done(insert(count(2))) leadsto bel(count(2)). }}\n post {{ bel(count(3)) }}\nr {{ do main. }}\n"
        )
    };
    let dir = project(
        "test2g",
        &[
            ("team.mas2g", mas),
            ("main.mod2g", main),
            ("k.pl", "count(0).\n"),
            ("pass.test2g", &test("eventually bel(count(3))")),
            ("fail.test2g", &test("never bel(count(2))")),
        ],
    );
    let pass = run_file(&dir.join("pass.test2g"), &TestOptions::default());
    assert_eq!(pass.len(), 1);
    assert_eq!(pass[0].outcome, Outcome::Passed, "{}", pass[0].to_text());
    let fail = run_file(&dir.join("fail.test2g"), &TestOptions::default());
    assert!(
        matches!(fail[0].outcome, Outcome::Failed(_)),
        "{}",
        fail[0].to_text()
    );
}

#[test]
fn test_blocks_named_after_a_definition_run_in_every_agent_launched_from_it() {
    use goal::testing::runner::{run_file, TestOptions};
    use goal::testing::Outcome;
    let mas = "define r as agent { use main as main module. }\nlaunchpolicy { launch r with name = bot, number = 2. }";
    let dir = project(
        "test2gdef",
        &[
            ("team.mas2g", mas),
            (
                "main.mod2g",
                "module main { if true then insert(x) + exit-module. }",
            ),
            (
                "team.test2g",
                "use team as mas.\ntest main with in { eventually bel(x). }\nr { do main. }\n",
            ),
        ],
    );
    let reports = run_file(&dir.join("team.test2g"), &TestOptions::default());
    let agents: Vec<&str> = reports.iter().map(|r| r.agent.as_str()).collect();
    assert_eq!(
        agents.len(),
        2,
        "{}",
        reports.iter().map(|r| r.to_text()).collect::<String>()
    );
    assert!(agents.iter().all(|a| a.starts_with("bot")), "{agents:?}");
    let text: String = reports.iter().map(|r| r.to_text()).collect();
    assert!(
        reports.iter().all(|r| r.outcome == Outcome::Passed),
        "{text}"
    );
}

#[test]
fn predicates_declared_dynamic_may_be_queried_before_any_fact_exists() {
    let dir = project(
        "dynamic",
        &[
            ("team.mas2g", A_MAS),
            ("init.mod2g", "use k as knowledge. module init { if bel(seen(X)) then print(X). }"),
            ("k.pl", ":- dynamic seen/1, other/2.\nvisited/1.\n"),
            ("main.mod2g", "use k as knowledge. module main { if bel(visited(R), \\+ gone(R)) then exit-module. }"),
            ("events.mod2g", EMPTY_EVENTS),
        ],
    );
    let codes: Vec<String> = check_path_with_agents(&dir.join("team.mas2g"))
        .iter()
        .flat_map(|r| {
            r.diagnostics
                .iter()
                .map(|d| format!("{}: {}", d.code, d.message))
        })
        .filter(|d| d.starts_with("E0121"))
        .collect();
    // seen/1 is declared, visited/1 too (a `p/1.` line after the directive); gone/1 is not.
    assert_eq!(codes.len(), 1, "{codes:?}");
    assert!(codes[0].contains("`gone/1`"), "{codes:?}");
}

#[test]
fn files_checked_on_their_own() {
    let dir = project(
        "alone",
        &[
            ("db.pl", ":- dynamic seen/1.\nvisited/1.\n:- initialization(main).\nroom(r1).\n"),
            ("control.mod2g", "use db. module control { if room(R), \\+ seen(R) then goTo(R). }"),
            ("acts.act2g", "define goTo(R) with pre { true } post { at(R) }\ndefine goTo(R) with pre { true } post { at(R) }\n"),
            ("main.mod2g", "use db as knowledge. module main { if room(R) then goTo(R). }"),
        ],
    );
    let codes = |f: &str| -> Vec<String> {
        check_path_with_agents(&dir.join(f))
            .iter()
            .flat_map(|r| r.diagnostics.iter().map(|d| d.code.clone()))
            .collect()
    };
    // `:- dynamic` is accepted; other directives are ignored with a warning.
    // A line `p/1.` after it is a fact with a warning (a dot where a comma was meant).
    assert_eq!(codes("db.pl"), ["W0609", "W0605"]);
    // A bare `use` of a .pl file: a MARBEL module, plain literals are fine.
    assert_eq!(codes("control.mod2g"), Vec::<String>::new());
    // The same spec twice is an error.
    assert!(
        codes("acts.act2g").contains(&"E0103".to_string()),
        "{:?}",
        codes("acts.act2g")
    );
    // In modular GOAL a plain literal is the use of a macro, which is not defined.
    assert!(
        codes("main.mod2g").contains(&"E0118".to_string()),
        "{:?}",
        codes("main.mod2g")
    );
}

#[test]
fn marbel_goal_literal_reads_a_goal_predicate_of_the_database() {
    let dir = project(
        "goalpred",
        &[
            ("team.mas2g", B_MAS),
            ("db.pl", "goal(deliver).\n"),
            (
                "control.mod2g",
                "use db. module control { if goal(X) then print(X) + exit-module. }",
            ),
            (
                "update.mod2g",
                "module update { if true then insert(updated). }",
            ),
        ],
    );
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    let w: Vec<&str> = sys
        .warnings
        .iter()
        .map(|p| p.diagnostic.code.as_str())
        .filter(|c| *c != "W0611") // the declarations of B_MAS are not read here
        .collect();
    assert_eq!(w, ["W0610"]);
    let mut a = agent(&dir, "r");
    assert_eq!(step(&mut a, &[], &[]).printed, ["deliver"]);
}

#[test]
fn load_time_errors_and_bw4t_parameter_notes() {
    // A rule in a beliefs file; a percept declared twice.
    let dir = project(
        "loaderrors",
        &[
            ("team.mas2g", A_MAS),
            (
                "init.mod2g",
                "use b as beliefs. module init { if true then exit-module. }",
            ),
            ("b.pl", "p :- q.\n"),
            ("main.mod2g", IDLE_MAIN),
            ("events.mod2g", EMPTY_EVENTS),
        ],
    );
    let p = load_mas(&dir.join("team.mas2g")).expect_err("does not load");
    assert_eq!(p[0].diagnostic.code, "E0609");
    let twice = "use \"bw4t.jar\" with agentcount = \"1\".
define r { use control for decisions. replace in/1. update in/1. }
launchpolicy { when * launch r. }";
    let dir = project(
        "twice",
        &[
            ("team.mas2g", twice),
            (
                "control.mod2g",
                "module control { if in(x) then exit-module. }",
            ),
        ],
    );
    let p = load_mas(&dir.join("team.mas2g")).expect_err("does not load");
    assert_eq!(p[0].diagnostic.code, "E0610");
    // Client parameters the built-in BW4T does not use, and an entity type it never has.
    let notes = "use \"BW4TClient.jar\" as environment with Map = \"Rainbow\", agentcount = \"2\", speed = \"20\", configfile = \"bots.xml\", clientip = \"localhost\".
define r as agent { use main as main module. }
launchpolicy { when type = robot launch r. }";
    let dir = project("notes", &[("team.mas2g", notes), ("main.mod2g", IDLE_MAIN)]);
    let sys = load_mas(&dir.join("team.mas2g")).expect("loads");
    // The client's `speed` and connection keys mean nothing here and are dropped; its bot
    // configuration files are announced as not read (the same selection as for a 2014 `.mas2g`).
    let w: Vec<(&str, &str)> = sys
        .warnings
        .iter()
        .map(|p| (p.diagnostic.code.as_str(), p.diagnostic.message.as_str()))
        .collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].0, "W0207");
    assert!(w[0].1.contains("configfile"), "{w:?}");
    let env = sys.env.expect("the built-in BW4T").params;
    assert_eq!(
        env.get("map").map(|t| t.to_string()),
        Some("rainbow".into())
    );
    assert_eq!(env.get("robots").map(|t| t.to_string()), Some("2".into()));
    assert!(!env.contains_key("clientip"));
    let codes: Vec<String> = check_path_with_agents(&dir.join("team.mas2g"))[0]
        .diagnostics
        .iter()
        .map(|d| d.code.clone())
        .collect();
    assert!(codes.contains(&"W0607".to_string()), "{codes:?}");
}

#[test]
fn macros_are_local_to_their_file() {
    let mut a = a_project(
        "macros",
        "use b as beliefs. module init { if true then exit-module. }",
        "use helper as module.
         define ready as bel(x).
         module main { if ready then helper + exit-module. }",
        EMPTY_EVENTS,
        &[
            ("b.pl", "x.\ny.\n"),
            (
                "helper.mod2g",
                "define ready as bel(y). exit = always.
                 module helper { if ready then print(helper_ready). }",
            ),
        ],
    );
    assert_eq!(step(&mut a, &[], &[]).printed, ["helper_ready"]);
    // The same name in both files: each file's own definition counts.
    let mut b = a_project(
        "macros2",
        "use b as beliefs. module init { if true then exit-module. }",
        "use helper as module.
         define ready as bel(x).
         module main { if ready then helper + exit-module. }",
        EMPTY_EVENTS,
        &[
            ("b.pl", "x.\n"),
            (
                "helper.mod2g",
                "define ready as bel(\\+ x). exit = always.
                 module helper { if ready then print(wrong). if true then print(own_macro). }",
            ),
        ],
    );
    assert_eq!(step(&mut b, &[], &[]).printed, ["own_macro"]);
}
