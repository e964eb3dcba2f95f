//! The `goal` command line: check, run, test, query and benchmark GOAL agent programs.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod cli;

/// How `goal` ends (also in docs/exit-codes.md).
const EXIT_CODES: &str = "\
Exit codes:
  0    success: files clean, tests passed, the run completed or ended by itself
  1    input errors, a failed test, a Prolog error answer, an output file not written,
       or a failure of the environment
  2    wrong command line (unknown flag, value out of range)
  3    the run hit its tick, cycle or time limit before completing
  4    an agent stopped on a runtime error (also a refused environment action)
  5    the run exceeded its memory cap (--max-memory)
  130  interrupted by Ctrl-C (SIGINT): the run still finishes its round and writes
       the trace's end record and the stats
  141  standard output was closed early (e.g. piped into head)
  143  stopped by SIGTERM (like Ctrl-C)";

/// A fast, deterministic runtime for GOAL agent programs.
#[derive(Parser)]
#[command(name = "goal", version, about, after_help = EXIT_CODES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Check .goal, .mas2g, .test2g and .pl files and report every error and warning.
    Check(cli::check::Args),
    /// Run a multi-agent system (.mas2g) or a single agent (.goal); without a file, the default BW4T team.
    Run(cli::run::Args),
    /// Run the named tests of .test2g files, or check a run against a golden trace (--golden).
    Test(cli::test::Args),
    /// Load Prolog files and print the answers of a query (or read queries from standard input).
    Prolog(cli::prolog::Args),
    /// Run a benchmark (token rings, reasoning, percept load, idle agents) and print its figures.
    Bench(cli::bench::Args),
    /// Grade a class: run every submission on maps, robot counts and seeds; write one table.
    Grade(cli::grade::Args),
    /// Explain what each rule of an agent did at a tick of a run (a trace or a .mas2g rerun).
    Why(cli::why::Args),
    /// Replay a recorded trace in the browser (prints the page's local address).
    View(cli::view::Args),
    /// Explain a diagnostic code (E0121, W0110, ...) with a wrong and a fixed example.
    Explain(cli::explain::Args),
    /// Create a ready project (a .mas2g, agents, a .test2g and a README) from a template.
    New(cli::new::Args),
}

fn main() -> ExitCode {
    cli::exit::quiet_on_broken_pipe();
    let cli = Cli::parse();
    match cli.command {
        Command::Check(args) => cli::check::main(args),
        Command::Run(args) => cli::run::main(args),
        Command::Prolog(args) => cli::prolog::main(args),
        Command::Test(args) => cli::test::main(args),
        Command::Bench(args) => cli::bench::main(args),
        Command::Grade(args) => cli::grade::main(args),
        Command::Why(args) => cli::why::main(args),
        Command::View(args) => cli::view::main(args),
        Command::New(args) => cli::new::main(args),
        Command::Explain(args) => cli::explain::main(args),
    }
}
