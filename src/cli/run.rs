//! `goal run [MAS|AGENT]`: run a multi-agent system, a single agent, or the default BW4T team.
//! Standard output carries only what agents print; progress, warnings and the summary go to
//! standard error.

use goal::agent::Message;
use goal::mas::run::{Observer, Progress, RunOptions};
use goal::mas::trace::TraceWriter;
use goal::mas::{default_team, summary, system, vocabulary, MasSystem, Problem};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `goal run`.
#[derive(clap::Args)]
pub struct Args {
    /// A .mas2g or .goal file; without it the built-in BW4T team runs on the default map.
    pub file: Option<PathBuf>,
    /// Run seed (replaces the MAS file's `seed`).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Map: a built-in name, a map file in the project's TOML format, or a BW4T XML map.
    #[arg(long)]
    pub map: Option<String>,
    /// Number of robots in the environment.
    #[arg(long)]
    pub robots: Option<usize>,
    /// Stop after this many environment ticks.
    #[arg(long, default_value_t = 10_000)]
    pub max_ticks: u64,
    /// Stop a single agent (`.goal`) after this many cycles.
    #[arg(long, default_value_t = 10_000)]
    pub max_cycles: u64,
    /// Worker threads for the agents (default: number of cores).
    #[arg(long)]
    pub workers: Option<usize>,
    /// Write the run as JSON lines to this file (see docs/trace-format.md).
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Write the summary as JSON to this file.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Pace the rounds to this many ticks per second (for watching).
    #[arg(long)]
    pub realtime: Option<f64>,
    /// Stop after this many seconds of wall time (the trace then depends on timing).
    #[arg(long)]
    pub time_limit: Option<f64>,
    /// Step every agent every tick, even when it has nothing new (slower; same trace).
    #[arg(long)]
    pub no_skip: bool,
    /// Show every message (logical form, speech act, English) and failed action on stderr.
    #[arg(long)]
    pub verbose: bool,
}

struct Console {
    verbose: bool,
    progress: bool,
    out: std::io::StdoutLock<'static>,
    shown: bool,
}

impl Console {
    fn clear(&mut self) {
        if self.shown {
            eprint!("\r\x1b[K");
            self.shown = false;
        }
    }
}

impl Observer for Console {
    fn printed(&mut self, _agent: &str, line: &str) {
        let _ = writeln!(self.out, "{line}");
    }
    fn message(&mut self, round: u64, m: &Message, delivered: bool) {
        if self.verbose {
            self.clear();
            let r = vocabulary::read(&m.sender, &m.content);
            let english = r.english.map(|e| format!(" \"{e}\"")).unwrap_or_default();
            let lost = if delivered { "" } else { " (unknown receiver)" };
            eprintln!(
                "[{round}] {} -> {}: {} ({:?}){english}{lost}",
                m.sender, m.receiver, r.logical_form, r.act
            );
        }
    }
    fn warning(&mut self, text: &str) {
        self.clear();
        eprintln!("warning: {text}");
    }
    fn action_failed(&mut self, agent: &str, action: &goal::term::Term, reason: &str) {
        if self.verbose {
            self.clear();
            eprintln!("{agent}: action {action} failed: {reason}");
        }
    }
    fn wants_progress(&self) -> bool {
        self.progress
    }
    fn progress(&mut self, p: &Progress) {
        let _ = self.out.flush();
        eprint!(
            "\r\x1b[Ktick {}  deliveries {} right, {} wrong  messages {}",
            p.tick, p.deliveries.right, p.deliveries.wrong, p.messages
        );
        self.shown = true;
    }
}

fn report(problems: &[Problem]) -> ExitCode {
    for p in problems {
        eprint!("{}", p.render());
    }
    ExitCode::from(1)
}

/// Runs `goal run`.
pub fn main(args: Args) -> ExitCode {
    let single = args
        .file
        .as_ref()
        .is_some_and(|f| f.extension().and_then(|e| e.to_str()) == Some("goal"));
    let loaded: Result<MasSystem, Vec<Problem>> = match &args.file {
        None => default_team::system(),
        Some(f) if single => system::load_agent(f),
        Some(f) => system::load_mas(f),
    };
    let sys = match loaded {
        Ok(s) => s,
        Err(p) => return report(&p),
    };
    // The built-in team's warnings are the project's business, not the user's.
    if args.file.is_some() {
        for w in &sys.warnings {
            eprint!("{}", w.render());
        }
        if let Some(env) = &sys.env {
            eprintln!("{}", env.describe());
        }
    }
    let mut opts = RunOptions {
        seed: args.seed,
        map: args.map.clone(),
        robots: args.robots,
        max_ticks: if sys.env.is_none() {
            args.max_cycles.min(args.max_ticks)
        } else {
            args.max_ticks
        },
        realtime: args.realtime,
        time_limit: args
            .time_limit
            .filter(|t| t.is_finite() && *t > 0.0)
            .map(std::time::Duration::from_secs_f64),
        skip_idle: !args.no_skip,
        trace_rules: args.trace.is_some(),
        ..RunOptions::default()
    };
    if let Some(w) = args.workers {
        opts.workers = w.max(1);
    }
    if sys.env.is_none() && (args.map.is_some() || args.robots.is_some()) {
        eprintln!("warning: --map and --robots need an environment; ignored");
    }
    let trace = match &args.trace {
        Some(p) => match std::fs::File::create(p) {
            Ok(f) => Some(TraceWriter::new(Box::new(BufWriter::new(f)))),
            Err(e) => {
                eprintln!("error: cannot create trace file {}: {e}", p.display());
                return ExitCode::from(1);
            }
        },
        None => None,
    };
    let mut console = Console {
        verbose: args.verbose,
        progress: std::io::stderr().is_terminal() && sys.env.is_some(),
        out: std::io::stdout().lock(),
        shown: false,
    };
    let result = goal::mas::run(&sys, &opts, trace, &mut console);
    console.clear();
    let _ = console.out.flush();
    let (summary, trace_err) = match result {
        Ok(r) => r,
        Err(p) => return report(&p),
    };
    if let Some(e) = trace_err {
        eprintln!("error: writing the trace failed: {e}");
    }
    if let Some(p) = &args.stats {
        let text = serde_json::to_string_pretty(&summary.to_json()).unwrap_or_default();
        if let Err(e) = std::fs::write(p, text + "\n") {
            eprintln!("error: cannot write stats file {}: {e}", p.display());
        }
    }
    eprint!("{}", summary::table(&summary));
    if summary.end == goal::mas::EndReason::Failure {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
