//! What `goal test` reports: one [`TestReport`] per named test, readable text and JSON.

use serde::Serialize;

/// Where and why a test failed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Failure {
    /// 1-based index of the failing section in the named test.
    pub section: usize,
    /// `do`, `assert` or `evaluate`.
    pub kind: String,
    /// 1-based line of the section (or condition) in the test file.
    pub line: usize,
    /// The condition's text as written (empty for a failing `do`).
    pub condition: String,
    /// What went wrong, in words.
    pub reason: String,
    /// The bindings under which it went wrong (`X=a, Y=b`), if any.
    pub bindings: Option<String>,
    /// The agent's reasoning cycle at the failure.
    pub cycle: u64,
}

/// How a test ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Outcome {
    /// Every section passed.
    Passed,
    /// A section failed.
    Failed(Failure),
    /// The wall-time `timeout` or the `--max-ticks` bound ran out first.
    TimedOut {
        /// Which bound ran out.
        reason: String,
        /// 1-based index of the section that was running (0: none yet).
        section: usize,
        cycle: u64,
    },
    /// The test could not run (the file, the MAS or the test code has errors).
    Error { message: String },
}

/// The result of one named test of one agent.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TestReport {
    /// The `.test2g` file.
    pub file: String,
    pub agent: String,
    pub test: String,
    #[serde(flatten)]
    pub outcome: Outcome,
    /// Reasoning cycles the agent ran.
    pub cycles: u64,
    /// Environment ticks (or rounds without an environment) the run took.
    pub ticks: u64,
    /// Lines printed by `watch` conditions.
    pub watch: Vec<String>,
}

impl TestReport {
    /// True when the test passed.
    pub fn passed(&self) -> bool {
        self.outcome == Outcome::Passed
    }

    /// The report as one JSON object.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }

    /// The report as readable text: one status line, then details for a failure.
    pub fn to_text(&self) -> String {
        let name = format!("{} {}/{}", self.file, self.agent, self.test);
        let mut s = match &self.outcome {
            Outcome::Passed => format!(
                "test {name} ... passed ({} cycles, {} ticks)\n",
                self.cycles, self.ticks
            ),
            Outcome::Failed(f) => {
                let mut s = format!("test {name} ... FAILED\n");
                s.push_str(&format!(
                    "  section {} ({}, line {}) failed at cycle {}\n",
                    f.section, f.kind, f.line, f.cycle
                ));
                if !f.condition.is_empty() {
                    s.push_str(&format!("  condition: {}\n", f.condition));
                }
                s.push_str(&format!("  reason: {}\n", f.reason));
                if let Some(b) = &f.bindings {
                    s.push_str(&format!("  bindings: {b}\n"));
                }
                s
            }
            Outcome::TimedOut {
                reason,
                section,
                cycle,
            } => format!(
                "test {name} ... TIMED OUT\n  {reason} while section {section} was running (cycle {cycle})\n"
            ),
            Outcome::Error { message } => {
                let mut s = format!("test {name} ... ERROR\n");
                for l in message.lines() {
                    s.push_str(&format!("  {l}\n"));
                }
                s
            }
        };
        for w in &self.watch {
            s.push_str(&format!("  watch: {w}\n"));
        }
        s
    }
}

/// The closing line: how many tests passed, failed, timed out or could not run.
pub fn summary(reports: &[TestReport]) -> String {
    let count = |f: fn(&Outcome) -> bool| reports.iter().filter(|r| f(&r.outcome)).count();
    let passed = count(|o| matches!(o, Outcome::Passed));
    let failed = count(|o| matches!(o, Outcome::Failed(_)));
    let timed = count(|o| matches!(o, Outcome::TimedOut { .. }));
    let errors = count(|o| matches!(o, Outcome::Error { .. }));
    let verdict = if passed == reports.len() {
        "ok"
    } else {
        "FAILED"
    };
    format!(
        "test result: {verdict}. {passed} passed; {failed} failed; {timed} timed out; {errors} errors\n"
    )
}
