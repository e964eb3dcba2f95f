//! The agent and its reasoning cycle: `Agent::step(percepts, messages)` runs one cycle
//! (percepts, messages, init on the first cycle, event when something is new, then main until
//! it performs a real action) and returns what the agent did. No I/O, no threads.

use super::directory::Directory;
use super::error::{Fault, RuntimeError};
use super::kr_bridge::{AgentEngine, KrKind, Limits};
use super::mailbox::{reusable, Message};
use super::mental_state::MentalState;
use super::module::{Frame, ModFrame, RunEnd};
use super::percepts::PerceptTypes;
use super::program::Program;
use super::timing::Timing;
use super::trace::{Event, TraceLevel};
use super::watch::{Observed, Watcher};
use crate::term::{Sym, Term};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeSet;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Why an agent stopped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The main module exited.
    MainExited,
    /// A fatal runtime error.
    Error(RuntimeError),
}

/// What one cycle produced.
#[derive(Clone, Debug, Default)]
pub struct CycleOutput {
    /// Environment actions (ground terms), in the order performed.
    pub env_actions: Vec<Term>,
    /// Outgoing messages, one per receiver, in the order sent.
    pub messages: Vec<Message>,
    /// The trace of the cycle.
    pub events: Vec<Event>,
    /// Lines written by `print/1`.
    pub printed: Vec<String>,
    /// Set when the agent stopped (in this or an earlier cycle).
    pub stopped: Option<StopReason>,
    /// Real actions performed (counted at every trace level).
    pub actions: u64,
    /// Where each environment action was performed (file, line, rule; the message is empty):
    /// the location of the error when the environment refuses the action.
    pub env_sites: Vec<RuntimeError>,
    /// The agent can do nothing more until new input (percepts or messages) arrives: another
    /// cycle without input would provably repeat the same nothing. Such a cycle is not run
    /// (see [`CycleOutput::skipped`]), so stepping a waiting agent or not is the same.
    pub waiting: bool,
    /// The step ran no cycle: the agent was waiting and got nothing new.
    pub skipped: bool,
}

impl CycleOutput {
    /// True when nothing was recorded: the output equals [`CycleOutput::default`].
    fn is_clear(&self) -> bool {
        // Destructured, so that a field added later must be added here too.
        let CycleOutput {
            env_actions,
            messages,
            events,
            printed,
            stopped,
            actions,
            env_sites,
            waiting,
            skipped,
        } = self;
        env_actions.is_empty()
            && messages.is_empty()
            && events.is_empty()
            && printed.is_empty()
            && stopped.is_none()
            && *actions == 0
            && env_sites.is_empty()
            && !waiting
            && !skipped
    }
}

/// How to create an agent.
#[derive(Clone, Debug)]
pub struct AgentConfig {
    /// Seed of the agent's random generator.
    pub seed: u64,
    /// Names of every agent in the system (the agent's own name may be included); ignored
    /// when `directory` is given.
    pub agents: Vec<String>,
    /// The system's agents, shared by all of them (must include this agent); saves building
    /// the list once per agent in large systems.
    pub directory: Option<Arc<Directory>>,
    /// Percept types declared by the environment.
    pub percept_types: Arc<PerceptTypes>,
    /// Limits of each KR query.
    pub limits: Limits,
    /// Maximum interpreter steps per cycle.
    pub max_steps: u64,
    /// How much to trace.
    pub trace: TraceLevel,
    /// Wall time one cycle may take; a longer cycle is cut with a runtime error (`None`: no
    /// limit; runs use [`DEFAULT_CYCLE_TIME`]).
    pub cycle_time: Option<Duration>,
    /// Most facts the belief base may hold; an update going beyond is a runtime error.
    pub max_beliefs: usize,
    /// Most messages one cycle may send; sending more is a runtime error.
    pub max_sent: usize,
    /// The KR engine answering the agent's queries.
    pub kr: KrKind,
}

/// Default of [`AgentConfig::cycle_time`].
pub const DEFAULT_CYCLE_TIME: Duration = Duration::from_secs(10);
/// Default of [`AgentConfig::max_beliefs`].
pub const DEFAULT_MAX_BELIEFS: usize = 1_000_000;

impl Default for AgentConfig {
    fn default() -> Self {
        AgentConfig {
            seed: 0,
            agents: Vec::new(),
            directory: None,
            percept_types: Arc::new(PerceptTypes::default()),
            limits: Limits::default(),
            max_steps: 1_000_000,
            trace: TraceLevel::Rules,
            cycle_time: None,
            max_beliefs: DEFAULT_MAX_BELIEFS,
            max_sent: usize::MAX,
            kr: KrKind::Native,
        }
    }
}

/// The mutable core of an agent that actions work on.
pub struct Core {
    pub name: String,
    /// The agent's name interned (messages carry it).
    pub me: Sym,
    pub ms: MentalState,
    pub rng: ChaCha8Rng,
    pub out: CycleOutput,
    /// Known agents (sorted, including self).
    pub known: Arc<Directory>,
    pub level: TraceLevel,
    pub max_steps: u64,
    /// Wall time one cycle may take, and when the running cycle must end.
    pub cycle_time: Option<Duration>,
    pub deadline: Option<Instant>,
    /// When the whole run must end (`--time-limit`, a test's `timeout`): no cycle or query
    /// runs past it.
    pub run_end: Option<Instant>,
    /// Most facts the belief base may hold, and most messages one cycle may send.
    pub max_beliefs: usize,
    pub max_sent: usize,
    /// Output of Prolog write/format built-ins.
    pub kr_out: String,
    /// A test controller's observer of module entry/exit and actions.
    pub watcher: Option<Box<dyn Watcher>>,
    /// Set when the cycle changed the state or drew on chance without performing a real
    /// action (e.g. a module entered with `focus=select`): the agent is then not waiting.
    pub unsettled: bool,
    /// Rules (`file:line label`) already warned about for a truncated `if` condition.
    pub truncated_rules: BTreeSet<String>,
    /// Sleep, timers and channel subscriptions (modular GOAL).
    pub timing: Timing,
    /// The run's simulated time in seconds (`None`: wall-clock time), whatever the KR engine.
    pub clock: Option<f64>,
    /// Records what the rules do, for `goal why` (`None` in ordinary runs).
    pub why: Option<super::why::Recorder>,
}

impl Core {
    /// Records an event if the trace level asks for it.
    pub fn event(&mut self, e: Event) {
        let need = match e {
            Event::Warning { .. } | Event::Error { .. } | Event::Stopped { .. } => TraceLevel::Off,
            Event::RuleEvaluated { .. } | Event::RuleFired { .. } => TraceLevel::Rules,
            _ => TraceLevel::Changes,
        };
        if matches!(e, Event::ActionPerformed { .. }) {
            self.out.actions += 1;
        }
        if self.level >= need {
            self.out.events.push(e);
        }
    }

    /// Checks the cycle's time quota: an error when the cycle ran too long.
    pub fn check_deadline(&self) -> Result<(), Fault> {
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            if self.run_end.is_some_and(|e| Instant::now() >= e) {
                return Err(Fault::new(
                    "the run's time limit was reached during this cycle",
                ));
            }
            let t = self.cycle_time.unwrap_or_default();
            return Err(Fault::new(format!(
                "the cycle took longer than its time quota of {} (--cycle-time)",
                show_duration(t)
            )));
        }
        Ok(())
    }

    /// Checks the size quotas: an error when the belief base holds too many facts or the
    /// cycle sent too many messages.
    pub fn check_sizes(&self) -> Result<(), Fault> {
        if self.out.messages.len() > self.max_sent {
            return Err(Fault::new(format!(
                "the cycle sent more than {} messages, the quota (--max-sent)",
                self.max_sent
            )));
        }
        if self.ms.beliefs.len() > self.max_beliefs {
            return Err(Fault::new(format!(
                "the belief base holds more than {} facts, the quota (--max-beliefs)",
                self.max_beliefs
            )));
        }
        Ok(())
    }

    /// Applies a percept batch to the percept base and records what changed.
    #[inline]
    pub fn perceive(&mut self, percepts: &[Term], types: &PerceptTypes, keep_batch: bool) {
        let p = &self.ms.percepts;
        if percepts.is_empty() && p.facts().is_empty() && p.batch().is_empty() {
            // Nothing to replace or remove: most cycles of agents without an environment.
            return;
        }
        self.perceive_batch(percepts, types, keep_batch);
    }

    /// [`Core::perceive`] when there is something to replace or remove.
    fn perceive_batch(&mut self, percepts: &[Term], types: &PerceptTypes, keep_batch: bool) {
        let record = self.level >= TraceLevel::Changes;
        let ch = self.ms.percepts.apply(percepts, types, keep_batch, record);
        for p in ch.removed.iter() {
            self.event(Event::PerceptRemoved {
                percept: p.to_string(),
            });
        }
        for p in ch.added.iter() {
            self.event(Event::PerceptAdded {
                percept: p.to_string(),
            });
        }
    }

    /// Records several events.
    #[inline]
    pub fn changes(&mut self, events: Vec<Event>) {
        // Most updates report nothing when the trace is off: no loop, no drop to call.
        if events.is_empty() {
            return;
        }
        for e in events {
            self.event(e);
        }
    }

    /// Shows an observable event to the watcher, if one is installed.
    pub fn watch(&mut self, at: Observed<'_>) {
        if let Some(w) = self.watcher.as_mut() {
            w.observe(&self.ms, at);
        }
    }
}

/// A GOAL agent: its program (shared), mental state, random generator and execution state.
pub struct Agent {
    program: Arc<Program>,
    core: Core,
    types: Arc<PerceptTypes>,
    cycle: u64,
    main: Vec<Frame>,
    main_entered: bool,
    acted_last: bool,
    /// The last cycle left the agent waiting for new input.
    waiting: bool,
    /// [`Agent::chance`] when main started in the current cycle.
    chance_before_main: u128,
    stopped: Option<StopReason>,
    /// Run by a test controller: `main` holds the current task instead of the main module.
    controlled: bool,
}

impl Agent {
    /// Creates agent `name` running `program`.
    pub fn new(program: Arc<Program>, name: &str, config: AgentConfig) -> Agent {
        let known = match config.directory {
            Some(d) if d.contains(name) => d,
            _ => {
                let mut names = config
                    .directory
                    .as_ref()
                    .map_or_else(|| config.agents.clone(), |d| d.names().to_vec());
                names.push(name.to_string());
                Directory::new(&names)
            }
        };
        let ms = MentalState::new(
            program.knowledge.clone(),
            &Term::atom(name),
            known.clone(),
            config.limits,
            config.seed ^ 0x9e37_79b9_7f4a_7c15,
        );
        let mut ms = ms;
        let engine = AgentEngine::new(
            config.kr,
            &program.knowledge,
            config.seed ^ 0x9e37_79b9_7f4a_7c15,
            config.limits,
        );
        let refused = engine.as_ref().err().cloned();
        if let Ok(e) = engine {
            ms.engine = std::cell::RefCell::new(e);
        }
        ms.record = config.trace >= TraceLevel::Changes;
        ms.models.enabled = program.uses_models;
        ms.mailbox.sessions = program
            .uses_sessions
            .then(crate::clamr::session::Book::default);
        let file = program.file.clone();
        let mut agent = Agent {
            program,
            core: Core {
                name: name.to_string(),
                me: Sym::intern(name),
                ms,
                rng: ChaCha8Rng::seed_from_u64(config.seed),
                out: CycleOutput::default(),
                known,
                level: config.trace,
                max_steps: config.max_steps,
                cycle_time: config.cycle_time,
                deadline: None,
                run_end: config.limits.deadline,
                max_beliefs: config.max_beliefs,
                max_sent: config.max_sent,
                kr_out: String::new(),
                watcher: None,
                unsettled: false,
                truncated_rules: BTreeSet::new(),
                timing: Timing::default(),
                clock: None,
                why: None,
            },
            types: config.percept_types,
            cycle: 0,
            main: Vec::new(),
            main_entered: false,
            acted_last: false,
            waiting: false,
            chance_before_main: 0,
            stopped: None,
            controlled: false,
        };
        if let Some(why) = refused {
            agent.halt(RuntimeError {
                file,
                line: 0,
                rule: None,
                message: why,
                binding: None,
            });
        }
        agent
    }

    /// The agent's name.
    pub fn name(&self) -> &str {
        &self.core.name
    }

    /// The mental state (read-only).
    pub fn mental_state(&self) -> &MentalState {
        &self.core.ms
    }

    /// Number of cycles run.
    pub fn cycles(&self) -> u64 {
        self.cycle
    }

    /// Why the agent stopped, if it did.
    pub fn stopped(&self) -> Option<&StopReason> {
        self.stopped.as_ref()
    }

    /// Hands the agent to a test controller: the main module is no longer entered by itself;
    /// cycles run the task given with [`Agent::start_task`] (init and event run as usual).
    pub fn control(&mut self) {
        self.controlled = true;
    }

    /// Starts running rule block `block` of the program (a test's `do` section compiled with
    /// `Program::extend`) from the next cycle on, with the usual cycle boundaries; any
    /// unfinished task is abandoned first.
    pub fn start_task(&mut self, block: usize) {
        self.abort_task();
        let n = self.program.blocks.get(block).map_or(0, |b| b.rules.len());
        self.main.push(Frame::Module(ModFrame {
            module: None,
            block,
            subst: crate::term::Subst::new(),
            order: (0..n as u32).collect(),
            next: 0,
            pass_acted: false,
            acted: false,
            pushed_focus: false,
            exiting: false,
        }));
        self.acted_last = true;
        self.waiting = false;
    }

    /// True while a task started with [`Agent::start_task`] is unfinished.
    pub fn task_running(&self) -> bool {
        self.controlled && !self.main.is_empty()
    }

    /// Stops the current task (a test boundary was reached): called modules are left (focus
    /// restored, exit events observed) without running more rules.
    pub fn abort_task(&mut self) {
        let prog = self.program.clone();
        if let Err(e) = self.core.unwind(&prog, &mut self.main) {
            self.core.event(Event::Error {
                message: e.message.clone(),
            });
        }
        self.main.clear();
        self.waiting = false;
    }

    /// True when the agent can do nothing more until new input arrives.
    pub fn waiting(&self) -> bool {
        self.waiting
    }

    /// Sets the simulated time (seconds since the start of the run) that `get_time/1`
    /// answers; `None`: wall-clock time.
    pub fn set_clock(&mut self, now: Option<f64>) {
        self.core.clock = now;
        if let Ok(mut e) = self.core.ms.engine.try_borrow_mut() {
            e.set_clock(now);
        }
    }

    /// Installs (or removes, with `None`) the watcher; returns the previous one.
    pub fn set_watcher(&mut self, w: Option<Box<dyn Watcher>>) -> Option<Box<dyn Watcher>> {
        std::mem::replace(&mut self.core.watcher, w)
    }

    /// Installs (or removes, with `None`) a recorder of what the rules do in each cycle.
    pub fn set_why(&mut self, r: Option<super::why::Recorder>) {
        self.core.why = r;
    }

    /// Runs one reasoning cycle with this cycle's percepts and incoming messages.
    pub fn step(&mut self, percepts: &[Term], messages: &[Message]) -> CycleOutput {
        let mut out = CycleOutput::default();
        self.step_into(percepts, messages, &mut out);
        out
    }

    /// [`Agent::step`] writing the cycle's output over `out`: the run loop builds each output
    /// in its place in the round's list instead of moving the 240-byte value through every caller.
    pub fn step_into(&mut self, percepts: &[Term], messages: &[Message], out: &mut CycleOutput) {
        if let Some(s) = &self.stopped {
            *out = CycleOutput {
                stopped: Some(s.clone()),
                ..CycleOutput::default()
            };
            return;
        }
        if self.waiting && percepts.is_empty() && messages.is_empty() {
            *out = CycleOutput {
                waiting: true,
                skipped: true,
                ..CycleOutput::default()
            };
            return;
        }
        // Sleep and timers (modular GOAL): a sleeping agent only perceives; timers add their
        // percepts to the batch; messages that came during sleep arrive when it wakes.
        let (mut batch, mut held) = (None, None);
        if self.core.timing.busy() {
            let Some(timed) = self.timed_input(percepts, messages, out) else {
                return;
            };
            (batch, held) = timed;
        }
        let percepts = batch.as_deref().unwrap_or(percepts);
        let messages = held.as_deref().unwrap_or(messages);
        self.cycle += 1;
        if let Some(w) = &self.core.why {
            w.begin(self.cycle);
        }
        // The last step handed its output over (taken): only something recorded between
        // steps (an aborted task's error) is left to drop.
        if !self.core.out.is_clear() {
            self.core.out = CycleOutput::default();
        }
        let quota_end = self
            .core
            .cycle_time
            .and_then(|t| Instant::now().checked_add(t));
        self.begin_cycle(match (quota_end, self.core.run_end) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        });
        match self.run_cycle(percepts, messages) {
            Ok(None) => {}
            Ok(Some(reason)) => {
                let reason = self.shut_down(reason);
                self.stop(reason)
            }
            Err(e) => {
                self.core.event(Event::Error {
                    message: e.to_string(),
                });
                self.stop(StopReason::Error(e));
            }
        }
        // Whatever stopped a combo early, no `sent/2` fact stays held past the cycle.
        self.core.ms.mailbox.settle();
        self.collect_printed();
        let done = &self.core.out;
        self.waiting = self.stopped.is_none()
            && !self.acted_last
            && !self.core.unsettled
            && done.actions == 0
            && done.env_actions.is_empty()
            && done.messages.is_empty()
            && done.printed.is_empty()
            && !self.core.timing.busy()
            && chance(&self.core) == self.chance_before_main;
        self.core.out.waiting = self.waiting;
        // The agent keeps what `out` held: clear when the caller passed it clear, else
        // cleared when its next step starts (`is_clear` above).
        std::mem::swap(out, &mut self.core.out);
    }

    /// The input of a cycle of an agent that sleeps or has timers: the percepts with the due
    /// timers' added and the messages held during sleep (`None` each: as given); `None` when
    /// the agent sleeps on (it only perceived: the cycle's output is in `out`). Out of line:
    /// most agents never sleep.
    #[cold]
    #[inline(never)]
    fn timed_input(
        &mut self,
        percepts: &[Term],
        messages: &[Message],
        out: &mut CycleOutput,
    ) -> Option<(Option<Vec<Term>>, Option<Vec<Message>>)> {
        let now = self.core.now_ms();
        if self.core.timing.asleep(now, messages) {
            self.core.out = CycleOutput::default();
            self.core
                .perceive(percepts, &self.types, self.program.uses_newpercept);
            std::mem::swap(out, &mut self.core.out);
            return None;
        }
        let held = self.core.timing.wake_messages(messages);
        let due = self.core.timing.due(now);
        let batch = (!due.is_empty()).then(|| [percepts, &due].concat());
        Some((batch, held))
    }

    /// Keeps a buffer for the next cycle's outgoing messages, after a step that gave `out`
    /// and read `inbox`: the output's own buffer when it sent nothing, else the emptied inbox
    /// (the run loop makes each outgoing buffer a receiver's inbox), so an agent passing a
    /// message on allocates no buffer for it. Only a small buffer is kept (not a broadcast's).
    pub fn keep_buffer(&mut self, mut inbox: Vec<Message>, out: &mut CycleOutput) {
        let mine = &mut self.core.out.messages;
        if mine.capacity() != 0 {
            return;
        }
        if out.messages.is_empty() && reusable(&out.messages) {
            std::mem::swap(mine, &mut out.messages);
        } else if reusable(&inbox) {
            inbox.clear();
            *mine = inbox;
        }
    }

    /// Runs the shutdown module (modular GOAL) once, as the agent's last cycle, because the
    /// run ends while the agent still runs; `None` without a shutdown module or once stopped.
    pub fn end_of_run(&mut self) -> Option<CycleOutput> {
        let m = self.program.shutdown?;
        if self.stopped.is_some() {
            return None;
        }
        self.cycle += 1;
        self.core.out = CycleOutput::default();
        // Only the cycle quota bounds this pass: the run's own end may already have passed.
        self.begin_cycle(
            self.core
                .cycle_time
                .and_then(|t| Instant::now().checked_add(t)),
        );
        let prog = self.program.clone();
        match run_once(&mut self.core, &prog, m) {
            Ok(()) => self.core.event(Event::Stopped {
                reason: "run ended".to_string(),
            }),
            Err(e) => {
                self.core.event(Event::Error {
                    message: e.to_string(),
                });
                self.stop(StopReason::Error(e));
            }
        }
        self.collect_printed();
        Some(std::mem::take(&mut self.core.out))
    }

    /// Starts a cycle's events under `deadline`, which long queries also stop at (the engine
    /// checks it as it goes).
    fn begin_cycle(&mut self, deadline: Option<Instant>) {
        self.core.deadline = deadline;
        self.core.ms.engine.borrow_mut().set_deadline(deadline);
        if self.core.level >= TraceLevel::Changes {
            self.core.event(Event::CycleStart { cycle: self.cycle });
        }
    }

    /// Moves what the KR engine printed this cycle into the cycle's output, line by line.
    fn collect_printed(&mut self) {
        self.core.ms.move_output_to(&mut self.core.kr_out);
        if !self.core.kr_out.is_empty() {
            let text = std::mem::take(&mut self.core.kr_out);
            self.core
                .out
                .printed
                .extend(text.lines().map(str::to_string));
        }
    }

    /// Stops the agent from outside with a runtime error (e.g. the environment refused one
    /// of its actions, which GOAL treats as fatal for the agent).
    pub fn halt(&mut self, e: RuntimeError) {
        if self.stopped.is_none() {
            self.stopped = Some(StopReason::Error(e));
            self.main.clear();
            self.waiting = false;
        }
    }

    fn stop(&mut self, reason: StopReason) {
        let text = match &reason {
            StopReason::MainExited => "main module exited".to_string(),
            StopReason::Error(e) => format!("runtime error: {e}"),
        };
        self.core.event(Event::Stopped { reason: text });
        self.core.out.stopped = Some(reason.clone());
        self.stopped = Some(reason);
        self.main.clear();
    }

    fn run_cycle(
        &mut self,
        percepts: &[Term],
        messages: &[Message],
    ) -> Result<Option<StopReason>, RuntimeError> {
        // The program is borrowed, not cloned: every agent shares one `Arc<Program>`, and a
        // clone per cycle writes its reference count, a cache line that then moves between
        // the cores of a run on several workers on every cycle (12% of ring50 on 2 workers).
        let Agent {
            program,
            core,
            types,
            cycle,
            main,
            main_entered,
            acted_last,
            chance_before_main,
            controlled,
            ..
        } = self;
        let prog: &Program = program;
        core.perceive(percepts, types, prog.uses_newpercept);
        if core
            .receive(messages)
            .map_err(|e| core.error(prog, None, e))?
        {
            core.check_goals().map_err(|e| core.error(prog, None, e))?;
        }
        let new = !percepts.is_empty() || !messages.is_empty() || *acted_last;
        if *cycle == 1 {
            if let Some(init) = prog.init {
                run_once(core, prog, init)?;
            }
        }
        if new {
            if let Some(event) = prog.event {
                run_once(core, prog, event)?;
            }
        }
        // Only what main does decides whether the agent is waiting: init and event ran on
        // this cycle's input, and main's last pass saw their effects.
        core.unsettled = false;
        *chance_before_main = chance(core);
        if *controlled {
            if main.is_empty() {
                *acted_last = false;
                return Ok(None);
            }
            return match core.run(prog, main, true)? {
                RunEnd::Suspended { acted } => {
                    *acted_last = acted;
                    Ok(None)
                }
                RunEnd::Finished => {
                    main.clear();
                    *acted_last = true;
                    Ok(None)
                }
            };
        }
        if !*main_entered {
            *main_entered = true;
            let f = core
                .enter(prog, prog.main, &[], None)
                .map_err(|e| core.module_error(prog, prog.main, e))?;
            main.push(Frame::Module(f));
        }
        match core.run(prog, main, true)? {
            RunEnd::Suspended { acted } => {
                *acted_last = acted;
                Ok(None)
            }
            RunEnd::Finished => Ok(Some(StopReason::MainExited)),
        }
    }

    /// Runs the shutdown module (modular GOAL), if any, once before the agent stops because
    /// its main module exited; an error there is the reason the agent stops instead.
    fn shut_down(&mut self, reason: StopReason) -> StopReason {
        let prog = self.program.clone();
        match (prog.shutdown, &reason) {
            (Some(m), StopReason::MainExited) => match run_once(&mut self.core, &prog, m) {
                Ok(()) => reason,
                Err(e) => {
                    self.core.event(Event::Error {
                        message: e.to_string(),
                    });
                    StopReason::Error(e)
                }
            },
            _ => reason,
        }
    }
}

/// A duration as seconds, e.g. `2s` or `0.5s`.
pub fn show_duration(d: Duration) -> String {
    format!("{}s", d.as_secs_f64())
}

/// Runs module `idx` of `prog` (`init`, `event` or `shutdown`) to completion on `core` (no
/// cycle boundaries inside).
fn run_once(core: &mut Core, prog: &Program, idx: usize) -> Result<(), RuntimeError> {
    let f = core
        .enter(prog, idx, &[], None)
        .map_err(|e| core.module_error(prog, idx, e))?;
    let mut stack = vec![Frame::Module(f)];
    core.run(prog, &mut stack, false)?;
    Ok(())
}

/// Changes whenever the agent with `core` drew a random number or read the clock in a query.
fn chance(core: &Core) -> u128 {
    core.ms.engine.try_borrow().map_or(0, |e| e.chance())
}
