//! Runs an [`Environment`] behind one handle, in lock-step or in real time.
//!
//! Two modes:
//! * **lock-step**: the caller asks for one [`EnvHandle::round`] at a time (a list of
//!   (entity, action) pairs in the order to apply them); the environment applies them in that
//!   order, advances exactly one tick and returns every action result and every entity's
//!   percept batch. Nothing happens between rounds, so runs are deterministic. The caller's own
//!   thread steps the environment: it would only wait for another thread's answer, and handing
//!   each round over between threads cost more system time than the whole tick.
//! * **real-time**: the environment ticks at a fixed rate on its own thread and is talked to
//!   over `crossbeam-channel`; actions submitted with [`EnvHandle::submit`]/[`EnvHandle::act`]
//!   are applied at the next tick in arrival order; percept batches are pulled with
//!   [`EnvHandle::perceive`].
//!
//! Errors are values: a stopped environment, or one that panicked, gives
//! [`EnvError::Stopped`]. Dropping the handle (or [`EnvHandle::stop`]) stops the environment
//! (and joins its thread).

use super::{ActionResult, EntityInfo, Environment, PerceptDecl};
use crate::term::Term;
use crossbeam_channel::{bounded, unbounded, Receiver, RecvTimeoutError, Sender};
use serde::Serialize;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How the environment thread advances time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// One tick per [`EnvHandle::round`], stepped on the caller's thread.
    LockStep,
    /// Ticks at the given rate (ticks per second; values <= 0 mean as fast as possible).
    RealTime { ticks_per_second: f64 },
}

/// Why a request to the environment thread did not get an answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EnvError {
    /// The environment thread has stopped (or crashed).
    Stopped,
    /// The request does not exist in the thread's mode.
    WrongMode(&'static str),
}

impl std::fmt::Display for EnvError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EnvError::Stopped => write!(f, "the environment has stopped"),
            EnvError::WrongMode(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for EnvError {}

/// What the environment offers: its entities and percept declarations.
#[derive(Clone, Debug, Serialize)]
pub struct EnvInfo {
    pub entities: Vec<EntityInfo>,
    pub declarations: Vec<PerceptDecl>,
}

/// The reply to one lock-step round.
#[derive(Clone, Debug)]
pub struct RoundReply {
    /// The tick number after this round's tick.
    pub tick: u64,
    /// One result per submitted action, in submission order.
    pub results: Vec<(String, ActionResult)>,
    /// Every entity's percept batch after the tick, in entity order.
    pub percepts: Vec<(String, Vec<Term>)>,
    /// True when the environment's task is complete.
    pub finished: bool,
}

/// The environment's progress and statistics.
#[derive(Clone, Debug, Serialize)]
pub struct EnvStatus {
    pub ticks: u64,
    pub finished: bool,
    pub stats: serde_json::Value,
}

type Batches = Vec<(String, Vec<Term>)>;

/// A real-time action waiting for the next tick, with where to send its result.
type Queued = (String, Term, Sender<Result<ActionResult, EnvError>>);

/// A request to a real-time environment thread.
enum Request {
    Info(Sender<EnvInfo>),
    Perceive(Vec<String>, Sender<Batches>),
    Act(String, Term, Sender<Result<ActionResult, EnvError>>),
    Status(Sender<EnvStatus>),
    /// The layout (true) or the scene (false) a viewer draws.
    View(bool, Sender<Option<serde_json::Value>>),
    /// A person's request for an entity ([`Environment::input`]).
    Input(String, Term, Sender<Result<(), String>>),
    Stop,
}

/// The caller's side of an environment.
pub struct EnvHandle {
    place: Place,
}

/// Where the environment runs.
enum Place {
    /// Lock-step, on the caller's thread; `None` once it panicked.
    Here(Mutex<Option<Box<dyn Environment>>>),
    /// Real-time, on its own thread.
    Thread {
        tx: Sender<Request>,
        join: Option<JoinHandle<()>>,
    },
}

const ROUNDS_ARE_LOCK_STEP: EnvError =
    EnvError::WrongMode("rounds are for lock-step mode; use submit()/act() in real-time mode");
const ACTS_ARE_REAL_TIME: EnvError =
    EnvError::WrongMode("single actions are for real-time mode; use round() in lock-step mode");

impl EnvHandle {
    /// Takes `env` to run in `mode` (real-time: on a new thread).
    pub fn spawn(env: Box<dyn Environment>, mode: Mode) -> EnvHandle {
        let place = match mode {
            Mode::LockStep => Place::Here(Mutex::new(Some(env))),
            Mode::RealTime { ticks_per_second } => {
                let (tx, rx) = unbounded();
                let join = std::thread::Builder::new()
                    .name("environment".into())
                    .spawn(move || run_real_time(env, rx, ticks_per_second))
                    .ok();
                Place::Thread { tx, join }
            }
        };
        EnvHandle { place }
    }

    /// Runs `here` on a lock-step environment, or asks the real-time thread with `there`.
    fn call<T>(
        &self,
        here: impl FnOnce(&mut dyn Environment) -> T,
        there: impl FnOnce(Sender<T>) -> Request,
    ) -> Result<T, EnvError> {
        match &self.place {
            Place::Here(env) => step(env, here),
            Place::Thread { tx, .. } => {
                let (reply, rx) = bounded(1);
                tx.send(there(reply)).map_err(|_| EnvError::Stopped)?;
                rx.recv().map_err(|_| EnvError::Stopped)
            }
        }
    }

    /// The entities and percept declarations.
    pub fn info(&self) -> Result<EnvInfo, EnvError> {
        self.call(|env| info(env), Request::Info)
    }

    /// Lock-step: applies `actions` in order, advances one tick, returns results and percepts.
    pub fn round(&self, actions: Vec<(String, Term)>) -> Result<RoundReply, EnvError> {
        match &self.place {
            Place::Here(env) => step(env, |env| round(env, actions)),
            Place::Thread { .. } => Err(ROUNDS_ARE_LOCK_STEP),
        }
    }

    /// The next percept batch of each named entity (all entities when `entities` is empty),
    /// without advancing time.
    pub fn perceive(&self, entities: &[String]) -> Result<Batches, EnvError> {
        self.call(
            |env| perceive(env, entities.to_vec()),
            |tx| Request::Perceive(entities.to_vec(), tx),
        )
    }

    /// Real-time: queues an action for the next tick; the receiver yields its result then.
    pub fn submit(
        &self,
        entity: &str,
        action: Term,
    ) -> Result<Receiver<Result<ActionResult, EnvError>>, EnvError> {
        let (tx, rx) = bounded(1);
        match &self.place {
            Place::Here(_) => drop(tx.send(Err(ACTS_ARE_REAL_TIME))),
            Place::Thread { tx: requests, .. } => requests
                .send(Request::Act(entity.to_string(), action, tx))
                .map_err(|_| EnvError::Stopped)?,
        }
        Ok(rx)
    }

    /// Real-time: queues an action and waits until the next tick has applied it.
    pub fn act(&self, entity: &str, action: Term) -> Result<ActionResult, EnvError> {
        self.submit(entity, action)?
            .recv()
            .map_err(|_| EnvError::Stopped)?
    }

    /// Ticks done, whether the task is complete, and the statistics.
    pub fn status(&self) -> Result<EnvStatus, EnvError> {
        self.call(|env| status(env), Request::Status)
    }

    /// The fixed layout a viewer draws ([`Environment::layout`]).
    pub fn layout(&self) -> Result<Option<serde_json::Value>, EnvError> {
        self.call(|env| view(env, true), |tx| Request::View(true, tx))
    }

    /// The moving parts a viewer draws now ([`Environment::scene`]).
    pub fn scene(&self) -> Result<Option<serde_json::Value>, EnvError> {
        self.call(|env| view(env, false), |tx| Request::View(false, tx))
    }

    /// Hands a person's request for `entity` to the environment between two ticks
    /// ([`Environment::input`]); the inner `Err` says why the environment refused it.
    pub fn input(&self, entity: &str, request: &Term) -> Result<Result<(), String>, EnvError> {
        self.call(
            |env| env.input(entity, request),
            |tx| Request::Input(entity.to_string(), request.clone(), tx),
        )
    }

    /// Stops the environment (and waits for its thread).
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        match &mut self.place {
            Place::Here(env) => drop(env.get_mut().map(Option::take)),
            Place::Thread { tx, join } => {
                let _ = tx.send(Request::Stop);
                if let Some(j) = join.take() {
                    let _ = j.join();
                }
            }
        }
    }
}

impl Drop for EnvHandle {
    fn drop(&mut self) {
        self.shutdown();
    }
}

/// Runs `f` on a lock-step environment; a panic stops the environment for good, as the
/// end of its thread would.
fn step<T>(
    env: &Mutex<Option<Box<dyn Environment>>>,
    f: impl FnOnce(&mut dyn Environment) -> T,
) -> Result<T, EnvError> {
    let mut slot = env.lock().unwrap_or_else(|p| p.into_inner());
    let live = slot.as_mut().ok_or(EnvError::Stopped)?;
    match catch_unwind(AssertUnwindSafe(|| f(live.as_mut()))) {
        Ok(v) => Ok(v),
        Err(_) => {
            *slot = None;
            Err(EnvError::Stopped)
        }
    }
}

/// One lock-step round: `actions` in order, one tick, every entity's percepts.
fn round(env: &mut dyn Environment, actions: Vec<(String, Term)>) -> RoundReply {
    let results = actions
        .into_iter()
        .map(|(e, a)| {
            let r = env.perform(&e, &a);
            (e, r)
        })
        .collect();
    env.tick();
    let percepts = perceive(env, Vec::new());
    RoundReply {
        tick: env.ticks(),
        results,
        percepts,
        finished: env.is_finished(),
    }
}

fn info(env: &dyn Environment) -> EnvInfo {
    EnvInfo {
        entities: env.entities(),
        declarations: env.declarations(),
    }
}

fn perceive(env: &mut dyn Environment, names: Vec<String>) -> Batches {
    let names = if names.is_empty() {
        env.entities().into_iter().map(|e| e.name).collect()
    } else {
        names
    };
    names
        .into_iter()
        .map(|n| {
            let p = env.percepts(&n);
            (n, p)
        })
        .collect()
}

fn status(env: &dyn Environment) -> EnvStatus {
    EnvStatus {
        ticks: env.ticks(),
        finished: env.is_finished(),
        stats: env.stats(),
    }
}

fn view(env: &mut dyn Environment, layout: bool) -> Option<serde_json::Value> {
    if layout {
        env.layout()
    } else {
        env.scene()
    }
}

fn run_real_time(mut env: Box<dyn Environment>, rx: Receiver<Request>, tps: f64) {
    let period = if tps > 0.0 && tps.is_finite() {
        Duration::from_secs_f64(1.0 / tps)
    } else {
        Duration::ZERO
    };
    let mut next = Instant::now() + period;
    let mut queue: Vec<Queued> = Vec::new();
    loop {
        // Tick first when due, so that a steady stream of requests cannot starve the clock.
        if Instant::now() >= next {
            for (e, a, tx) in queue.drain(..) {
                let _ = tx.send(Ok(env.perform(&e, &a)));
            }
            env.tick();
            next += period;
            let now = Instant::now();
            if next < now {
                // Fell behind (slow machine): do not try to catch up with a burst of ticks.
                next = now + period;
            }
            if period > Duration::ZERO {
                continue;
            }
        }
        match rx.recv_deadline(next) {
            Ok(Request::Info(tx)) => drop(tx.send(info(env.as_ref()))),
            Ok(Request::Perceive(names, tx)) => drop(tx.send(perceive(env.as_mut(), names))),
            Ok(Request::Act(e, a, tx)) => queue.push((e, a, tx)),
            Ok(Request::Status(tx)) => drop(tx.send(status(env.as_ref()))),
            Ok(Request::View(layout, tx)) => drop(tx.send(view(env.as_mut(), layout))),
            Ok(Request::Input(e, t, tx)) => drop(tx.send(env.input(&e, &t))),
            Ok(Request::Stop) | Err(RecvTimeoutError::Disconnected) => break,
            Err(RecvTimeoutError::Timeout) => {}
        }
    }
}
