//! Hooks for test controllers: a [`Watcher`] sees the mental state at every observable event
//! (module entry, module exit, each performed action), as `.test2g` conditions need.

use super::mental_state::MentalState;
use crate::term::Term;

/// An observable point of an agent's run.
#[derive(Clone, Copy, Debug)]
pub enum Observed<'a> {
    /// A named module was entered.
    ModuleEntered(&'a str),
    /// A named module exited.
    ModuleExited(&'a str),
    /// An action was performed (the ground action term, e.g. `insert(p)` or `move(a, b)`).
    Action(&'a Term),
}

/// Observes an agent's mental state at each observable event (installed with
/// `Agent::set_watcher`).
pub trait Watcher: Send {
    /// Called right after the event happened.
    fn observe(&mut self, ms: &MentalState, at: Observed<'_>);
}
