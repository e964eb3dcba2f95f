//! Deliberately failing `.test2g` files (each condition kind failing once): their reports are
//! snapshotted, so a change in what a failure says is reviewed. Plus the passing fixture that
//! uses every section kind.

use goal::testing::report::summary;
use goal::testing::runner::{run_file, TestOptions};
use goal::testing::{Outcome, TestReport};
use std::path::Path;

fn run(name: &str) -> Vec<TestReport> {
    // A relative path keeps file names in the reports independent of the checkout.
    std::env::set_current_dir(env!("CARGO_MANIFEST_DIR")).expect("manifest dir");
    let path = Path::new("tests/fixtures/test2g").join(name);
    let opts = TestOptions {
        max_ticks: 200,
        ..TestOptions::default()
    };
    run_file(&path, &opts)
}

fn report(name: &str) -> String {
    let reports = run(name);
    assert_eq!(reports.len(), 1, "one named test per failing fixture");
    assert!(!reports[0].passed(), "{name} must fail");
    reports[0].to_text()
}

fn failure(name: &str) -> goal::testing::report::Failure {
    match run(name).remove(0).outcome {
        Outcome::Failed(f) => f,
        other => panic!("{name}: expected a failure, got {other:?}"),
    }
}

#[test]
fn assert_fails_with_its_message() {
    let f = failure("failing/assert.test2g");
    assert_eq!((f.section, f.kind.as_str()), (2, "assert"));
    assert_eq!(f.reason, "assertion failed: the count starts at one");
    insta::assert_snapshot!("assert", report("failing/assert.test2g"));
}

#[test]
fn always_fails_at_the_first_event_without_answers() {
    let f = failure("failing/always.test2g");
    assert_eq!(f.condition, "always bel(count(N), N < 4)");
    insta::assert_snapshot!("always", report("failing/always.test2g"));
}

#[test]
fn never_fails_with_the_bindings_that_held() {
    let f = failure("failing/never.test2g");
    assert_eq!(f.bindings.as_deref(), Some("N=3"));
    insta::assert_snapshot!("never", report("failing/never.test2g"));
}

#[test]
fn eventually_fails_when_the_run_ends_and_watch_prints() {
    let r = run("failing/eventually.test2g").remove(0);
    assert!(matches!(&r.outcome, Outcome::Failed(f) if f.reason.contains("never held")));
    assert_eq!(r.watch.len(), 4, "{:?}", r.watch);
    insta::assert_snapshot!("eventually", report("failing/eventually.test2g"));
}

#[test]
fn atend_fails_at_the_end_of_the_run() {
    insta::assert_snapshot!("atend", report("failing/atend.test2g"));
}

#[test]
fn a_chain_fails_with_the_trigger_bindings() {
    let f = failure("failing/chain.test2g");
    assert_eq!(f.bindings.as_deref(), Some("N=3"));
    insta::assert_snapshot!("chain", report("failing/chain.test2g"));
}

#[test]
fn react_to_fails_when_the_reaction_never_comes() {
    insta::assert_snapshot!("reactto", report("failing/reactto.test2g"));
}

#[test]
fn do_and_not_do_conditions_match_the_last_action() {
    let f = failure("failing/do_action.test2g");
    assert!(f.reason.contains("action bump"), "{}", f.reason);
    insta::assert_snapshot!("do_action", report("failing/do_action.test2g"));
    insta::assert_snapshot!("not_do", report("failing/not_do.test2g"));
}

#[test]
fn a_runtime_error_fails_the_do_section() {
    let f = failure("failing/runtime_error.test2g");
    assert_eq!(f.kind, "do");
    assert!(f.reason.contains("zero_divisor"), "{}", f.reason);
    insta::assert_snapshot!("runtime_error", report("failing/runtime_error.test2g"));
}

#[test]
fn the_tick_bound_times_a_test_out() {
    let r = run("failing/ticks.test2g").remove(0);
    assert!(matches!(r.outcome, Outcome::TimedOut { section: 1, .. }));
    insta::assert_snapshot!("ticks", report("failing/ticks.test2g"));
}

#[test]
fn every_section_kind_passes_and_every_named_test_runs() {
    let reports = run("passing/sections.test2g");
    let names: Vec<&str> = reports.iter().map(|r| r.test.as_str()).collect();
    assert_eq!(names, ["stepsByHand", "runsToTheEnd"]);
    assert!(reports.iter().all(|r| r.passed()), "{}", summary(&reports));
    assert!(summary(&reports).starts_with("test result: ok. 2 passed"));
}

#[test]
fn json_reports_name_section_condition_bindings_and_cycle() {
    let r = run("failing/chain.test2g").remove(0);
    insta::assert_json_snapshot!("chain_json", r.to_json());
}

#[test]
fn the_wall_time_timeout_times_a_test_out() {
    std::env::set_current_dir(env!("CARGO_MANIFEST_DIR")).expect("manifest dir");
    let opts = TestOptions {
        max_ticks: u64::MAX,
        ..TestOptions::default()
    };
    let r = run_file(
        Path::new("tests/fixtures/test2g/failing/timeout.test2g"),
        &opts,
    )
    .remove(0);
    match r.outcome {
        Outcome::TimedOut {
            reason, section, ..
        } => {
            assert_eq!(reason, "the timeout of 1s ran out");
            assert_eq!(section, 1);
        }
        other => panic!("expected a timeout, got {other:?}"),
    }
}
