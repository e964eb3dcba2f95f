//! Runs an [`Environment`] on its own thread and talks to it over `crossbeam-channel`.
//!
//! Two modes:
//! * **lock-step**: the caller sends one [`EnvHandle::round`] at a time (a list of
//!   (entity, action) pairs in the order to apply them); the environment applies them in that
//!   order, advances exactly one tick and replies with every action result and every entity's
//!   percept batch. Nothing happens between rounds, so runs are deterministic.
//! * **real-time**: the environment ticks at a fixed rate; actions submitted with
//!   [`EnvHandle::submit`]/[`EnvHandle::act`] are applied at the next tick in arrival order;
//!   percept batches are pulled with [`EnvHandle::perceive`].
//!
//! Errors are values: a stopped or crashed environment thread gives [`EnvError::Stopped`].
//! Dropping the handle (or [`EnvHandle::stop`]) stops and joins the thread.

use super::{ActionResult, EntityInfo, Environment, PerceptDecl};
use crate::term::Term;
use crossbeam_channel::{bounded, unbounded, Receiver, RecvTimeoutError, Sender};
use serde::Serialize;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How the environment thread advances time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// One tick per [`EnvHandle::round`].
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

enum Request {
    Info(Sender<EnvInfo>),
    Round(Vec<(String, Term)>, Sender<Result<RoundReply, EnvError>>),
    Perceive(Vec<String>, Sender<Batches>),
    Act(String, Term, Sender<Result<ActionResult, EnvError>>),
    Status(Sender<EnvStatus>),
    /// The layout (true) or the scene (false) a viewer draws.
    View(bool, Sender<Option<serde_json::Value>>),
    /// A person's request for an entity ([`Environment::input`]).
    Input(String, Term, Sender<Result<(), String>>),
    Stop,
}

/// The caller's side of an environment thread.
pub struct EnvHandle {
    tx: Sender<Request>,
    join: Option<JoinHandle<()>>,
}

impl EnvHandle {
    /// Moves `env` onto a new thread running in `mode`.
    pub fn spawn(env: Box<dyn Environment>, mode: Mode) -> EnvHandle {
        let (tx, rx) = unbounded();
        let join = std::thread::Builder::new()
            .name("environment".into())
            .spawn(move || match mode {
                Mode::LockStep => run_lock_step(env, rx),
                Mode::RealTime { ticks_per_second } => run_real_time(env, rx, ticks_per_second),
            })
            .ok();
        EnvHandle { tx, join }
    }

    fn ask<T>(&self, make: impl FnOnce(Sender<T>) -> Request) -> Result<T, EnvError> {
        let (tx, rx) = bounded(1);
        self.tx.send(make(tx)).map_err(|_| EnvError::Stopped)?;
        rx.recv().map_err(|_| EnvError::Stopped)
    }

    /// The entities and percept declarations.
    pub fn info(&self) -> Result<EnvInfo, EnvError> {
        self.ask(Request::Info)
    }

    /// Lock-step: applies `actions` in order, advances one tick, returns results and percepts.
    pub fn round(&self, actions: Vec<(String, Term)>) -> Result<RoundReply, EnvError> {
        self.ask(|tx| Request::Round(actions, tx))?
    }

    /// The next percept batch of each named entity (all entities when `entities` is empty),
    /// without advancing time.
    pub fn perceive(&self, entities: &[String]) -> Result<Batches, EnvError> {
        self.ask(|tx| Request::Perceive(entities.to_vec(), tx))
    }

    /// Real-time: queues an action for the next tick; the receiver yields its result then.
    pub fn submit(
        &self,
        entity: &str,
        action: Term,
    ) -> Result<Receiver<Result<ActionResult, EnvError>>, EnvError> {
        let (tx, rx) = bounded(1);
        self.tx
            .send(Request::Act(entity.to_string(), action, tx))
            .map_err(|_| EnvError::Stopped)?;
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
        self.ask(Request::Status)
    }

    /// The fixed layout a viewer draws ([`Environment::layout`]).
    pub fn layout(&self) -> Result<Option<serde_json::Value>, EnvError> {
        self.ask(|tx| Request::View(true, tx))
    }

    /// The moving parts a viewer draws now ([`Environment::scene`]).
    pub fn scene(&self) -> Result<Option<serde_json::Value>, EnvError> {
        self.ask(|tx| Request::View(false, tx))
    }

    /// Hands a person's request for `entity` to the environment between two ticks
    /// ([`Environment::input`]); the inner `Err` says why the environment refused it.
    pub fn input(&self, entity: &str, request: &Term) -> Result<Result<(), String>, EnvError> {
        self.ask(|tx| Request::Input(entity.to_string(), request.clone(), tx))
    }

    /// Stops the thread and waits for it.
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        let _ = self.tx.send(Request::Stop);
        if let Some(j) = self.join.take() {
            let _ = j.join();
        }
    }
}

impl Drop for EnvHandle {
    fn drop(&mut self) {
        self.shutdown();
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

fn run_lock_step(mut env: Box<dyn Environment>, rx: Receiver<Request>) {
    while let Ok(req) = rx.recv() {
        match req {
            Request::Info(tx) => drop(tx.send(info(env.as_ref()))),
            Request::Round(actions, tx) => {
                let results = actions
                    .into_iter()
                    .map(|(e, a)| {
                        let r = env.perform(&e, &a);
                        (e, r)
                    })
                    .collect();
                env.tick();
                let percepts = perceive(env.as_mut(), Vec::new());
                let reply = RoundReply {
                    tick: env.ticks(),
                    results,
                    percepts,
                    finished: env.is_finished(),
                };
                let _ = tx.send(Ok(reply));
            }
            Request::Perceive(names, tx) => drop(tx.send(perceive(env.as_mut(), names))),
            Request::Act(_, _, tx) => {
                let _ = tx.send(Err(EnvError::WrongMode(
                    "single actions are for real-time mode; use round() in lock-step mode",
                )));
            }
            Request::Status(tx) => drop(tx.send(status(env.as_ref()))),
            Request::View(layout, tx) => drop(tx.send(view(env.as_mut(), layout))),
            Request::Input(e, t, tx) => drop(tx.send(env.input(&e, &t))),
            Request::Stop => break,
        }
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
            Ok(Request::Round(_, tx)) => {
                let _ = tx.send(Err(EnvError::WrongMode(
                    "rounds are for lock-step mode; use submit()/act() in real-time mode",
                )));
            }
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
