//! Modular and MARBEL systems written the ways students write them (different module layouts,
//! use forms, action specs and percept declarations; `tests/fixtures/modular/styles/`): each
//! passes `goal check` without errors and runs; the BW4T robots deliver blocks.

use goal::mas::run::{run, Quiet, RunOptions};
use goal::mas::stats::RunSummary;
use goal::mas::system::load_mas;
use goal::syntax::check::check_path_with_agents;
use std::path::PathBuf;

fn style(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/modular/styles")
        .join(path)
}

/// `goal check` of the system finds no error; the system runs `ticks` ticks without an agent
/// error.
fn check_and_run(path: &str, ticks: u64) -> RunSummary {
    let file = style(path);
    let errors: Vec<String> = check_path_with_agents(&file)
        .iter()
        .flat_map(|r| {
            r.diagnostics
                .iter()
                .filter(|d| d.is_error())
                .map(|d| d.render(&r.source))
        })
        .collect();
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    let sys = load_mas(&file).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let opts = RunOptions {
        seed: Some(1),
        max_ticks: ticks,
        workers: 1,
        trace_rules: false,
        ..RunOptions::default()
    };
    let (s, err) =
        run(&sys, &opts, None, &mut Quiet).unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None, "{path}: runtime failure");
    for (name, a) in &s.agents {
        assert_eq!(a.error, None, "{path}: {name} stopped on an error");
    }
    s
}

/// The TU Delft 2016 template: all client parameters, `module main` in robot.mod2g, an `.act2g`,
/// `percept(not(..))` events.
#[test]
fn delft_template_style_delivers() {
    let s = check_and_run("delft/robot.mas2g", 3_000);
    assert!(s.deliveries.right >= 1, "{:?}", s.deliveries);
}

/// The VU course template (MARBEL): `add`/`update`/`replace` declarations, a `.pl` database
/// with `:- dynamic` and cut-off declaration lines, plain-literal conditions.
#[test]
fn course_template_style_delivers() {
    let s = check_and_run("course/BW4T.mas2g", 3_000);
    assert!(s.deliveries.right >= 1, "{:?}", s.deliveries);
}

/// Sources in subdirectories with quoted relative references, `name = *`, channels, timers,
/// `sleep` and a shutdown module: the agents stop after five heartbeats of 200 ms (100 ticks
/// of simulated time), each printing its count from the shutdown module.
#[test]
fn subdirectory_style_with_timers_channels_and_shutdown() {
    let s = check_and_run("digger/digger.mas2g", 1_000);
    assert_eq!(s.agents.len(), 2);
    assert!(
        s.agents.values().all(|a| a.stopped),
        "{:?}",
        s.agents.keys()
    );
    assert!(
        s.ticks <= 110,
        "stopped by the timer after about 100 ticks, not {}",
        s.ticks
    );
}
