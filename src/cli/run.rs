//! `goal run [MAS|AGENT]`: run a multi-agent system, a single agent, or the default BW4T team.
//! Standard output carries only what agents print; progress, warnings and the summary go to
//! standard error. The exit code tells how the run ended (see `goal --help`).

use super::exit;
use super::limits;
use goal::agent::Message;
use goal::env::EntityInfo;
use goal::mas::input::{Input, InputLog};
use goal::mas::run::{Observer, Progress, RunOptions};
use goal::mas::trace::TraceWriter;
use goal::mas::{default_team, summary, system, vocabulary, MasSystem, Problem};
use goal::view::{server, Control, Feed, FeedWriter, Pacer, Site, ViewServer};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

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
    /// Number of HumanBots, robots people play in the browser (BW4T's `humancount`; implies
    /// --view): `goal run --humans 1` adds a fourth robot to the default team for you.
    #[arg(long, value_parser = limits::humans)]
    pub humans: Option<usize>,
    /// Stop after this many environment ticks (at least 1).
    #[arg(long, default_value_t = 10_000, value_parser = limits::positive)]
    pub max_ticks: u64,
    /// Stop a system without environment after this many cycles (rounds; at least 1).
    #[arg(long, default_value_t = 10_000, value_parser = limits::positive)]
    pub max_cycles: u64,
    /// Worker threads for the agents (1 to 1024; default: number of cores).
    #[arg(long, value_parser = limits::workers)]
    pub workers: Option<usize>,
    /// Write the run as JSON lines to this file (see docs/trace-format.md).
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Write the summary as JSON to this file.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Pace the rounds to this many ticks per second (for watching; 0.001 to 1000000).
    #[arg(long, value_parser = limits::rate)]
    pub realtime: Option<f64>,
    /// Stop after this many seconds of wall time (the trace then depends on timing).
    #[arg(long, value_parser = limits::seconds)]
    pub time_limit: Option<f64>,
    /// Seconds one cycle of an agent may take; a longer cycle stops that agent with an error.
    #[arg(long, default_value_t = goal::agent::DEFAULT_CYCLE_TIME.as_secs_f64(), value_parser = limits::seconds)]
    pub cycle_time: f64,
    /// Most facts an agent's belief base may hold; more stops that agent with an error.
    #[arg(long, default_value_t = goal::agent::DEFAULT_MAX_BELIEFS as u64, value_parser = limits::positive)]
    pub max_beliefs: u64,
    /// Most messages waiting for an agent in one round; more are dropped (and reported).
    #[arg(long, default_value_t = goal::mas::run::DEFAULT_MAX_MAILBOX as u64, value_parser = limits::positive)]
    pub max_mailbox: u64,
    /// Most messages an agent may send in one cycle; more stops that agent with an error.
    #[arg(long, default_value_t = goal::mas::run::DEFAULT_MAX_MAILBOX as u64, value_parser = limits::positive)]
    pub max_sent: u64,
    /// Stop the run when the process uses more than this many MiB of memory.
    #[arg(long, default_value_t = goal::mas::run::DEFAULT_MAX_MEMORY >> 20, value_parser = limits::positive)]
    pub max_memory: u64,
    /// Step every agent every tick, even when it has nothing new (slower; same trace).
    #[arg(long)]
    pub no_skip: bool,
    /// Start each line an agent prints with the agent's name (`Bot1: ...`).
    #[arg(long)]
    pub prefix: bool,
    /// Show every message (logical form, speech act, English) and failed action on stderr.
    #[arg(long)]
    pub verbose: bool,
    /// Watch the run in a browser: serve it on ADDR:PORT (default 127.0.0.1, any free port),
    /// paced for watching; the page can pause, step and change the speed.
    #[arg(long, value_name = "ADDR:PORT", num_args = 0..=1, default_missing_value = server::DEFAULT_ADDR)]
    pub view: Option<String>,
    /// How messages travel: `in-process` (default) or `ring`, the simulated token ring.
    #[arg(long, value_parser = ["in-process", "ring"], default_value = "in-process")]
    pub comm: String,
    /// Ring fault: AGENT's link fails at TICK (`Bot2@500`; repeatable; needs --comm ring).
    #[arg(long, value_name = "AGENT@TICK", value_parser = goal::clamr::transport::parse_fail)]
    pub comm_fail: Vec<(String, u64)>,
    /// Ring fault: each message is lost with this probability (0 to 1; seeded; needs --comm ring).
    #[arg(long, value_parser = limits::probability)]
    pub comm_loss: Option<f64>,
    /// Write the conversations' session records into the trace (see docs/trace-format.md).
    #[arg(long)]
    pub trace_sessions: bool,
    /// The KR engine of agents whose `.mas2g` entry has no `language`: native (default) or scryer.
    #[arg(long, default_value = "native", value_parser = super::limits::kr_engine)]
    pub kr: goal::kr::KrKind,
}

struct Console {
    verbose: bool,
    progress: bool,
    prefix: bool,
    out: std::io::StdoutLock<'static>,
    shown: bool,
    /// Raised when standard output is a closed pipe: the run stops after the round.
    stop: Arc<AtomicUsize>,
    /// Paces the run for a watching page (`--view`).
    pacer: Option<Pacer>,
    /// The watching page's controls, through which people play HumanBots.
    control: Option<Arc<Control>>,
    /// The people's requests taken so far (a why-question reruns them).
    inputs: InputLog,
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
    fn printed(&mut self, agent: &str, line: &str) {
        let line = limits::escape_controls(line);
        let written = if self.prefix {
            writeln!(self.out, "{agent}: {line}")
        } else {
            writeln!(self.out, "{line}")
        };
        if written.is_err_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe) {
            self.stop
                .store(usize::from(exit::BROKEN_PIPE - 128), Ordering::Relaxed);
        }
    }
    fn message(&mut self, round: u64, m: &Message, delivered: bool) {
        if self.verbose {
            self.clear();
            let r = vocabulary::read(m.sender.name(), &m.content);
            let english = r.english.map(|e| format!(" \"{e}\"")).unwrap_or_default();
            let lost = if delivered { "" } else { " (not delivered)" };
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
        // Not verbose: the agent's stop (a runtime error, reported as a warning) says it.
        if self.verbose {
            self.clear();
            eprintln!("{agent}: action {action} failed: {reason}");
        }
    }
    fn wants_progress(&self) -> bool {
        self.progress
    }
    fn pace(&mut self, _round: u64, tick: u64) {
        if let Some(p) = &mut self.pacer {
            p.wait(tick);
        }
    }
    fn entities(&mut self, entities: &[EntityInfo]) {
        let humans: Vec<String> = entities
            .iter()
            .filter(|e| e.kind == goal::view::players::HUMAN_KIND)
            .map(|e| e.name.clone())
            .collect();
        match &self.control {
            Some(c) => c.players().announce(humans),
            None if !humans.is_empty() => self.warning(&format!(
                "nobody can play the HumanBots {} without the browser view: they stand still \
                 (run with --view to play them)",
                humans.join(", ")
            )),
            None => {}
        }
    }
    fn inputs(&mut self, _round: u64) -> Vec<Input> {
        self.control
            .as_ref()
            .map(|c| c.players().drain())
            .unwrap_or_default()
    }
    fn input_applied(&mut self, round: u64, tick: u64, input: &Input, result: &Result<(), String>) {
        if let Some(c) = &self.control {
            c.players().applied(tick, result);
        }
        self.inputs.push(round, input.clone());
        if self.verbose {
            self.clear();
            let what = match result {
                Ok(()) => "taken".to_string(),
                Err(e) => format!("refused: {e}"),
            };
            eprintln!(
                "[{round}] player request for {}: {} {what}",
                input.entity,
                input.request_text()
            );
        }
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
    exit::code(exit::FAILURE)
}

/// Ctrl-C and SIGTERM set `flag` to the signal's number: the run finishes its round, writes
/// the trace's end record and the stats, and exits with 128 + the signal. A second signal
/// ends the program at once.
pub(crate) fn catch_signals(flag: &Arc<AtomicUsize>) {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use signal_hook::flag as sig;
    for s in [SIGINT, SIGTERM] {
        let again = Arc::new(AtomicBool::new(false));
        // Registered first, so it sees the flag of an earlier signal only.
        let _ = sig::register_conditional_shutdown(s, 128 + s, again.clone());
        let _ = sig::register(s, again);
        let _ = sig::register_usize(s, flag.clone(), s as usize);
    }
}

/// Starts the view server for `site` on `addr` and prints its address; `None` (said on
/// stderr) when it cannot serve.
pub(crate) fn open_view(addr: &str, site: Site) -> Option<ViewServer> {
    let mut notes = Vec::new();
    let served = server::serve(addr, site, &mut notes);
    for n in notes {
        eprintln!("warning: {n}");
    }
    match served {
        Ok(s) => {
            eprintln!("view: {} (open it in a browser)", s.url());
            Some(s)
        }
        Err(e) => {
            eprintln!("error: {e}");
            None
        }
    }
}

/// Waits until Ctrl-C or SIGTERM sets `stop`.
pub(crate) fn wait_for_signal(stop: &AtomicUsize) {
    while stop.load(Ordering::Relaxed) == 0 {
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}

/// A watched run: the page's feed of trace lines, its controls and the server.
struct Watch {
    feed: Arc<Feed>,
    control: Arc<Control>,
    server: ViewServer,
}

fn watch(
    args: &Args,
    addr: &str,
    sys: &MasSystem,
    opts: &RunOptions,
    inputs: &InputLog,
) -> Option<Watch> {
    let feed = Arc::new(Feed::new());
    let control = Control::new(goal::view::control::DEFAULT_SPEED);
    let title = args
        .file
        .as_ref()
        .map_or("the default BW4T team".into(), |f| f.display().to_string());
    let site = Site {
        feed: feed.clone(),
        control: Some(control.clone()),
        // Runs are deterministic: a why-question reruns the system up to the asked tick.
        // People's requests are part of the run: the rerun takes them again.
        why: Some(Arc::new(
            goal::why::Why::for_system(sys.clone(), opts.clone()).with_inputs(inputs.clone()),
        )),
        title,
    };
    let server = open_view(addr, site)?;
    Some(Watch {
        feed,
        control,
        server,
    })
}

/// The trace sink: the `--trace` file, the watching page's feed, or both.
fn trace_sink(
    path: Option<&PathBuf>,
    feed: Option<&Arc<Feed>>,
) -> Result<Option<TraceWriter>, String> {
    let file = match path {
        Some(p) => match std::fs::File::create(p) {
            Ok(f) => Some(BufWriter::new(f)),
            Err(e) => return Err(format!("cannot create trace file {}: {e}", p.display())),
        },
        None => None,
    };
    let out: Box<dyn Write + Send> = match (file, feed) {
        (Some(f), Some(feed)) => Box::new(goal::view::feed::Tee {
            first: f,
            second: FeedWriter::new(feed.clone()),
        }),
        (Some(f), None) => Box::new(f),
        (None, Some(feed)) => Box::new(FeedWriter::new(feed.clone())),
        (None, None) => return Ok(None),
    };
    Ok(Some(TraceWriter::new(out)))
}

fn options(args: &Args, sys: &MasSystem, stop: &Arc<AtomicUsize>) -> RunOptions {
    let cycle_time = std::time::Duration::from_secs_f64(args.cycle_time);
    let time_limit = args.time_limit.map(std::time::Duration::from_secs_f64);
    let mut opts = RunOptions {
        seed: args.seed,
        map: args.map.clone(),
        robots: args.robots,
        humans: args.humans,
        max_ticks: if sys.env.is_none() {
            args.max_cycles.min(args.max_ticks)
        } else {
            args.max_ticks
        },
        realtime: args.realtime,
        time_limit,
        skip_idle: !args.no_skip,
        // The page shows the rules fired, like a trace file.
        trace_rules: args.trace.is_some() || args.view.is_some(),
        interrupt: Some(stop.clone()),
        max_memory: Some(args.max_memory.saturating_mul(1 << 20)),
        // A cycle never outlasts the run's time limit.
        cycle_time: Some(time_limit.map_or(cycle_time, |t| t.min(cycle_time))),
        max_beliefs: usize::try_from(args.max_beliefs).unwrap_or(usize::MAX),
        max_mailbox: usize::try_from(args.max_mailbox).unwrap_or(usize::MAX),
        max_sent: usize::try_from(args.max_sent).unwrap_or(usize::MAX),
        kr: args.kr,
        ..RunOptions::default()
    };
    if let Some(w) = args.workers {
        opts.workers = w;
    }
    opts.comm = goal::clamr::CommOptions {
        kind: if args.comm == "ring" {
            goal::clamr::transport::Kind::Ring
        } else {
            goal::clamr::transport::Kind::InProcess
        },
        faults: goal::clamr::ring::Faults {
            fail: args.comm_fail.clone(),
            loss: args.comm_loss.unwrap_or(0.0),
        },
        sessions: args.stats.is_some(),
        trace_sessions: args.trace_sessions,
    };
    opts
}

/// `goal run --view team.mas2g`: clap reads the file as `--view`'s address; a value that is
/// no address but names an existing file is the system to run, watched on the default address.
fn view_file_as_system(args: &mut Args) {
    // People play HumanBots in the browser: --humans serves the view.
    if args.humans.is_some_and(|h| h > 0) && args.view.is_none() {
        args.view = Some(server::DEFAULT_ADDR.to_string());
    }
    let Some(v) = &args.view else { return };
    if args.file.is_none() && server::parse_addr(v).is_err() && std::path::Path::new(v).is_file() {
        args.file = Some(PathBuf::from(v));
        args.view = Some(server::DEFAULT_ADDR.to_string());
    }
}

/// Runs `goal run`.
pub fn main(mut args: Args) -> ExitCode {
    view_file_as_system(&mut args);
    if args.comm != "ring" && (!args.comm_fail.is_empty() || args.comm_loss.is_some()) {
        eprintln!(
            "error: --comm-fail and --comm-loss inject faults into the token ring; add --comm ring"
        );
        return exit::code(exit::USAGE);
    }
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
    let stop = Arc::new(AtomicUsize::new(0));
    let opts = options(&args, &sys, &stop);
    if sys.env.is_none() && (args.map.is_some() || args.robots.is_some() || args.humans.is_some()) {
        eprintln!("warning: --map, --robots and --humans need an environment; ignored");
    }
    let inputs = InputLog::new();
    let watched = match &args.view {
        Some(addr) => match watch(&args, addr, &sys, &opts, &inputs) {
            Some(w) => Some(w),
            None => return exit::code(exit::FAILURE),
        },
        None => None,
    };
    let trace = match trace_sink(args.trace.as_ref(), watched.as_ref().map(|w| &w.feed)) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    catch_signals(&stop);
    let mut console = Console {
        verbose: args.verbose,
        progress: std::io::stderr().is_terminal() && sys.env.is_some(),
        prefix: args.prefix,
        out: std::io::stdout().lock(),
        shown: false,
        stop: stop.clone(),
        pacer: watched
            .as_ref()
            .map(|w| Pacer::new(w.control.clone(), stop.clone())),
        control: watched.as_ref().map(|w| w.control.clone()),
        inputs,
    };
    let result = goal::mas::run(&sys, &opts, trace, &mut console);
    console.clear();
    let _ = console.out.flush();
    let (summary, trace_err) = match result {
        Ok(r) => r,
        Err(p) => return report(&p),
    };
    let mut files_ok = true;
    if let Some(e) = trace_err {
        eprintln!("error: writing the trace failed: {e}");
        files_ok = false;
    }
    if let Some(p) = &args.stats {
        let text = serde_json::to_string_pretty(&summary.to_json()).unwrap_or_default();
        if let Err(e) = std::fs::write(p, text + "\n") {
            eprintln!("error: cannot write stats file {}: {e}", p.display());
            files_ok = false;
        }
    }
    eprint!("{}", summary::table(&summary));
    let signal = stop.load(Ordering::Relaxed);
    let code = exit::of_run(&summary, signal);
    if let Some(w) = watched {
        w.feed.close();
        w.control.end();
        if signal == 0 {
            eprintln!(
                "the run is over; the page stays at {} until Ctrl-C",
                w.server.url()
            );
            wait_for_signal(&stop);
        }
    }
    if !files_ok && code != exit::SIGINT && code != exit::SIGTERM {
        return exit::code(exit::FAILURE);
    }
    exit::code(code)
}
