//! Watching a run in the browser: a small local web server (`tiny_http`) that serves one page,
//! embedded in the binary, and the run's trace lines — live while `goal run --view` runs, or
//! read from a file for `goal view TRACE`. The page rebuilds the world and every agent's mind
//! from those lines (the trace format is the one data model, docs/trace-format.md); see
//! docs/view.md.
//!
//! * [`feed`]: the trace lines so far, shared between the run and the server's clients, the
//!   newest in memory and the older ones in a [`spill`] file on disk, so memory stays bounded;
//! * [`control`]: pacing, pausing and single-stepping a live run from the page (through the
//!   round driver's [`crate::mas::Observer::pace`]);
//! * [`replay`]: checking a recorded trace and serving it from its file;
//! * [`server`]: the HTTP routes, the server-sent-event stream and the why endpoint;
//! * [`page`]: the embedded page (HTML, CSS, JavaScript; no build step, no network);
//! * [`players`], [`play`]: people playing a live run's HumanBots from their browsers (one
//!   robot each) and the endpoints their pages use; requests reach the run through
//!   [`Control::players`] at its tick boundaries (`Observer::inputs`).

pub mod control;
pub mod feed;
pub mod page;
pub mod play;
pub mod players;
pub mod replay;
pub mod server;
pub mod spill;

pub use control::{Control, Pacer};
pub use feed::{Feed, FeedWriter};
pub use server::{serve, Site, ViewServer};

/// Answers "why did (or didn't) each rule fire" for an agent at a tick, as JSON
/// (`{ agent, tick, cycle, module, rules: [ { rule, text, outcome, bindings, failed_literal,
/// failed_action } ] }`); the page shows it for the selected agent and tick.
pub trait WhyProvider: Send + Sync {
    /// The report for `agent` at `tick`, or why there is none.
    fn why(&self, agent: &str, tick: u64) -> Result<serde_json::Value, String>;
}
