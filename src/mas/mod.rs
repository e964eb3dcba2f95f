//! Multi-agent systems: the `.mas2g` model, launch policies, the scheduler, message routing, traces.
//!
//! Load a system with [`system::load_mas`] (a `.mas2g` file), [`system::load_agent`] (one
//! `.goal` file, no environment) or [`default_team::system`] (the built-in BW4T team), then
//! [`run::run`] it with [`run::RunOptions`]; the result is a [`stats::RunSummary`]. Traces are
//! JSON lines ([`trace::TraceWriter`], format in `docs/trace-format.md`).

pub mod default_team;
pub mod launch;
pub mod routing;
pub mod run;
pub mod scheduler;
pub mod stats;
pub mod summary;
pub mod system;
pub mod trace;
pub mod vocabulary;

pub use run::{run, Observer, Progress, RunOptions};
pub use stats::{EndReason, RunSummary};
pub use system::{MasSystem, Problem};
