//! Multi-agent systems: the `.mas2g` model, launch policies, the scheduler, message routing, traces.
//!
//! Load a system with [`system::load_mas`] (a `.mas2g` file), [`system::load_agent`] (one
//! `.goal` file, no environment) or [`default_team::system`] (the built-in BW4T team), then
//! [`run::run`] it with [`run::RunOptions`]; the result is a [`stats::RunSummary`]. Traces are
//! JSON lines ([`trace::TraceWriter`], format in `docs/trace-format.md`).
//!
//! Lock-step rounds (ARCHITECTURE.md, "How a run flows"): the environment runs on its
//! own thread ([`crate::env::thread`]), agents are owned by the workers of a
//! [`scheduler::Pool`] (worker 0 is the scheduler thread), environment actions are applied in
//! agent-name order and messages delivered at the next round in (sender, sequence) order, so
//! a run depends only on programs, map and seed. Agents with nothing new are not stepped.
//!
//! ## Not there yet
//! * Real-time mode: `--realtime TPS` paces the lock-step rounds (same trace, slower); agents
//!   do not yet cycle freely against a free-running environment.
//! * Entities that are freed or deleted during a run (BW4T never does this today), so agents
//!   are never stopped or relaunched by the environment.
//! * Environments other than the built-in `bw4t` and `blocksworld`; `language=` of agent files
//!   is ignored.
//! * CLAMR sessions (conversation tracking).

pub mod default_team;
pub mod envcheck;
pub mod environment;
pub mod input;
pub mod launch;
pub mod memory;
pub mod modular;
pub mod observer;
pub mod options;
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
