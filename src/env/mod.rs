//! The environment interface: entities, typed percepts, actions and their results.
//!
//! An environment owns a simulated world with named entities (robots, ...). Agents act through
//! [`Environment::perform`] with actions written as terms, the world advances by
//! [`Environment::tick`], and each entity receives a per-tick percept batch from
//! [`Environment::percepts`]. Each percept predicate has a declared [`PerceptType`]; the agent
//! runtime keeps a typed percept base from the batches (`agent::percepts`).
//! [`filter::PerceptFilter`] turns the full current truth into such batches.
//! [`thread::EnvHandle`] runs any environment (lock-step on the caller's thread, real-time on its own), and
//! [`FromInitParams`] creates one from init parameters (key -> term).

pub mod filter;
pub mod suggest;
pub mod thread;

use crate::diag::Diagnostic;
use crate::term::Term;
use serde::Serialize;
use std::collections::BTreeMap;

pub use filter::PerceptFilter;
pub use suggest::{closest, did_you_mean, unknown_action};

/// How a percept predicate is delivered (the BW4T3 interface's four kinds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum PerceptType {
    /// Only in the first batch of an entity.
    Once,
    /// In the first batch and again (all current instances) whenever the set of instances changes.
    OnChange,
    /// New instances when they start to hold, `not(p)` when `p` stops holding.
    OnChangeWithNegation,
    /// Every current instance in every batch.
    Always,
}

/// The declared delivery type of one percept predicate `name/arity`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PerceptDecl {
    pub name: String,
    pub arity: usize,
    pub kind: PerceptType,
}

impl PerceptDecl {
    /// A declaration of `name/arity` with the given type.
    pub fn new(name: &str, arity: usize, kind: PerceptType) -> PerceptDecl {
        PerceptDecl {
            name: name.to_string(),
            arity,
            kind,
        }
    }
}

/// An entity the environment offers to agents.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct EntityInfo {
    /// The entity's name, e.g. `Bot1`.
    pub name: String,
    /// The entity type used by launch rules, e.g. `bot`.
    pub kind: String,
}

/// The outcome of one action, as the agent sees it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub enum ActionResult {
    /// The action was accepted (movement actions then run over the following ticks).
    Ok,
    /// The action was refused; the message says why.
    Failed(String),
}

impl ActionResult {
    /// A failure with the given message.
    pub fn fail(msg: impl Into<String>) -> ActionResult {
        ActionResult::Failed(msg.into())
    }

    /// True when the action was accepted.
    pub fn is_ok(&self) -> bool {
        matches!(self, ActionResult::Ok)
    }
}

/// Initialisation parameters (key -> term), e.g. `map = banana`, `seed = 7`.
pub type InitParams = BTreeMap<String, Term>;

/// An environment that agents can act in and perceive, one tick at a time.
pub trait Environment: Send {
    /// The entities agents may control, in entity-id order.
    fn entities(&self) -> Vec<EntityInfo>;
    /// The percept predicates with their delivery types.
    fn declarations(&self) -> Vec<PerceptDecl>;
    /// Performs `action` for `entity` now (between ticks).
    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult;
    /// Advances the world by one tick.
    fn tick(&mut self);
    /// The number of ticks done so far.
    fn ticks(&self) -> u64;
    /// The next percept batch of `entity` (empty for unknown entities).
    fn percepts(&mut self, entity: &str) -> Vec<Term>;
    /// True when the environment's task is complete (the simulation may still run on).
    fn is_finished(&self) -> bool;
    /// Run statistics as JSON.
    fn stats(&self) -> serde_json::Value;
    /// The fixed layout a viewer draws (map), as JSON; `None`: nothing to draw.
    fn layout(&self) -> Option<serde_json::Value> {
        None
    }
    /// The moving parts a viewer draws now, as JSON objects keyed by name (so changes between
    /// ticks are small); `None`: nothing to draw. Called once per tick at most.
    fn scene(&mut self) -> Option<serde_json::Value> {
        None
    }
    /// Takes a request a person made for `entity` (e.g. a click in the browser view); the
    /// environment turns it into that entity's percepts. `Err` says why it was refused.
    fn input(&mut self, entity: &str, request: &Term) -> Result<(), String> {
        let _ = (entity, request);
        Err("this environment takes no requests from people".into())
    }
}

/// Environments that can be set up from init parameters (e.g. those of a `.mas2g` file).
pub trait FromInitParams: Sized {
    /// The parameter keys this environment understands.
    fn init_param_names() -> &'static [&'static str];
    /// Creates the environment; bad or unknown parameters are diagnostics.
    fn from_init_params(params: &InitParams) -> Result<Self, Vec<Diagnostic>>;
}
