//! `goal why [TRACE|MAS] --agent NAME --tick N`: what each rule of the agent did in its cycle
//! at that tick (fired, the literal that failed, the action whose precondition failed, not
//! evaluated), found by rerunning the system up to that tick. See docs/why.md.

use super::exit;
use goal::mas::run::RunOptions;
use goal::mas::{default_team, system, MasSystem, Problem};
use goal::why::{text, Why, WhyError};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `goal why`.
#[derive(clap::Args)]
pub struct Args {
    /// A trace written by `goal run --trace`, or a .mas2g or .goal file to run; without it the
    /// built-in BW4T team on the default map.
    pub file: Option<PathBuf>,
    /// The agent to explain.
    #[arg(long)]
    pub agent: String,
    /// The tick of its cycle to explain.
    #[arg(long)]
    pub tick: u64,
    /// Run seed, for a .mas2g or .goal file (a trace names its own).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Map, for a .mas2g or .goal file: a built-in name, a TOML map or a BW4T XML map.
    #[arg(long)]
    pub map: Option<String>,
    /// Number of robots, for a .mas2g or .goal file.
    #[arg(long)]
    pub robots: Option<usize>,
    /// For a .mas2g or .goal file: the run's tick limit, as `goal run --max-ticks` (later
    /// ticks are past its end).
    #[arg(long, default_value_t = 10_000, value_parser = super::limits::positive)]
    pub max_ticks: u64,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

fn is_program(f: &Path) -> bool {
    matches!(
        f.extension().and_then(|e| e.to_str()),
        Some("mas2g" | "goal")
    )
}

fn loaded(p: Result<MasSystem, Vec<Problem>>) -> Result<MasSystem, WhyError> {
    p.map_err(|ps| WhyError::Load(ps.iter().map(|p| p.render()).collect()))
}

fn why(args: &Args) -> Result<Why, WhyError> {
    let opts = RunOptions {
        seed: args.seed,
        map: args.map.clone(),
        robots: args.robots,
        max_ticks: args.max_ticks,
        ..RunOptions::default()
    };
    match &args.file {
        Some(f) if !is_program(f) => Why::for_trace(f),
        Some(f) if f.extension().and_then(|e| e.to_str()) == Some("goal") => {
            Ok(Why::for_system(loaded(system::load_agent(f))?, opts))
        }
        Some(f) => Ok(Why::for_system(loaded(system::load_mas(f))?, opts)),
        None => Ok(Why::for_system(loaded(default_team::system())?, opts)),
    }
}

/// Runs `goal why`.
pub fn main(args: Args) -> ExitCode {
    let for_run = args.seed.is_some() || args.map.is_some() || args.robots.is_some();
    if for_run && args.file.as_deref().is_some_and(|f| !is_program(f)) {
        eprintln!(
            "error: --seed, --map and --robots are for a .mas2g or .goal file; a trace names \
             its own"
        );
        return exit::code(exit::USAGE);
    }
    let report = why(&args).and_then(|w| w.report(&args.agent, args.tick));
    if let Ok(r) = &report {
        if r.matches_trace == Some(false) {
            eprintln!("warning: {}", goal::why::MISMATCH);
        }
    }
    match report {
        Ok(r) if args.json => {
            let text = serde_json::to_string_pretty(&r).unwrap_or_default();
            exit::say(&(text + "\n"));
            exit::code(exit::OK)
        }
        Ok(r) => {
            exit::say(&text::render(&r));
            exit::code(exit::OK)
        }
        Err(WhyError::Load(m)) => {
            eprint!("{m}");
            if !m.ends_with('\n') {
                eprintln!();
            }
            exit::code(exit::FAILURE)
        }
        Err(e) => {
            eprintln!("error: {e}");
            exit::code(exit::FAILURE)
        }
    }
}
