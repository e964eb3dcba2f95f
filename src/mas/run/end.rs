//! Ending a run and its rounds: the results of environment actions, halting stopped
//! agents, the end conditions, and the shutdown pass of agents still running at the end.

use super::*;

impl<'a> Setup<'a> {
    /// Runs the shutdown module of each agent still running as the run ends, in agent-name
    /// order, traced like a cycle; its environment actions and messages are not carried out
    /// (the run's last round is over), each is traced as a warning instead.
    pub(super) fn end_of_run(
        &mut self,
        when: (u64, u64),
        mut trace: Option<&mut TraceWriter>,
        obs: &mut dyn Observer,
    ) {
        let (round, tick) = when;
        let mut order: Vec<usize> = (0..self.slots.len())
            .filter(|&i| !self.slots[i].stats.stopped)
            .collect();
        order.sort_by(|&a, &b| self.slots[a].name.cmp(&self.slots[b].name));
        for i in order {
            let Some(Some(out)) = self.pool.with_agent(i, |a| a.end_of_run()) else {
                continue;
            };
            let s = &mut self.slots[i];
            report_cycle(s, &out, when, trace.as_deref_mut(), obs);
            let dropped = out
                .env_actions
                .iter()
                .map(|a| format!("environment action {a}"));
            let unsent = out
                .messages
                .iter()
                .map(|m| format!("message {} to {}", m.content, m.receiver));
            for what in dropped.chain(unsent) {
                let msg =
                    format!("{what} of the shutdown module not carried out: the run has ended");
                if let Some(t) = trace.as_deref_mut() {
                    t.warning(round, tick, &s.name, &msg);
                }
                obs.warning(&format!("{}: {msg}", s.name));
            }
            if let Some(StopReason::Error(e)) = out.stopped {
                s.stats.stopped = true;
                s.stats.error = Some(e.to_string());
                obs.warning(&format!("agent {} stopped: {e}", s.name));
            }
        }
    }

    /// Traces the results of a round's environment actions and stops each agent whose
    /// action was refused (GOAL treats that as fatal); returns how many agents stopped.
    pub(super) fn results(
        &mut self,
        acted: Acted<'_>,
        results: &[(String, ActionResult)],
        (round, tick): (u64, u64),
        mut trace: Option<&mut TraceWriter>,
        obs: &mut dyn Observer,
    ) -> usize {
        let mut stopped = 0;
        for (k, ((entity, result), (_, a))) in results.iter().zip(acted.actions).enumerate() {
            let i = acted.actors[k];
            if let Some(t) = trace.as_deref_mut() {
                t.action(
                    round,
                    tick,
                    &self.slots[i].name,
                    entity,
                    &a.to_string(),
                    result,
                );
            }
            if let ActionResult::Failed(m) = result {
                obs.action_failed(&self.slots[i].name, a, m);
                let mut e = std::mem::take(&mut acted.sites[k]);
                e.message = format!("environment action {a} failed: {m}");
                if self.halt(i, e, round, tick, trace.as_deref_mut(), obs) {
                    stopped += 1;
                }
            }
        }
        stopped
    }

    /// Stops agent `i` on runtime error `e` from outside its cycle (the agent, its slot, the
    /// trace and the observer all learn it); true when it was running.
    pub(super) fn halt(
        &mut self,
        i: usize,
        e: RuntimeError,
        round: u64,
        tick: u64,
        trace: Option<&mut TraceWriter>,
        obs: &mut dyn Observer,
    ) -> bool {
        let s = &mut self.slots[i];
        if s.stats.stopped {
            return false;
        }
        let text = e.to_string();
        if let Some(t) = trace {
            t.warning(
                round,
                tick,
                &s.name,
                &format!("stopped: runtime error: {text}"),
            );
        }
        obs.warning(&format!("agent {} stopped: {text}", s.name));
        s.stats.stopped = true;
        s.stats.error = Some(text);
        self.pool.halt(i, e);
        true
    }

    /// Why the run must stop before the next round, if it must: a signal, the wall-time
    /// limit, or the memory cap (checked every [`MEMORY_CHECK_EVERY`]).
    pub(super) fn interrupted_or_over(
        &self,
        start: Instant,
        memory_checked: &mut Instant,
        obs: &mut dyn Observer,
    ) -> Option<EndReason> {
        if self
            .opts
            .interrupt
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed) != 0)
        {
            return Some(EndReason::Interrupted);
        }
        if self.opts.time_limit.is_some_and(|l| start.elapsed() >= l) {
            return Some(EndReason::TimeLimit);
        }
        let cap = self.opts.max_memory?;
        if memory_checked.elapsed() < MEMORY_CHECK_EVERY {
            return None;
        }
        *memory_checked = Instant::now();
        let used = crate::mas::memory::resident_bytes()?;
        if used <= cap {
            return None;
        }
        obs.warning(&format!(
            "the run uses {} MiB of memory, more than its cap of {} MiB (--max-memory); stopping",
            used >> 20,
            cap >> 20
        ));
        Some(EndReason::MemoryLimit)
    }
}
