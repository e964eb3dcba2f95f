//! `goal check FILE...`: parse and validate files, print diagnostics.

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `goal check`.
#[derive(clap::Args)]
pub struct Args {
    /// Files to check (.goal, .mas2g, .test2g, .pl).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// Runs `goal check`.
pub fn main(_args: Args) -> ExitCode {
    eprintln!("goal check: the parser is not built yet (issue 2)");
    ExitCode::from(2)
}
