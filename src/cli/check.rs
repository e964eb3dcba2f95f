//! `goal check FILE... [--format json]`: parse and validate files, print diagnostics.

use goal::syntax::check::FileReport;
use std::path::PathBuf;
use std::process::ExitCode;

/// How diagnostics are printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Like rustc: `error[E0014]: ...`, the source line and a caret.
    Text,
    /// One JSON object per line.
    Json,
}

/// Arguments of `goal check`.
#[derive(clap::Args)]
pub struct Args {
    /// Files to check (.goal, .mod2g, .mas2g, .test2g, .pl).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output format of the diagnostics.
    #[arg(long, value_enum, default_value = "text")]
    pub format: Format,
}

/// Runs `goal check`: diagnostics on stdout, a summary line on stderr; exit 1 when any error.
pub fn main(args: Args) -> ExitCode {
    // A .mas2g also checks the agent files it names.
    let reports: Vec<FileReport> = args
        .files
        .iter()
        .flat_map(|f| goal::mas::envcheck::check_path(f))
        .collect();
    let (mut errors, mut warnings) = (0usize, 0usize);
    for r in &reports {
        for d in &r.diagnostics {
            if d.is_error() {
                errors += 1;
            } else {
                warnings += 1;
            }
            match args.format {
                Format::Text => print!("{}", d.render(&r.source)),
                Format::Json => println!("{}", d.to_json(&r.source)),
            }
        }
    }
    eprintln!(
        "checked {} file{}: {errors} error{}, {warnings} warning{}",
        reports.len(),
        plural(reports.len()),
        plural(errors),
        plural(warnings)
    );
    if errors > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
