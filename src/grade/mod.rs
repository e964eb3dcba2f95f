//! `goal grade`: many submissions run on a set of maps, robot counts and seeds, each run an
//! isolated child process under tick, wall-time and memory limits, summed up in one table
//! (CSV, JSON, or a self-contained HTML report); and tournaments of submissions against each
//! other. Users read docs/grading.md.
//!
//! A run is `goal run MAS --stats FILE` in a child process of the same `goal` binary, so a
//! submission that crashes, hangs or eats memory costs only its own runs. Everything in the
//! table comes from the runs' statistics and exit codes, which depend only on the programs,
//! the map, the robot count and the seed; wall times are kept apart (`wall_seconds` of each
//! run in the JSON output).

pub mod child;
pub mod class;
pub mod html;
pub mod pool;
pub mod run;
pub mod table;
pub mod tests;
pub mod tournament;

use class::Submission;
use run::{RunResult, RunSpec};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;
use table::{Graded, Rank, Row};
use tests::TestResults;
use tournament::{Match, Standing};

/// What to run and under which limits.
#[derive(Clone, Debug)]
pub struct GradeOptions {
    /// The `goal` binary that runs each child.
    pub program: PathBuf,
    pub maps: Vec<String>,
    pub robots: Vec<usize>,
    pub seeds: Vec<u64>,
    /// Child processes at once.
    pub jobs: usize,
    /// Tick limit of a run.
    pub max_ticks: u64,
    /// Wall-time limit of a run (its own `--time-limit`).
    pub time_limit: Duration,
    /// Time a child gets past its own limit before it is killed.
    pub grace: Duration,
    /// Memory cap of a run in MiB (its own `--max-memory`; the rlimit is set above it).
    pub max_memory_mib: u64,
}

/// Everything `goal grade` found out.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    pub maps: Vec<String>,
    pub robots: Vec<usize>,
    pub seeds: Vec<u64>,
    /// Per submission and map (empty in a tournament).
    pub table: Vec<Row>,
    /// The submissions in order (empty in a tournament).
    pub ranking: Vec<Rank>,
    /// The tournament's standings (only in a tournament).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub standings: Vec<Standing>,
    /// Each submission's own tests, by name (not run in a tournament).
    pub tests: BTreeMap<String, TestResults>,
    /// Every run (or match), in order, with its wall time.
    pub runs: Vec<RunResult>,
}

/// A directory for the children's statistics files, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Result<Scratch, String> {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let dir = std::env::temp_dir().join(format!("goal-grade-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        Ok(Scratch(dir))
    }

    fn file(&self, kind: &str, i: usize) -> PathBuf {
        self.0.join(format!("{kind}-{i}.json"))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Every run of the class: submission x map x robots x seed, in that order.
pub fn plan(subs: &[Submission], opts: &GradeOptions) -> Vec<RunSpec> {
    let mut out = Vec::new();
    for (i, s) in subs.iter().enumerate() {
        if s.mas.is_err() {
            continue;
        }
        for map in &opts.maps {
            for &robots in &opts.robots {
                for &seed in &opts.seeds {
                    out.push(RunSpec {
                        submission: i,
                        map: map.clone(),
                        robots,
                        seed,
                    });
                }
            }
        }
    }
    out
}

/// A job of the pool: one run, or one submission's tests.
enum Job {
    Run(usize, RunSpec),
    Tests(usize),
}

enum Done {
    Run(RunResult),
    Tests(usize, Option<TestResults>),
}

/// Grades `subs`: every run and every submission's tests on `opts.jobs` processes at once.
/// `progress` hears one line per finished job.
pub fn grade(
    subs: &[Submission],
    opts: &GradeOptions,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Report, String> {
    let scratch = Scratch::new()?;
    let mut jobs: Vec<Job> = (0..subs.len())
        .filter(|&i| !subs[i].tests.is_empty())
        .map(Job::Tests)
        .collect();
    jobs.extend(
        plan(subs, opts)
            .into_iter()
            .enumerate()
            .map(|(i, s)| Job::Run(i, s)),
    );
    let total = jobs.len();
    let results = pool::map(
        opts.jobs,
        &jobs,
        |job| match job {
            Job::Run(i, spec) => {
                let s = &subs[spec.submission];
                let mas = s
                    .mas
                    .as_ref()
                    .map(PathBuf::as_path)
                    .unwrap_or(Path::new(""));
                let stats = scratch.file("run", *i);
                Done::Run(run::run_one(&s.name, mas, &s.dir, spec, opts, stats))
            }
            Job::Tests(i) => Done::Tests(*i, tests::run_tests(&subs[*i], opts)),
        },
        |_, done| progress(&describe(total, done, subs)),
    );
    let mut runs = Vec::new();
    let mut tests = BTreeMap::new();
    for d in results {
        match d {
            Done::Run(r) => runs.push(r),
            Done::Tests(i, Some(t)) => {
                tests.insert(subs[i].name.clone(), t);
            }
            Done::Tests(_, None) => {}
        }
    }
    let graded: Vec<Graded> = subs
        .iter()
        .map(|s| Graded {
            name: &s.name,
            not_run: s.mas.as_ref().err().map(String::as_str),
            tests: tests.get(&s.name),
        })
        .collect();
    Ok(Report {
        maps: opts.maps.clone(),
        robots: opts.robots.clone(),
        seeds: opts.seeds.clone(),
        table: table::rows(&graded, &opts.maps, &runs),
        ranking: table::ranking(&graded, &runs),
        standings: Vec::new(),
        tests,
        runs,
    })
}

/// A progress line for a finished job.
fn describe(total: usize, done: &Done, subs: &[Submission]) -> String {
    match done {
        Done::Run(r) => format!(
            "{} {} robots {} seed {}: {} ({} ticks){} [of {total} jobs]",
            r.submission,
            r.map,
            r.robots,
            r.seed,
            r.outcome.name(),
            r.ticks,
            r.note
                .as_ref()
                .map(|n| format!(": {n}"))
                .unwrap_or_default()
        ),
        Done::Tests(i, t) => format!(
            "{} tests: {} [of {total} jobs]",
            subs[*i].name,
            t.as_ref().map_or_else(|| "-".into(), |t| t.summary())
        ),
    }
}

/// Plays the tournament of the runnable submissions: every match as a child
/// `goal grade --play A --play B` process.
pub fn tournament(
    subs: &[Submission],
    opts: &GradeOptions,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Report, String> {
    let scratch = Scratch::new()?;
    let players: Vec<usize> = (0..subs.len()).filter(|&i| subs[i].mas.is_ok()).collect();
    if players.len() < 2 {
        return Err(format!(
            "a tournament needs at least two runnable submissions, found {}",
            players.len()
        ));
    }
    let matches = tournament::pairings(&players, &opts.maps, &opts.robots, &opts.seeds);
    let indexed: Vec<(usize, &Match)> = matches.iter().enumerate().collect();
    let total = matches.len();
    let results = pool::map(
        opts.jobs,
        &indexed,
        |(i, m)| play(subs, m, opts, scratch.file("match", *i)),
        |_, r| {
            progress(&format!(
                "{} {} robots {} seed {}: {} teams {:?} [of {total} matches]",
                r.submission,
                r.map,
                r.robots,
                r.seed,
                r.outcome.name(),
                r.teams
            ))
        },
    );
    let names: Vec<String> = subs.iter().map(|s| s.name.clone()).collect();
    let played: Vec<(Match, RunResult)> =
        matches.into_iter().zip(results.iter().cloned()).collect();
    Ok(Report {
        maps: opts.maps.clone(),
        robots: opts.robots.clone(),
        seeds: opts.seeds.clone(),
        table: Vec::new(),
        ranking: Vec::new(),
        standings: tournament::standings(&names, &played),
        tests: BTreeMap::new(),
        runs: results,
    })
}

/// One match as a child process.
fn play(subs: &[Submission], m: &Match, opts: &GradeOptions, stats: PathBuf) -> RunResult {
    let [a, b] = m.teams.map(|t| &subs[t]);
    let mas = |s: &Submission| s.mas.clone().unwrap_or_default();
    let mut cmd = Command::new(&opts.program);
    cmd.arg("grade")
        .arg("--play")
        .arg(mas(a))
        .arg("--play")
        .arg(mas(b));
    let spec = RunSpec {
        submission: m.teams[0],
        map: m.map.clone(),
        robots: m.robots,
        seed: m.seed,
    };
    run::limit_args(&mut cmd, &spec, opts, &stats);
    run::finish(
        &format!("{} vs {}", a.name, b.name),
        &spec,
        cmd,
        opts,
        &stats,
    )
}
