//! `goal run [MAS|AGENT]`: run a multi-agent system, a single agent, or the default BW4T team.

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `goal run`.
#[derive(clap::Args)]
pub struct Args {
    /// A .mas2g or .goal file; without it the built-in BW4T team runs on the default map.
    pub file: Option<PathBuf>,
}

/// Runs `goal run`.
pub fn main(_args: Args) -> ExitCode {
    eprintln!("goal run: running agents is not built yet (issues 4-6); `goal check` and `cargo test` work today");
    ExitCode::from(2)
}
