//! The GOAL agent: mental state, conditions, modules, rules, actions and the reasoning cycle.
//!
//! Public API: compile a program with [`Program::from_source`] (shared via `Arc`), create
//! agents with [`Agent::new`] and an [`AgentConfig`], and run cycles with [`Agent::step`],
//! which returns a [`CycleOutput`] (environment actions, [`Message`]s, trace [`Event`]s,
//! printed lines, and a [`StopReason`] once the agent stopped).
//!
//! Design notes:
//! * A program is compiled once (`compile.rs`: macros expanded with renamed variables, calls
//!   resolved by name/arity, action-spec variables renamed apart) and shared by every agent;
//!   an agent holds only its mental state, a `NativeEngine` (seeded RNG, output buffer) and
//!   its execution stack, so 10,000 agents are cheap.
//! * Execution is an explicit stack of frames (`module.rs`): module passes, rule applications
//!   (answers computed up front) and combos. In main context the stack is suspended after every
//!   rule application that performed a real action (and after an idle pass), which is the
//!   cycle boundary of GOAL's 2014 runtime; the next `step` resumes it after percepts,
//!   messages and the event module. `init` and `event` run to completion. Nothing recurses
//!   over user-controlled nesting; a step budget turns endless module loops into errors.
//! * Percepts are typed (`percepts.rs`); `percept/1` reads the typed base and `newpercept/1`
//!   the raw batch of the current cycle.
//! * Conditions with selectors other than `this`/`self` query mental models of the other agents
//!   (`models.rs`), which received messages update when the program uses such selectors; sends
//!   support `all`, `allother`, `self`, names, variables and lists.

pub mod action;
mod compile;
pub mod condition;
pub mod conjunction;
pub mod cycle;
pub mod directory;
pub mod error;
pub mod goals;
pub mod kr_bridge;
pub mod load;
mod lookup;
pub mod mailbox;
pub mod mental_state;
mod mentions;
pub mod message;
pub mod models;
pub mod module;
pub mod percepts;
pub mod program;
pub mod rule;
mod spare;
pub mod timing;
pub mod trace;
pub mod watch;
pub mod why;

pub use cycle::{
    show_duration, Agent, AgentConfig, CycleOutput, StopReason, DEFAULT_CYCLE_TIME,
    DEFAULT_MAX_BELIEFS,
};
pub use directory::Directory;
pub use error::RuntimeError;
pub use mailbox::Message;
pub use percepts::{PerceptType, PerceptTypes};
pub use program::Program;
pub use trace::{Event, TraceLevel};
pub use watch::{Observed, Watcher};
