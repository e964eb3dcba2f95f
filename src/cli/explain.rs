//! `goal explain CODE`: the page of a diagnostic code (what it means, a wrong and a fixed
//! example), like `rustc --explain`.

use super::exit::{self, say};
use goal::syntax::codes::{page, CODES};
use std::process::ExitCode;

/// Arguments of `goal explain`.
#[derive(clap::Args)]
pub struct Args {
    /// A diagnostic code, such as E0121, W0110 or M0013 (any case).
    pub code: String,
}

/// Prints the page of the code; an unknown code is a plain message, the closest known code and
/// exit 1.
pub fn main(args: Args) -> ExitCode {
    let code = args.code.trim().to_ascii_uppercase();
    if let Some(text) = page(&code) {
        say(text);
        return ExitCode::SUCCESS;
    }
    let known = CODES.iter().map(|(c, _)| *c);
    let hint = match goal::env::suggest::closest(&code, known) {
        Some(near) => format!("; did you mean {near}?"),
        None => String::new(),
    };
    eprintln!(
        "error: `{}` is not a diagnostic code of goal{hint} Codes look like E0121 (errors), \
         W0110 (warnings) or M0013 (maps, environments, starting a run); docs/diagnostics/ \
         lists them all.",
        args.code
    );
    ExitCode::from(exit::FAILURE)
}
