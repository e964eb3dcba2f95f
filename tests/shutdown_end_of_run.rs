//! The shutdown module (modular GOAL) of each agent still running when the run ends runs once,
//! in agent-name order, traced like a cycle; an agent a runtime error stopped does not run it.

use goal::mas::run::{run, Observer, RunOptions};
use goal::mas::system::load_mas;
use goal::mas::trace::TraceWriter;
use goal::mas::{EndReason, RunSummary};
use std::io::Write;
use std::sync::{Arc, Mutex};

#[derive(Clone, Default)]
struct Buf(Arc<Mutex<Vec<u8>>>);

impl Write for Buf {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[derive(Default)]
struct Collect {
    printed: Vec<(String, String)>,
    warnings: Vec<String>,
}

impl Observer for Collect {
    fn printed(&mut self, agent: &str, line: &str) {
        self.printed.push((agent.to_string(), line.to_string()));
    }
    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_string());
    }
}

/// Writes the project `files` into a fresh directory and runs its `team.mas2g`.
fn run_project(
    name: &str,
    files: &[(&str, &str)],
    max_ticks: u64,
) -> (RunSummary, String, Collect) {
    let dir = std::env::temp_dir().join(format!("goal-end-of-run-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    let sys = load_mas(&dir.join("team.mas2g")).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let buf = Buf::default();
    let mut obs = Collect::default();
    let opts = RunOptions {
        workers: 1,
        max_ticks,
        ..RunOptions::default()
    };
    let (summary, err) = run(
        &sys,
        &opts,
        Some(TraceWriter::new(Box::new(buf.clone()))),
        &mut obs,
    )
    .unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None);
    let text = String::from_utf8(buf.0.lock().unwrap().clone()).unwrap();
    (summary, text, obs)
}

const TEAM: &str = "define zed as agent { use busy as main module. use bye as shutdown module. }
define amy as agent { use busy as main module. use bye as shutdown module. }
define bad as agent { use broken as main module. use bye as shutdown module. }
launchpolicy { launch zed. launch amy. launch bad. }";

const BYE: &str = "module bye { if true then print(bye) + (amy).send(bye). }";

#[test]
fn cycle_limit_runs_each_running_agents_shutdown_once_in_name_order() {
    let (summary, trace, obs) = run_project(
        "limit",
        &[
            ("team.mas2g", TEAM),
            ("busy.mod2g", "module busy { if true then print(working). }"),
            (
                "broken.mod2g",
                "module broken { if bel(X is a + 1) then print(X). }",
            ),
            ("bye.mod2g", BYE),
        ],
        5,
    );
    assert_eq!(summary.end, EndReason::CycleLimit);
    let byes: Vec<&str> = obs
        .printed
        .iter()
        .filter(|(_, l)| l == "bye")
        .map(|(a, _)| a.as_str())
        .collect();
    assert_eq!(
        byes,
        ["amy", "zed"],
        "running agents, in name order, once; not `bad`"
    );
    assert!(
        summary.agents["bad"].error.is_some(),
        "bad stopped on its error"
    );
    // The end-of-run step is traced like a cycle, before the end record.
    let lines: Vec<&str> = trace.lines().collect();
    let end = lines.len() - 1;
    assert!(lines[end].contains("\"type\":\"end\""), "{}", lines[end]);
    let last_cycles: Vec<&str> = lines[..end]
        .iter()
        .filter(|l| l.contains("\"type\":\"cycle\""))
        .rev()
        .take(2)
        .copied()
        .collect();
    assert!(last_cycles[1].contains("\"agent\":\"amy\"") && last_cycles[1].contains("bye"));
    assert!(last_cycles[0].contains("\"agent\":\"zed\"") && last_cycles[0].contains("run ended"));
    // Messages of the shutdown module are not delivered: the run is over.
    assert!(
        obs.warnings
            .iter()
            .any(|w| w.contains("not carried out: the run has ended")),
        "{:?}",
        obs.warnings
    );
}

#[test]
fn an_idle_end_runs_the_shutdown_module() {
    let team = "define amy as agent { use wait as main module. use bye as shutdown module. }
launchpolicy { launch amy. }";
    let (summary, _, obs) = run_project(
        "idle",
        &[
            ("team.mas2g", team),
            (
                "wait.mod2g",
                "module wait { if bel(1 > 2) then print(no). }",
            ),
            ("bye.mod2g", "module bye { if true then print(bye). }"),
        ],
        1000,
    );
    assert_eq!(summary.end, EndReason::Idle);
    assert_eq!(obs.printed, [("amy".to_string(), "bye".to_string())]);
}
