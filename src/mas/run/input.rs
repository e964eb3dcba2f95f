//! Taking people's requests into a run: between the agents' actions and the environment's
//! tick of a round, the observer's requests go to the environment (`Environment::input`) in
//! the order given, each written to the trace with its result, so a rerun that gives the same
//! requests at the same rounds reproduces the run.

use super::*;
use crate::mas::input::Input;

impl Setup<'_> {
    /// Hands the observer's requests for round `round` to the environment.
    pub(super) fn take_inputs(
        &mut self,
        (round, tick): (u64, u64),
        mut trace: Option<&mut TraceWriter>,
        obs: &mut dyn Observer,
    ) {
        let Some(h) = &self.env else { return };
        let inputs: Vec<Input> = obs.inputs(round);
        for input in inputs {
            let result = h
                .input(&input.entity, &input.request)
                .unwrap_or_else(|e| Err(e.to_string()));
            if let Some(t) = trace.as_deref_mut() {
                t.input(round, tick, &input, &result);
            }
            obs.input_applied(round, tick, &input, &result);
        }
    }
}
