//! Testing agents: `goal test` runs the named tests of `.test2g` files (the 2014 `masTest`
//! form, see the README's "Testing agents") on a lock-step, seeded launch of their MAS, and golden traces
//! check that a run still produces the trace it was recorded with.
//!
//! Entry points: [`runner::run_file`] (one `.test2g` file to one [`report::TestReport`] per
//! named test) and [`golden::check`] (a run against a recorded `goal run --trace` file).

pub mod controller;
pub mod golden;
pub mod monitor;
pub mod report;
pub mod runner;

pub use report::{Outcome, TestReport};
