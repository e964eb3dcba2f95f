//! The GOAL agent: mental state, conditions, modules, rules, actions and the reasoning cycle.
//!
//! Public API: compile a program with [`Program::from_source`] (shared via `Arc`), create
//! agents with [`Agent::new`] and an [`AgentConfig`], and run cycles with [`Agent::step`],
//! which returns a [`CycleOutput`] (environment actions, [`Message`]s, trace [`Event`]s,
//! printed lines, and a [`StopReason`] once the agent stopped).

pub mod action;
mod compile;
pub mod condition;
pub mod cycle;
pub mod directory;
pub mod error;
pub mod goals;
pub mod kr_bridge;
pub mod mailbox;
pub mod mental_state;
pub mod message;
pub mod module;
pub mod percepts;
pub mod program;
pub mod rule;
pub mod trace;

pub use cycle::{Agent, AgentConfig, CycleOutput, StopReason};
pub use directory::Directory;
pub use error::RuntimeError;
pub use mailbox::Message;
pub use percepts::{PerceptType, PerceptTypes};
pub use program::Program;
pub use trace::{Event, TraceLevel};
