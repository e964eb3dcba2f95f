//! Idle skipping never changes what agents do: for every runnable program of the repository
//! (shipped agents, fixtures, test files), the trace with skipping equals the trace without
//! it, byte for byte. Waiting is decided by the agent's cycle (`CycleOutput::waiting`), so
//! the two examples that the old action-count guess got wrong are checked by name as well.

use goal::mas::run::{run, Quiet, RunOptions};
use goal::mas::system::{load_agent, load_mas};
use goal::mas::trace::TraceWriter;
use goal::mas::{EndReason, MasSystem, RunSummary};
use goal::testing::runner::{run_file, TestOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

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

/// Every file with extension `ext` under `dir`, sorted (directories named `invalid` hold
/// programs that do not load on purpose).
fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "invalid") {
                files(&p, ext, out);
            }
        } else if p.extension().is_some_and(|e| e == ext) {
            out.push(p);
        }
    }
}

fn load(p: &Path) -> Option<MasSystem> {
    let loaded = if p.extension().is_some_and(|e| e == "goal") {
        load_agent(p)
    } else {
        load_mas(p)
    };
    loaded.ok()
}

/// The summary and trace of a run; `None` when the system cannot start (e.g. it launches no
/// agent).
fn traced(sys: &MasSystem, skip: bool, ticks: u64) -> Option<(RunSummary, String)> {
    let buf = Buf::default();
    let opts = RunOptions {
        max_ticks: ticks,
        workers: 2,
        skip_idle: skip,
        // A generous quota: the default 10 s could cut a cycle on a loaded machine in one of
        // the two runs only, which is timing, not skipping.
        cycle_time: Some(std::time::Duration::from_secs(120)),
        ..RunOptions::default()
    };
    let (summary, err) = run(
        sys,
        &opts,
        Some(TraceWriter::new(Box::new(buf.clone()))),
        &mut Quiet,
    )
    .ok()?;
    assert_eq!(err, None);
    let text = String::from_utf8(buf.0.lock().unwrap().clone()).unwrap();
    Some((summary, text))
}

fn same_both_ways(p: &Path, ticks: u64) -> Option<(RunSummary, String)> {
    let sys = load(p)?;
    let (a, ta) = traced(&sys, true, ticks)?;
    let (b, tb) = traced(&sys, false, ticks).expect("starts the second time");
    assert_eq!(
        ta,
        tb,
        "{}: the trace depends on idle skipping",
        p.display()
    );
    assert_eq!(a, b, "{}: the figures depend on idle skipping", p.display());
    Some((a, ta))
}

#[test]
fn every_program_runs_the_same_with_and_without_skipping() {
    let mut all = Vec::new();
    for dir in ["agents", "tests/fixtures"] {
        files(&root().join(dir), "mas2g", &mut all);
        files(&root().join(dir), "goal", &mut all);
    }
    // The hoarder runs into its cycle-time quota: a timing-dependent end by design.
    all.retain(|p| !p.ends_with("runtime/hoarder.goal"));
    let mut runnable = Vec::new();
    for p in &all {
        if same_both_ways(p, 300).is_some() {
            runnable.push(p.file_name());
        }
    }
    let runnable = runnable.len();
    // Agent files that are modules of a system do not load alone; most files run.
    assert!(
        runnable >= 20,
        "only {runnable} of {} programs ran",
        all.len()
    );
}

#[test]
fn every_test_file_has_the_same_outcome_with_and_without_skipping() {
    let mut all = Vec::new();
    for dir in ["agents", "tests/fixtures"] {
        files(&root().join(dir), "test2g", &mut all);
    }
    assert!(all.len() >= 15, "{all:?}");
    for p in &all {
        let opts = |skip_idle| TestOptions {
            max_ticks: 2_000,
            skip_idle,
            ..TestOptions::default()
        };
        let a = run_file(p, &opts(true));
        let b = run_file(p, &opts(false));
        assert_eq!(
            a,
            b,
            "{}: test reports depend on idle skipping",
            p.display()
        );
    }
}

fn skip_fixture(name: &str) -> PathBuf {
    root().join("tests/fixtures/skip").join(name)
}

#[test]
fn a_linearall_main_that_only_prints_keeps_cycling() {
    let (s, trace) = same_both_ways(&skip_fixture("print_linearall.goal"), 5).expect("loads");
    assert_eq!(s.end, EndReason::CycleLimit, "{trace}");
    // One print (a real action) per cycle: first, second, first, second, first.
    assert_eq!(s.agents["print_linearall"].cycles, 5);
    assert_eq!(trace.matches("\"text\":\"first\"").count(), 3, "{trace}");
    assert_eq!(trace.matches("\"text\":\"second\"").count(), 2, "{trace}");
}

#[test]
fn main_gets_control_back_after_a_called_module_exits() {
    let (s, trace) = same_both_ways(&skip_fixture("module_exit.goal"), 50).expect("loads");
    assert_eq!(s.end, EndReason::AllStopped, "{trace}");
    assert!(trace.contains("\"text\":\"back_in_main\""), "{trace}");
}

#[test]
fn an_agent_polling_the_clock_is_not_waiting() {
    let (s, trace) = same_both_ways(&skip_fixture("clock.goal"), 50).expect("loads");
    assert_eq!(s.end, EndReason::AllStopped, "{trace}");
    assert!(
        trace.contains("\"text\":\"a_tenth_of_a_second\""),
        "{trace}"
    );
}

#[test]
fn an_agent_rolling_dice_is_not_waiting() {
    let (s, trace) = same_both_ways(&skip_fixture("dice.goal"), 1_000).expect("loads");
    assert_eq!(s.end, EndReason::AllStopped, "{trace}");
    assert!(trace.contains("\"text\":\"six\""), "{trace}");
}
