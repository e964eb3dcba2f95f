//! A submission's own `.test2g` files, run as a child `goal test --format json` process.

use super::child;
use super::class::Submission;
use super::GradeOptions;
use serde::Serialize;
use std::process::Command;

/// How many of a submission's tests passed.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TestResults {
    pub passed: u64,
    pub failed: u64,
    /// Tests that ran out of their time or tick bound.
    pub timed_out: u64,
    /// Tests that could not run (errors in the files).
    pub errors: u64,
    /// Why the test run itself broke down (killed, crashed), if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub problem: Option<String>,
}

impl TestResults {
    /// Tests reported.
    pub fn total(&self) -> u64 {
        self.passed + self.failed + self.timed_out + self.errors
    }

    /// `passed/total`, `-` without tests, `killed`... when the run broke down.
    pub fn summary(&self) -> String {
        match &self.problem {
            Some(_) if self.total() == 0 => "broken".into(),
            _ if self.total() == 0 => "-".into(),
            _ => format!("{}/{}", self.passed, self.total()),
        }
    }
}

/// Runs the submission's tests (`None` when it has none).
pub fn run_tests(sub: &Submission, opts: &GradeOptions) -> Option<TestResults> {
    if sub.tests.is_empty() {
        return None;
    }
    let mut cmd = Command::new(&opts.program);
    cmd.current_dir(&sub.dir)
        .arg("test")
        .arg("--format")
        .arg("json")
        .arg("--max-ticks")
        .arg(opts.max_ticks.to_string())
        .args(&sub.tests);
    // Every named test is a run of its own: the test child gets a few runs' time.
    let time = opts.time_limit * TEST_RUNS;
    let limits = super::run::child_limits(opts, time);
    let (end, out) = match child::run_capturing(cmd, &limits) {
        Ok(x) => x,
        Err(e) => {
            return Some(TestResults {
                problem: Some(e),
                ..TestResults::default()
            })
        }
    };
    let mut r = TestResults::default();
    for line in out.lines() {
        let Ok(v) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        match v["status"].as_str() {
            Some("passed") => r.passed += 1,
            Some("failed") => r.failed += 1,
            Some("timed_out") => r.timed_out += 1,
            Some(_) => r.errors += 1,
            None => {}
        }
    }
    if end.killed {
        r.problem = Some("killed after the time limit".into());
    } else if end.code.is_none() {
        r.problem = Some(format!("ended by signal {}", end.signal.unwrap_or(0)));
    }
    Some(r)
}

/// How many runs' time limits a submission's test run gets.
const TEST_RUNS: u32 = 5;
