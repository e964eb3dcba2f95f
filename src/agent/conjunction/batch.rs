//! A planned belief literal asked under each substitution of a condition level in turn: the
//! plan's fact bases and limits looked up once for the level, and each run's answers added to
//! one buffer the caller reuses (no answer list made and moved per substitution).

use super::*;

/// A plan ready to run under many substitutions in a row, over one mental state.
pub struct Batch<'a> {
    plan: &'a Plan,
    bases: [&'a FactBase; 6],
    /// The mailbox's messages waiting aside, read after its base (see [`MentalState::plan_bases`]).
    arrived: Arrived<'a>,
}

impl<'a> Batch<'a> {
    /// `plan` over the fact bases of `ms`; `None` when the engine's limits leave no room for
    /// plans (see [`Plan::answers`]).
    pub fn new(plan: &'a Plan, ms: &'a MentalState) -> Option<Batch<'a>> {
        ms.native_roomy().then(|| {
            let (bases, arrived) = ms.plan_bases();
            Batch {
                plan,
                bases,
                arrived,
            }
        })
    }

    /// [`Plan::answers`] under `theta` into `out` (emptied first): whether `cap` stopped
    /// them; `None`: ask the engine (what `out` holds then means nothing).
    pub fn answers_into(&self, theta: &Subst, cap: usize, out: &mut Answers) -> Option<bool> {
        out.clear();
        run::answers_into(self.plan, &self.bases, self.arrived, theta, cap, out)
    }
}
