//! What a run reports besides its trace, and how a test controller takes part in a run.

use super::input::Input;
use super::stats::{Deliveries, EndReason};
use crate::agent::{Agent, AgentConfig, Message, Program};
use crate::env::EntityInfo;
use crate::term::Term;
use std::sync::Arc;

/// Progress of a running system.
#[derive(Clone, Copy, Debug, Default)]
pub struct Progress {
    pub round: u64,
    pub tick: u64,
    pub deliveries: Deliveries,
    pub messages: u64,
}

/// Receives what a run produces besides the trace (all methods optional).
pub trait Observer {
    /// A line an agent printed with `print/1`.
    fn printed(&mut self, _agent: &str, _line: &str) {}
    /// A message sent in round `round` (`delivered` false when the receiver is unknown).
    fn message(&mut self, _round: u64, _m: &Message, _delivered: bool) {}
    /// A runtime warning.
    fn warning(&mut self, _text: &str) {}
    /// The environment refused an action.
    fn action_failed(&mut self, _agent: &str, _action: &Term, _reason: &str) {}
    /// True when the observer wants [`Observer::progress`] calls (they cost a status query).
    fn wants_progress(&self) -> bool {
        false
    }
    /// Progress, every few rounds.
    fn progress(&mut self, _p: &Progress) {}
    /// Round `round` is over and the environment is at `tick`: a watching observer may block
    /// here to pace, pause or single-step the run (the next round starts when it returns).
    fn pace(&mut self, _round: u64, _tick: u64) {}
    /// Every agent is created and the first round is about to start (benchmarks time the
    /// creation apart from the run).
    fn started(&mut self, _agents: usize, _workers: usize) {}
    /// The environment's entities, once before the first round (a view offers people the
    /// HumanBots among them).
    fn entities(&mut self, _entities: &[EntityInfo]) {}
    /// Requests people made for entities, taken in round `round` before the environment's
    /// tick (in this order); a rerun gives those its run recorded for that round.
    fn inputs(&mut self, _round: u64) -> Vec<Input> {
        Vec::new()
    }
    /// A request taken in round `round` at `tick`: applied (`Ok`) or refused (`Err`: why).
    fn input_applied(
        &mut self,
        _round: u64,
        _tick: u64,
        _input: &Input,
        _result: &Result<(), String>,
    ) {
    }

    // A test controller takes part in the run through the methods below (`goal test` runs
    // on this same round driver); plain observers keep the defaults.

    /// Agent `i` (`name`, running `program`): an observer may create it itself, e.g. a tested
    /// agent running an extended program under a controller; `None`: the usual agent.
    fn agent(
        &mut self,
        _i: usize,
        _name: &str,
        _program: &Arc<Program>,
        _config: &AgentConfig,
    ) -> Option<Agent> {
        None
    }
    /// The agents the observer steers (by index): they are stepped whenever
    /// [`Observer::busy`] says so, and shown to the observer before and after each step.
    fn steers(&self) -> Vec<usize> {
        Vec::new()
    }
    /// True when steered agent `i` must be stepped this round even without new input.
    fn busy(&self, _i: usize, _agent: &Agent) -> bool {
        false
    }
    /// Steered agent `i` is about to be stepped.
    fn before_step(&mut self, _i: usize, _agent: &Agent) {}
    /// Steered agent `i` was stepped.
    fn after_step(&mut self, _i: usize, _agent: &mut Agent) {}
    /// True when the observer has what it needs: the run ends ([`EndReason::Released`]).
    fn done(&self) -> bool {
        false
    }
    /// The run ended: a last look at steered agent `i`.
    fn ended(&mut self, _i: usize, _agent: &mut Agent, _end: EndReason) {}
}

/// An observer that ignores everything.
pub struct Quiet;
impl Observer for Quiet {}
