//! `goal prolog FILE.pl... -q QUERY`: query a knowledge base from the shell.

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `goal prolog`.
#[derive(clap::Args)]
pub struct Args {
    /// Prolog files to load.
    pub files: Vec<PathBuf>,
    /// The query; without it, queries are read from standard input, one per line.
    #[arg(short, long)]
    pub query: Option<String>,
}

/// Runs `goal prolog`.
pub fn main(_args: Args) -> ExitCode {
    eprintln!("goal prolog: the Prolog engine is not built yet (issue 3)");
    ExitCode::from(2)
}
