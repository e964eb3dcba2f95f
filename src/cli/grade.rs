//! `goal grade CLASS_DIR`: run every submission of a class on maps, robot counts and seeds in
//! isolated child processes and write one table (text on stdout; CSV, JSON or HTML with
//! `--out`); `--tournament` plays the submissions against each other. See docs/grading.md.
//!
//! The hidden `--play A.mas2g --play B.mas2g` mode is one tournament match, run by `goal
//! grade` itself as a child process.

use super::exit;
use super::limits;
use goal::grade::{self, class, table, tournament, GradeOptions, Report};
use goal::mas::{system, Observer, RunOptions};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

/// Arguments of `goal grade`.
#[derive(clap::Args)]
pub struct Args {
    /// The class directory: one subdirectory per submission, each with one .mas2g file.
    #[arg(required_unless_present = "play")]
    pub class_dir: Option<PathBuf>,
    /// Maps to run on, comma-separated (built-in names or map files).
    #[arg(long, alias = "map", value_delimiter = ',', default_value = "banana")]
    pub maps: Vec<String>,
    /// Robot counts, comma-separated (in a tournament: robots per team).
    #[arg(long, value_delimiter = ',', default_value = "1", value_parser = robots)]
    pub robots: Vec<usize>,
    /// Run seeds, comma-separated.
    #[arg(long, alias = "seed", value_delimiter = ',', default_value = "1")]
    pub seeds: Vec<u64>,
    /// Runs at once (1 to 1024; default: number of cores).
    #[arg(long, value_parser = limits::workers)]
    pub jobs: Option<usize>,
    /// Tick limit of each run.
    #[arg(long, alias = "max-ticks", default_value_t = 10_000, value_parser = limits::positive)]
    pub ticks: u64,
    /// Wall-time limit of each run in seconds; a run still going 5 s later is killed.
    #[arg(long, default_value_t = 60.0, value_parser = limits::seconds)]
    pub time_limit: f64,
    /// Memory cap of each run in MiB.
    #[arg(long, default_value_t = 1024, value_parser = limits::positive)]
    pub max_memory: u64,
    /// Write the table to this file: .csv, .json or .html (may be given more than once).
    #[arg(long)]
    pub out: Vec<PathBuf>,
    /// Play the submissions against each other (BW4T, one team per submission per map).
    #[arg(long)]
    pub tournament: bool,
    /// One tournament match: the teams' .mas2g files (used by `goal grade` itself).
    #[arg(long, hide = true)]
    pub play: Vec<PathBuf>,
    /// With --play: write the match's summary as JSON to this file.
    #[arg(long, hide = true)]
    pub stats: Option<PathBuf>,
}

fn robots(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=1000).contains(&n) => Ok(n),
        _ => Err("must be a whole number from 1 to 1000".into()),
    }
}

/// The output formats, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Csv,
    Json,
    Html,
}

fn format_of(p: &Path) -> Option<Format> {
    match p.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "csv" => Some(Format::Csv),
        "json" => Some(Format::Json),
        "html" | "htm" => Some(Format::Html),
        _ => None,
    }
}

/// The report as text in `format`.
fn render(r: &Report, format: Option<Format>) -> String {
    let (header, rows) = if r.standings.is_empty() {
        (
            table::CSV_HEADER,
            r.table.iter().map(table::Row::cells).collect::<Vec<_>>(),
        )
    } else {
        (
            tournament::CSV_HEADER,
            r.standings
                .iter()
                .map(tournament::Standing::cells)
                .collect(),
        )
    };
    match format {
        None => table::text(header, &rows),
        Some(Format::Csv) => table::csv(header, &rows),
        Some(Format::Json) => serde_json::to_string_pretty(r).unwrap_or_default() + "\n",
        Some(Format::Html) => grade::html::report(r),
    }
}

/// Runs `goal grade`.
pub fn main(args: Args) -> ExitCode {
    if !args.play.is_empty() {
        return play_main(&args);
    }
    for p in &args.out {
        if format_of(p).is_none() {
            eprintln!(
                "error: --out {}: the file name must end in .csv, .json or .html",
                p.display()
            );
            return exit::code(exit::USAGE);
        }
    }
    if let Some(m) = args.maps.iter().find(|m| !is_map(m)) {
        eprintln!(
            "error: --maps: `{m}` is neither a built-in map ({}) nor a map file",
            goal::bw4t::map::builtin_names().join(", ")
        );
        return exit::code(exit::USAGE);
    }
    let program = match std::env::current_exe() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: cannot find the goal binary to run submissions with: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    let class_dir = args.class_dir.clone().unwrap_or_default();
    let subs = match class::discover(&class_dir) {
        Ok(s) if s.is_empty() => {
            eprintln!(
                "error: {} holds no submission directories",
                class_dir.display()
            );
            return exit::code(exit::FAILURE);
        }
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    for s in &subs {
        if let Err(why) = &s.mas {
            eprintln!("warning: submission {} is not run: {why}", s.name);
        }
    }
    let opts = GradeOptions {
        program,
        maps: distinct(&args.maps),
        robots: distinct(&args.robots),
        seeds: distinct(&args.seeds),
        jobs: args
            .jobs
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        max_ticks: args.ticks,
        time_limit: Duration::from_secs_f64(args.time_limit),
        grace: GRACE,
        max_memory_mib: args.max_memory,
    };
    let progress = |line: &str| eprintln!("{line}");
    let report = if args.tournament {
        grade::tournament(&subs, &opts, &progress)
    } else {
        grade::grade(&subs, &opts, &progress)
    };
    let report = match report {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    exit::say(&render(&report, None));
    let mut ok = true;
    for p in &args.out {
        if let Err(e) = std::fs::write(p, render(&report, format_of(p))) {
            eprintln!("error: cannot write {}: {e}", p.display());
            ok = false;
        }
    }
    exit::code(if ok { exit::OK } else { exit::FAILURE })
}

/// True for a built-in map name or an existing map file.
fn is_map(m: &str) -> bool {
    goal::bw4t::map::builtin(m).is_some() || Path::new(m).is_file()
}

/// `v` without repeated values (the first of each kept): a map given twice is graded once.
fn distinct<T: Clone + PartialEq>(v: &[T]) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for x in v {
        if !out.contains(x) {
            out.push(x.clone());
        }
    }
    out
}

/// Time a child gets past its own time limit before it is killed.
const GRACE: Duration = Duration::from_secs(5);

/// An observer that only passes warnings on.
struct Quiet;

impl Observer for Quiet {
    fn warning(&mut self, text: &str) {
        eprintln!("warning: {text}");
    }
}

/// One tournament match (`--play A --play B`): the teams' systems merged into one BW4T run.
fn play_main(args: &Args) -> ExitCode {
    let mut teams = Vec::new();
    for p in &args.play {
        match system::load_mas(p) {
            Ok(s) => teams.push(s),
            Err(problems) => {
                for pr in problems {
                    eprint!("{}", pr.render());
                }
                return exit::code(exit::FAILURE);
            }
        }
    }
    let n = args.robots.first().copied().unwrap_or(1);
    let sys = match tournament::merge(&teams, n) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    let time_limit = Duration::from_secs_f64(args.time_limit);
    let opts = RunOptions {
        seed: args.seeds.first().copied(),
        map: args.maps.first().cloned(),
        robots: Some(n * teams.len()),
        max_ticks: args.ticks,
        workers: 1,
        trace_rules: false,
        time_limit: Some(time_limit),
        max_memory: Some(args.max_memory.saturating_mul(1 << 20)),
        cycle_time: Some(time_limit.min(goal::agent::DEFAULT_CYCLE_TIME)),
        ..RunOptions::default()
    };
    let summary = match goal::mas::run(&sys, &opts, None, &mut Quiet) {
        Ok((s, _)) => s,
        Err(problems) => {
            for pr in problems {
                eprint!("{}", pr.render());
            }
            return exit::code(exit::FAILURE);
        }
    };
    if let Some(p) = &args.stats {
        let text = serde_json::to_string_pretty(&summary.to_json()).unwrap_or_default();
        if let Err(e) = std::fs::write(p, text + "\n") {
            eprintln!("error: cannot write stats file {}: {e}", p.display());
            return exit::code(exit::FAILURE);
        }
    }
    exit::code(exit::of_run(&summary, 0))
}
