//! The graded table: one row per submission and map, from the runs; the ranking of the
//! submissions; CSV and readable text.

use super::run::{Outcome, RunResult};
use super::tests::TestResults;
use serde::Serialize;
use std::collections::BTreeMap;

/// One submission on one map, over every robot count and seed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    pub submission: String,
    /// The map, or `-` for a submission that could not be run at all.
    pub map: String,
    pub runs: u64,
    pub completed: u64,
    /// `completed / runs` (0 without runs).
    pub completion_rate: f64,
    /// Mean ticks of the completed runs, to one decimal; `None` when none completed.
    pub ticks_to_complete: Option<f64>,
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
    pub messages: u64,
    /// Agents stopped on runtime errors, over all runs.
    pub agent_errors: u64,
    /// How the runs ended, e.g. `completed 2, limit 1`; or why nothing ran.
    pub outcomes: String,
    /// The submission's own tests: `passed/total`, `-` without tests.
    pub tests: String,
}

/// A submission's place in the ranking.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Rank {
    pub rank: usize,
    pub submission: String,
    pub completion_rate: f64,
    pub ticks_to_complete: Option<f64>,
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
}

/// `x` rounded to `places` decimals (so that tables compare as text).
pub fn round(x: f64, places: i32) -> f64 {
    let k = 10f64.powi(places);
    (x * k).round() / k
}

fn rate(n: u64, of: u64) -> f64 {
    if of == 0 {
        0.0
    } else {
        round(n as f64 / of as f64, 3)
    }
}

fn mean_ticks(runs: &[&RunResult]) -> Option<f64> {
    let done: Vec<u64> = runs
        .iter()
        .filter(|r| r.outcome == Outcome::Completed)
        .map(|r| r.ticks)
        .collect();
    (!done.is_empty()).then(|| round(done.iter().sum::<u64>() as f64 / done.len() as f64, 1))
}

fn outcomes(runs: &[&RunResult]) -> String {
    let mut counts: BTreeMap<Outcome, u64> = BTreeMap::new();
    for r in runs {
        *counts.entry(r.outcome).or_default() += 1;
    }
    counts
        .iter()
        .map(|(o, n)| format!("{} {n}", o.name()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The row of `runs` (all of one submission and map).
fn row(submission: &str, map: &str, runs: &[&RunResult], tests: &str) -> Row {
    let sum = |f: fn(&RunResult) -> u64| runs.iter().map(|r| f(r)).sum::<u64>();
    let completed = runs
        .iter()
        .filter(|r| r.outcome == Outcome::Completed)
        .count() as u64;
    Row {
        submission: submission.to_string(),
        map: map.to_string(),
        runs: runs.len() as u64,
        completed,
        completion_rate: rate(completed, runs.len() as u64),
        ticks_to_complete: mean_ticks(runs),
        deliveries_right: sum(|r| r.deliveries_right),
        deliveries_wrong: sum(|r| r.deliveries_wrong),
        messages: sum(|r| r.messages),
        agent_errors: sum(|r| r.agent_errors),
        outcomes: outcomes(runs),
        tests: tests.to_string(),
    }
}

/// What the table is made of, per submission in class order.
pub struct Graded<'a> {
    pub name: &'a str,
    /// Why it could not be run, if it could not.
    pub not_run: Option<&'a str>,
    pub tests: Option<&'a TestResults>,
}

/// The rows: per submission (class order), per map (in the order given).
pub fn rows(subs: &[Graded], maps: &[String], runs: &[RunResult]) -> Vec<Row> {
    let mut out = Vec::new();
    for s in subs {
        let tests = s.tests.map_or_else(|| "-".to_string(), |t| t.summary());
        if let Some(why) = s.not_run {
            let mut r = row(s.name, "-", &[], &tests);
            r.outcomes = format!("not run: {why}");
            out.push(r);
            continue;
        }
        for m in maps {
            let mine: Vec<&RunResult> = runs
                .iter()
                .filter(|r| r.submission == s.name && &r.map == m)
                .collect();
            out.push(row(s.name, m, &mine, &tests));
        }
    }
    out
}

/// The ranking over all maps: completion rate (higher first), mean ticks to complete (fewer
/// first; none last), wrong deliveries (fewer first), then the name.
pub fn ranking(subs: &[Graded], runs: &[RunResult]) -> Vec<Rank> {
    let mut ranks: Vec<Rank> = subs
        .iter()
        .map(|s| {
            let mine: Vec<&RunResult> = runs.iter().filter(|r| r.submission == s.name).collect();
            let r = row(s.name, "", &mine, "");
            Rank {
                rank: 0,
                submission: r.submission,
                completion_rate: r.completion_rate,
                ticks_to_complete: r.ticks_to_complete,
                deliveries_right: r.deliveries_right,
                deliveries_wrong: r.deliveries_wrong,
            }
        })
        .collect();
    ranks.sort_by(|a, b| {
        b.completion_rate
            .total_cmp(&a.completion_rate)
            .then_with(|| {
                let t = |r: &Rank| r.ticks_to_complete.unwrap_or(f64::INFINITY);
                t(a).total_cmp(&t(b))
            })
            .then(a.deliveries_wrong.cmp(&b.deliveries_wrong))
            .then_with(|| a.submission.cmp(&b.submission))
    });
    for (i, r) in ranks.iter_mut().enumerate() {
        r.rank = i + 1;
    }
    ranks
}

/// The header of the CSV table.
pub const CSV_HEADER: &[&str] = &[
    "submission",
    "map",
    "runs",
    "completed",
    "completion_rate",
    "ticks_to_complete",
    "deliveries_right",
    "deliveries_wrong",
    "messages",
    "agent_errors",
    "outcomes",
    "tests",
];

impl Row {
    /// The row's cells as text, in [`CSV_HEADER`] order.
    pub fn cells(&self) -> Vec<String> {
        vec![
            self.submission.clone(),
            self.map.clone(),
            self.runs.to_string(),
            self.completed.to_string(),
            self.completion_rate.to_string(),
            self.ticks_to_complete
                .map_or_else(String::new, |t| t.to_string()),
            self.deliveries_right.to_string(),
            self.deliveries_wrong.to_string(),
            self.messages.to_string(),
            self.agent_errors.to_string(),
            self.outcomes.clone(),
            self.tests.clone(),
        ]
    }
}

/// A CSV field, quoted when it holds a comma, quote or line break (RFC 4180).
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Rows of cells as CSV text with a header line.
pub fn csv(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = header.join(",");
    out.push('\n');
    for r in rows {
        let cells: Vec<String> = r.iter().map(|c| csv_field(c)).collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// Rows of cells as an aligned text table.
pub fn text(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: Vec<&str>| {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect();
        padded.join("  ").trim_end().to_string() + "\n"
    };
    let mut out = line(header.to_vec());
    for r in rows {
        out.push_str(&line(r.iter().map(String::as_str).collect()));
    }
    out
}
