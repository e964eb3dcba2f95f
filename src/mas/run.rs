//! Running a system in lock-step rounds: the environment publishes one tick's percepts, every
//! agent with new input runs one cycle (in parallel on the worker pool), actions go to the
//! environment in agent-name order and messages are delivered for the next round in (sender,
//! sequence) order. The result depends only on the programs, the map and the seed.

mod end;
mod input;
mod start;

use super::environment::{env_params, percept_types};
use super::launch::{agent_seed, Launch, Launcher};
use super::routing::Router;
use super::scheduler::{Job, Pool};
use super::stats::{AgentStats, Deliveries, EndReason, RunSummary};
use super::system::{MasSystem, Problem};
use super::trace::{AgentInfo, TraceWriter};
// The run's options and observer are part of its interface.
pub use super::observer::{Observer, Progress, Quiet};
pub use super::options::{RunOptions, DEFAULT_MAX_MAILBOX, DEFAULT_MAX_MEMORY, TICK_SECONDS};
use crate::agent::mailbox::reusable;
use crate::agent::{
    Agent, AgentConfig, CycleOutput, Directory, Event, Message, RuntimeError, StopReason,
    TraceLevel,
};
use crate::diag::Diagnostic;
use crate::env::thread::{EnvHandle, Mode};
use crate::env::ActionResult;
use crate::kr::Limits;
use crate::term::Term;
use std::collections::BTreeMap;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Most emptied outgoing-message buffers the run loop keeps for inboxes.
const SPARE_BUFFERS: usize = 64;

/// How often the resident memory is checked against the cap.
const MEMORY_CHECK_EVERY: Duration = Duration::from_millis(20);

/// Runs `system` to its end; the trace (if any) is written as the run goes.
pub fn run(
    system: &MasSystem,
    opts: &RunOptions,
    trace: Option<TraceWriter>,
    obs: &mut dyn Observer,
) -> Result<(RunSummary, Option<String>), Vec<Problem>> {
    // Without a trace nobody reads the events: the agents then skip building them.
    let level = match (&trace, opts.trace_rules) {
        (None, _) => TraceLevel::Off,
        (Some(_), true) => TraceLevel::Rules,
        (Some(_), false) => TraceLevel::Changes,
    };
    let mut setup = Setup::new(system, opts, level, obs)?;
    let summary = setup.run_loop(trace, obs);
    Ok(summary)
}

struct Slot {
    name: String,
    reference: String,
    entity: Option<String>,
    stats: AgentStats,
    /// The agent's last cycle left it waiting for new input (see `CycleOutput::waiting`).
    waiting: bool,
    percepts: Vec<Term>,
    inbox: Vec<Message>,
    /// In the ready queue (something new for the next round).
    queued: bool,
    /// Rounds before this one are accounted in `stats.idle_ticks`.
    counted: u64,
}

/// Accounts, traces and reports one cycle of the agent in slot `s` (its warnings and prints).
fn report_cycle(
    s: &mut Slot,
    out: &CycleOutput,
    (round, tick): (u64, u64),
    trace: Option<&mut TraceWriter>,
    obs: &mut dyn Observer,
) {
    s.stats.cycles += 1;
    s.stats.actions += out.actions;
    if let Some(t) = trace {
        t.cycle(round, tick, &s.name, &out.events);
    }
    for e in &out.events {
        if let Event::Warning { message } = e {
            obs.warning(&format!("{}: {message}", s.name));
        }
    }
    for line in &out.printed {
        obs.printed(&s.name, line);
    }
}

/// Queues slot `i` for the next round (once).
fn mark(queue: &mut Vec<usize>, slot: &mut Slot, i: usize) {
    if !slot.queued {
        slot.queued = true;
        queue.push(i);
    }
}

/// A round's environment actions (entity, action) in agent-name order, with the agent that
/// performed each one and where in its program.
struct Acted<'r> {
    actions: &'r [(String, Term)],
    actors: &'r [usize],
    sites: &'r mut [RuntimeError],
}

struct Setup<'a> {
    system: &'a MasSystem,
    opts: &'a RunOptions,
    seed: u64,
    map: Option<String>,
    env: Option<EnvHandle>,
    pool: Pool,
    slots: Vec<Slot>,
    router: Router,
    /// The communication layer (CLAMR transport and sessions); `None` on the default path.
    comm: Option<crate::clamr::Comm>,
    by_entity: BTreeMap<String, Vec<usize>>,
    initial: Vec<(String, Vec<Term>)>,
    /// Slots with something new (acted, percepts or messages): with idle skipping only these
    /// are looked at, so a round costs time in the number of busy agents, not all agents.
    ready: Vec<usize>,
}

impl<'a> Setup<'a> {
    fn deliver_percepts(&mut self, batches: Vec<(String, Vec<Term>)>) {
        for (entity, batch) in batches {
            if let Some(ids) = self.by_entity.get(&entity) {
                for &i in ids {
                    let s = &mut self.slots[i];
                    if !s.stats.stopped && !batch.is_empty() {
                        s.percepts.extend(batch.iter().cloned());
                        mark(&mut self.ready, s, i);
                    }
                }
            }
        }
    }

    fn env_status(&self) -> (Deliveries, Option<serde_json::Value>) {
        let Some(h) = &self.env else {
            return (Deliveries::default(), None);
        };
        match h.status() {
            Ok(s) => {
                let get = |k: &str| s.stats.get(k).and_then(|v| v.as_u64()).unwrap_or(0);
                let d = Deliveries {
                    right: get("deliveries_right"),
                    wrong: get("deliveries_wrong"),
                };
                (d, Some(s.stats))
            }
            Err(_) => (Deliveries::default(), None),
        }
    }

    fn run_loop(
        &mut self,
        mut trace: Option<TraceWriter>,
        obs: &mut dyn Observer,
    ) -> (RunSummary, Option<String>) {
        let infos = self.agent_infos();
        if let Some(t) = trace.as_mut() {
            t.header(
                &self.system.file,
                self.system.env.as_ref().map(|e| e.kind.name()),
                self.seed,
                self.map.as_deref(),
                &infos,
                self.opts.replay_json(),
            );
        }
        if let Some(t) = trace.as_mut() {
            self.draw(t, 0, 0, true);
        }
        let initial = std::mem::take(&mut self.initial);
        self.deliver_percepts(initial);
        obs.started(self.slots.len(), self.pool.workers());
        let start = Instant::now();
        let mut round: u64 = 0;
        let mut tick: u64 = 0;
        let mut messages: u64 = 0;
        let mut last_progress = Instant::now();
        let mut iters: u64 = 0;
        let mut alive = self.slots.iter().filter(|s| !s.stats.stopped).count();
        let mut memory_checked = start;
        let steered = obs.steers();
        let mut env_finished = false;
        let mut spare: Vec<usize> = Vec::new();
        // The round's jobs, outputs and messages; the buffers are kept from round to round.
        let mut jobs: Vec<Job> = Vec::new();
        let mut outputs: Vec<(usize, CycleOutput)> = Vec::new();
        let mut sent: Vec<Message> = Vec::new();
        // The agents' emptied outgoing-message buffers, given to inboxes that have none: a
        // message passed on then allocates no inbox.
        let mut buffers: Vec<Vec<Message>> = Vec::new();
        let end = loop {
            if let Some(reason) = self.interrupted_or_over(start, &mut memory_checked, obs) {
                break reason;
            }
            if obs.done() {
                break EndReason::Released;
            }
            let forced = self.busy_steered(&steered, obs);
            let k = iters;
            iters += 1;
            // The queue's buffer is handed back and forth between rounds: a round allocates
            // nothing for it.
            let mut candidates = std::mem::replace(&mut self.ready, std::mem::take(&mut spare));
            if self.opts.skip_idle {
                candidates.sort_unstable();
            } else {
                candidates.clear();
                candidates.extend(0..self.slots.len());
            }
            // Cycles that can do something (new input, or the agent is not waiting).
            let mut due = 0usize;
            for &i in &candidates {
                let s = &mut self.slots[i];
                s.queued = false;
                if s.stats.stopped {
                    s.percepts.clear();
                    s.inbox.clear();
                    continue;
                }
                // Rounds since the slot was last looked at had nothing new for it.
                s.stats.idle_ticks += k - s.counted;
                s.counted = k + 1;
                let new = !s.waiting
                    || !s.percepts.is_empty()
                    || !s.inbox.is_empty()
                    || forced.contains(&i);
                due += usize::from(new);
                // Without skipping, a waiting agent is stepped too: its step is a no-op by
                // construction (`Agent::step`), so the trace is the same either way.
                if new || !self.opts.skip_idle {
                    jobs.push((
                        i,
                        std::mem::take(&mut s.percepts),
                        std::mem::take(&mut s.inbox),
                    ));
                } else {
                    s.stats.idle_ticks += 1;
                }
            }
            candidates.clear();
            spare = candidates;
            if due == 0 && self.env.is_none() && !self.comm.as_ref().is_some_and(|c| c.busy()) {
                break if alive == 0 {
                    EndReason::AllStopped
                } else {
                    EndReason::Idle
                };
            }
            let stepped: Vec<usize> = steered
                .iter()
                .copied()
                .filter(|i| jobs.iter().any(|j| j.0 == *i))
                .collect();
            for &i in &stepped {
                self.pool.with_agent(i, |a| obs.before_step(i, a));
            }
            let clock = Some(tick as f64 * TICK_SECONDS);
            if let Err(e) = self.pool.round_into(&mut jobs, clock, &mut outputs) {
                obs.warning(&e.0);
                break EndReason::Failure;
            }
            let mut actions: Vec<(String, Term)> = Vec::new();
            let mut actors: Vec<usize> = Vec::new();
            let mut sites: Vec<RuntimeError> = Vec::new();
            for (i, out) in outputs.drain(..) {
                let s = &mut self.slots[i];
                let was_stopped = s.stats.stopped;
                s.waiting = out.waiting;
                if out.skipped {
                    // A waiting agent stepped without new input ran no cycle.
                    s.stats.idle_ticks += 1;
                    continue;
                }
                report_cycle(s, &out, (round, tick), trace.as_mut(), obs);
                let mut at = out.env_sites.into_iter();
                for a in out.env_actions {
                    match &s.entity {
                        Some(e) => {
                            s.stats.env_actions += 1;
                            actions.push((e.clone(), a));
                            actors.push(i);
                            sites.push(at.next().unwrap_or_default());
                        }
                        None => {
                            // GOAL: an `@env` action of an agent not connected to an
                            // environment is fatal (in `goal test` as in `goal run`).
                            let msg =
                                format!("environment action {a} by an agent without an entity");
                            if let Some(t) = trace.as_mut() {
                                t.warning(round, tick, &s.name, &msg);
                            }
                            let mut e = at.next().unwrap_or_default();
                            e.message = msg;
                            obs.warning(&format!("agent {} stopped: {e}", s.name));
                            s.stats.stopped = true;
                            s.stats.error = Some(e.to_string());
                            self.pool.halt(i, e);
                            break;
                        }
                    }
                }
                s.stats.messages_sent += out.messages.len() as u64;
                let mut outgoing = out.messages;
                sent.append(&mut outgoing);
                if reusable(&outgoing) && buffers.len() < SPARE_BUFFERS {
                    buffers.push(outgoing);
                }
                match out.stopped {
                    Some(StopReason::Error(e)) => {
                        s.stats.stopped = true;
                        s.stats.error = Some(e.to_string());
                        obs.warning(&format!("agent {} stopped: {e}", s.name));
                    }
                    Some(StopReason::MainExited) => s.stats.stopped = true,
                    None => {}
                }
                if s.stats.stopped && !was_stopped {
                    alive -= 1;
                } else if !s.waiting && !s.stats.stopped {
                    mark(&mut self.ready, s, i);
                }
            }
            for &i in &stepped {
                let waiting = self.pool.with_agent(i, |a| {
                    obs.after_step(i, a);
                    a.waiting()
                });
                let s = &mut self.slots[i];
                s.waiting = waiting.unwrap_or(true);
                if !s.waiting && !s.stats.stopped {
                    mark(&mut self.ready, s, i);
                }
            }
            // Messages are in (sender, sequence) order already: outputs come in slot order,
            // slots are in name order (`start.rs`), and each agent sends in sequence.
            debug_assert!(sent
                .windows(2)
                .all(|w| w[0].sender.name() <= w[1].sender.name()));
            messages += sent.len() as u64;
            if let Some(c) = self.comm.as_mut() {
                let mut warn = |w: &str| obs.warning(w);
                let all = std::mem::take(&mut sent);
                let (arrived, lost) = c.carry((round, tick), all, trace.as_mut(), &mut warn);
                for m in &lost {
                    if let Some(t) = trace.as_mut() {
                        t.message(round, tick, m, false);
                    }
                    obs.message(round, m, false);
                }
                sent = arrived;
            }
            for m in sent.drain(..) {
                let receiver = self.router.index(m.receiver);
                let full = receiver.is_some_and(|j| self.mailbox_full(j, round, tick, obs));
                let delivered = receiver.is_some() && !full;
                if let Some(t) = trace.as_mut() {
                    t.message(round, tick, &m, delivered);
                }
                obs.message(round, &m, delivered);
                match receiver {
                    Some(j) if !full => {
                        let s = &mut self.slots[j];
                        if !s.stats.stopped {
                            if s.inbox.capacity() == 0 {
                                s.inbox = buffers.pop().unwrap_or_default();
                            }
                            s.inbox.push(m);
                            mark(&mut self.ready, s, j);
                        }
                    }
                    Some(_) => {}
                    None => obs.warning(&format!(
                        "message {} from {} to unknown agent {} dropped",
                        m.content, m.sender, m.receiver
                    )),
                }
            }
            let mut finished = false;
            if !env_finished {
                self.take_inputs((round, tick), trace.as_mut(), obs);
            }
            match &self.env {
                // A finished environment stays as it is while a controller goes on.
                Some(_) if env_finished => tick += 1,
                Some(h) => match h.round(actions.clone()) {
                    Ok(reply) => {
                        let acted = Acted {
                            actions: &actions,
                            actors: &actors,
                            sites: &mut sites,
                        };
                        let when = (round, tick);
                        alive -= self.results(acted, &reply.results, when, trace.as_mut(), obs);
                        tick = reply.tick;
                        finished = reply.finished;
                        if let Some(t) = trace.as_mut() {
                            self.draw(t, round + 1, tick, false);
                        }
                        self.deliver_percepts(reply.percepts);
                    }
                    Err(e) => {
                        obs.warning(&format!("environment: {e}"));
                        break EndReason::Failure;
                    }
                },
                None => tick += 1,
            }
            round += 1;
            if obs.wants_progress() && last_progress.elapsed() >= Duration::from_millis(100) {
                last_progress = Instant::now();
                let (deliveries, _) = self.env_status();
                obs.progress(&Progress {
                    round,
                    tick,
                    deliveries,
                    messages,
                });
            }
            if finished && steered.is_empty() {
                break EndReason::Completed;
            }
            env_finished |= finished;
            if alive == 0 {
                break EndReason::AllStopped;
            }
            if tick >= self.opts.max_ticks {
                break match self.env {
                    Some(_) => EndReason::TickLimit,
                    None => EndReason::CycleLimit,
                };
            }
            obs.pace(round, tick);
            if let Some(tps) = self.opts.realtime.filter(|t| *t > 0.0 && t.is_finite()) {
                let due = Duration::try_from_secs_f64(round as f64 / tps)
                    .ok()
                    .and_then(|d| start.checked_add(d));
                let now = Instant::now();
                if let Some(due) = due.filter(|d| *d > now) {
                    std::thread::sleep(due - now);
                }
            }
        };
        for s in self.slots.iter_mut().filter(|s| !s.stats.stopped) {
            s.stats.idle_ticks += round.saturating_sub(s.counted);
        }
        if !matches!(
            end,
            EndReason::MemoryLimit | EndReason::Failure | EndReason::Released
        ) {
            self.end_of_run((round, tick), trace.as_mut(), obs);
        }
        for &i in &steered {
            self.pool.with_agent(i, |a| obs.ended(i, a, end));
        }
        let (deliveries, env_stats) = self.env_status();
        let (sessions, comm) = match self.comm.as_mut() {
            Some(c) => {
                let mut warn = |w: &str| obs.warning(w);
                let (s, t) = c.finish((round, tick), trace.as_mut(), &mut warn);
                (Some(s), Some(t))
            }
            None => (None, None),
        };
        let summary = RunSummary {
            completed: end == EndReason::Completed,
            end,
            ticks: tick,
            rounds: round,
            deliveries,
            messages,
            seed: self.seed,
            map: self.map.clone(),
            agents: self
                .slots
                .iter()
                .map(|s| (s.name.clone(), s.stats.clone()))
                .collect(),
            env: env_stats,
            sessions,
            comm,
        };
        let err = match trace {
            Some(mut t) => {
                t.end(summary.trace_json());
                t.finish().err()
            }
            None => None,
        };
        (summary, err)
    }

    /// The steered agents that must be stepped this round (queued for it).
    fn busy_steered(&mut self, steered: &[usize], obs: &mut dyn Observer) -> Vec<usize> {
        let mut busy = Vec::new();
        for &i in steered {
            if self.slots[i].stats.stopped {
                continue;
            }
            if self.pool.with_agent(i, |a| obs.busy(i, a)) == Some(true) {
                busy.push(i);
                mark(&mut self.ready, &mut self.slots[i], i);
            }
        }
        busy
    }

    /// True when agent `j` has as many messages waiting as its mailbox may hold: the message
    /// is dropped, counted, and reported the first time.
    fn mailbox_full(&mut self, j: usize, round: u64, tick: u64, obs: &mut dyn Observer) -> bool {
        let max = self.opts.max_mailbox;
        let s = &mut self.slots[j];
        if s.inbox.len() < max {
            return false;
        }
        if s.stats.messages_dropped == 0 {
            obs.warning(&format!(
                "{}: mailbox full ({max} messages waiting, --max-mailbox); further messages to it \
                 are dropped (round {round}, tick {tick})",
                s.name
            ));
        }
        s.stats.messages_dropped += 1;
        true
    }

    /// Writes what a viewer draws of the environment to the trace: its layout (`first`) and
    /// the changes of its scene at the start of `tick`. Nothing without an environment or when
    /// it has nothing to draw.
    fn draw(&self, trace: &mut TraceWriter, round: u64, tick: u64, first: bool) {
        let Some(h) = &self.env else { return };
        if first {
            if let Ok(Some(layout)) = h.layout() {
                trace.map(layout);
            }
        }
        if let Ok(Some(scene)) = h.scene() {
            trace.world(round, tick, &scene);
        }
    }
}
