//! `goal view TRACE`: replay a recorded run in the browser. Serves the page and the trace on a
//! local address (printed), until Ctrl-C.

use super::exit;
use goal::view::{replay, server, Site};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicUsize;
use std::sync::Arc;

/// Arguments of `goal view`.
#[derive(clap::Args)]
pub struct Args {
    /// A trace written by `goal run --trace FILE`.
    pub trace: PathBuf,
    /// Where to serve the page: ADDR:PORT (default: this machine only, any free port).
    #[arg(long, default_value = server::DEFAULT_ADDR)]
    pub addr: String,
}

/// Runs `goal view`.
pub fn main(args: Args) -> ExitCode {
    let feed = match replay::load(&args.trace) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return exit::code(exit::FAILURE);
        }
    };
    // The trace's header names the system and its options: why-questions rerun it.
    let why: Option<Arc<dyn goal::view::WhyProvider>> = match goal::why::Why::for_trace(&args.trace)
    {
        Ok(w) => Some(Arc::new(w)),
        Err(e) => {
            eprintln!("warning: why-questions are unavailable for this replay: {e}");
            None
        }
    };
    let site = Site {
        feed: Arc::new(feed),
        control: None,
        why,
        title: args.trace.display().to_string(),
    };
    let stop = Arc::new(AtomicUsize::new(0));
    super::run::catch_signals(&stop);
    let Some(server) = super::run::open_view(&args.addr, site) else {
        return exit::code(exit::FAILURE);
    };
    eprintln!("replaying {}; press Ctrl-C to stop", args.trace.display());
    super::run::wait_for_signal(&stop);
    drop(server);
    exit::code(exit::OK)
}
