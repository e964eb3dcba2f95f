//! The agent hooks `goal test` relies on: a controlled agent runs only the tasks it is given
//! (init and event as usual), a watcher sees module entry, module exit and every action with
//! the mental state of that moment, and `Program::extend` compiles outside code against a
//! program (unknown names are errors).

use goal::agent::mental_state::MentalState;
use goal::agent::{Agent, AgentConfig, Observed, Program, Watcher};
use goal::syntax::test2g::ast::TestSection;
use std::sync::{Arc, Mutex};

const COUNTER: &str = "init module { beliefs { count(0). } }
main module [exit=always] {
  program {
    if bel(count(N), M is N + 1) then delete(count(N)) + insert(count(M)).
  }
}
";

struct Log(Arc<Mutex<Vec<String>>>);

impl Watcher for Log {
    fn observe(&mut self, ms: &MentalState, at: Observed<'_>) {
        let counts: Vec<String> = ms
            .beliefs
            .iter()
            .filter(|b| b.to_string().starts_with("count"))
            .map(|b| b.to_string())
            .collect();
        let what = match at {
            Observed::ModuleEntered(m) => format!("enter {m}"),
            Observed::ModuleExited(m) => format!("exit {m}"),
            Observed::Action(a) => format!("do {a}"),
        };
        self.0
            .lock()
            .expect("not poisoned")
            .push(format!("{what} [{}]", counts.join(",")));
    }
}

/// The `do` combos of a one-section test, parsed from test2g text.
fn combos(text: &str) -> Vec<Vec<goal::syntax::ast::Action>> {
    let (t, diags) = goal::syntax::test2g::parse(text, "t.test2g");
    assert!(diags.is_empty(), "{diags:?}");
    let t = t.expect("parses");
    t.agents[0].tests[0]
        .sections
        .iter()
        .filter_map(|s| match s {
            TestSection::Do { combo, .. } => Some(combo.clone()),
            _ => None,
        })
        .collect()
}

const TEST: &str = "masTest { mas = \"x.mas2g\". a { t { do main. do main + main. } } }";

#[test]
fn a_controlled_agent_runs_its_tasks_and_the_watcher_sees_every_event() {
    let prog = Program::from_source("c.goal", COUNTER).expect("compiles");
    let ext = prog
        .extend("t.test2g", TEST, &combos(TEST), &[])
        .expect("main is callable");
    assert_eq!(ext.blocks.len(), 2);
    let mut a = Agent::new(ext.program.clone(), "a", AgentConfig::default());
    a.control();
    let log = Arc::new(Mutex::new(Vec::new()));
    a.set_watcher(Some(Box::new(Log(log.clone()))));
    // Without a task, only init runs (its beliefs come after its entry): main is not entered
    // by itself.
    a.step(&[], &[]);
    assert!(!a.task_running());
    a.step(&[], &[]);
    assert_eq!(
        log.lock().expect("lock").clone(),
        ["enter init []", "exit init [count(0)]"]
    );
    a.start_task(ext.blocks[1]);
    let mut cycles = 0;
    while a.task_running() && cycles < 10 {
        a.step(&[], &[]);
        cycles += 1;
    }
    assert!(!a.task_running());
    let events = log.lock().expect("lock")[2..].to_vec();
    assert_eq!(
        events,
        [
            "enter main [count(0)]",
            "do delete(count(0)) []",
            "do insert(count(1)) [count(1)]",
            "exit main [count(1)]",
            "enter main [count(1)]",
            "do delete(count(1)) []",
            "do insert(count(2)) [count(2)]",
            "exit main [count(2)]",
        ]
    );
    assert!(
        a.stopped().is_none(),
        "a finished task does not stop the agent"
    );
}

#[test]
fn an_aborted_task_leaves_its_modules() {
    let prog = Program::from_source("c.goal", COUNTER).expect("compiles");
    let ext = prog
        .extend("t.test2g", TEST, &combos(TEST), &[])
        .expect("compiles");
    let mut a = Agent::new(ext.program.clone(), "a", AgentConfig::default());
    a.control();
    a.step(&[], &[]);
    a.start_task(ext.blocks[0]);
    a.step(&[], &[]);
    assert!(a.task_running(), "main acted: the cycle ended inside it");
    let log = Arc::new(Mutex::new(Vec::new()));
    a.set_watcher(Some(Box::new(Log(log.clone()))));
    a.abort_task();
    assert!(!a.task_running());
    assert_eq!(log.lock().expect("lock").clone(), ["exit main [count(1)]"]);
}

#[test]
fn extend_rejects_unknown_actions() {
    let prog = Program::from_source("c.goal", COUNTER).expect("compiles");
    let text = "masTest { mas = \"x.mas2g\". a { t { do nothere(1). } } }";
    let err = prog
        .extend("t.test2g", text, &combos(text), &[])
        .expect_err("unknown action");
    assert_eq!(err[0].code, "E0413");
}
