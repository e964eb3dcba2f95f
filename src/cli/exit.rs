//! The exit codes of `goal` (see docs/exit-codes.md), one place for all subcommands.

use goal::mas::{EndReason, RunSummary};
use std::process::ExitCode;

/// Everything went as asked: files clean, tests passed, the run completed or ended by itself.
pub const OK: u8 = 0;
/// Errors in the input files, a failed test, an error answer, an output file that could not be
/// written, or a failure of the environment or a worker thread.
pub const FAILURE: u8 = 1;
/// The command line was wrong (an unknown flag, a value out of range).
pub const USAGE: u8 = 2;
/// A run hit its tick, cycle or time limit before its task was complete.
pub const INCOMPLETE: u8 = 3;
/// An agent stopped on a runtime error (the others may have finished).
pub const AGENT_ERROR: u8 = 4;
/// The run used more memory than its cap (`--max-memory`).
pub const MEMORY: u8 = 5;
/// Interrupted by Ctrl-C (SIGINT): 128 + 2.
pub const SIGINT: u8 = 130;
/// Standard output was closed early (e.g. piped into `head`): 128 + SIGPIPE (13).
pub const BROKEN_PIPE: u8 = 141;
/// Stopped by SIGTERM: 128 + 15.
pub const SIGTERM: u8 = 143;

/// The exit code of a finished run: failures first, then agent errors, then limits.
pub fn of_run(s: &RunSummary, signal: usize) -> u8 {
    match s.end {
        EndReason::Failure => return FAILURE,
        EndReason::MemoryLimit => return MEMORY,
        EndReason::Interrupted => return 128u8.saturating_add(signal.min(127) as u8),
        _ => {}
    }
    if s.agents.values().any(|a| a.error.is_some()) {
        return AGENT_ERROR;
    }
    match s.end {
        EndReason::TickLimit | EndReason::CycleLimit | EndReason::TimeLimit => INCOMPLETE,
        _ => OK,
    }
}

/// `code` as an [`ExitCode`].
pub fn code(code: u8) -> ExitCode {
    ExitCode::from(code)
}

/// Ends the program quietly when standard output is a closed pipe (the conventional code of
/// a process killed by SIGPIPE), instead of a panic from `println!`.
pub fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let text = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if text.contains("Broken pipe") {
            std::process::exit(i32::from(BROKEN_PIPE));
        }
        default(info);
    }));
}

/// Writes `text` to standard output; a closed pipe ends the program quietly.
pub fn say(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(i32::from(BROKEN_PIPE));
        }
    }
}
