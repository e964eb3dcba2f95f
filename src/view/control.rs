//! Pacing, pausing and single-stepping a live run from the page. The page changes a shared
//! [`Control`]; the run's observer calls [`Pacer::wait`] after every round (the round driver's
//! `Observer::pace`), so there is one driver and the trace is the same at any pace.

use super::players::Players;
use serde_json::{json, Value};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Default pace of a watched run: ticks per second of BW4T in real time (its default step
/// delay of 10 ms per tick).
pub const DEFAULT_SPEED: f64 = 1.0 / crate::mas::run::TICK_SECONDS;
/// The fastest pace the page may ask for (ticks per second); faster means "as fast as possible".
pub const MAX_SPEED: f64 = 100_000.0;
/// How often a paused run looks at the interrupt flag (Ctrl-C still ends a paused run).
const POLL: Duration = Duration::from_millis(100);

#[derive(Clone, Copy, Debug)]
struct State {
    paused: bool,
    /// Ticks per second.
    speed: f64,
    /// Single steps asked for while paused.
    steps: u64,
    /// The last tick the run reached.
    tick: u64,
    /// The run is over (nothing to pace any more).
    ended: bool,
}

/// What the page may change about a live run: its pace, and (for people playing HumanBots)
/// the requests the run takes at its next tick boundary.
pub struct Control {
    state: Mutex<State>,
    changed: Condvar,
    players: Players,
}

/// A change the page asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    Pause,
    Play,
    /// One more round while paused.
    Step,
    /// Ticks per second (clamped to 0.1 ..= [`MAX_SPEED`]).
    Speed(f64),
}

impl Command {
    /// Reads `pause`, `play`, `step` or `speed=N` (the query of `POST /api/control`).
    pub fn parse(query: &str) -> Result<Command, String> {
        match query.split_once('=') {
            None if query == "pause" => Ok(Command::Pause),
            None if query == "play" => Ok(Command::Play),
            None if query == "step" => Ok(Command::Step),
            Some(("speed", v)) => match v.parse::<f64>() {
                Ok(s) if s.is_finite() && s > 0.0 => Ok(Command::Speed(s.clamp(0.1, MAX_SPEED))),
                _ => Err(format!(
                    "speed must be a positive number of ticks per second, not `{v}`"
                )),
            },
            _ => Err(format!(
                "unknown control `{query}`: use pause, play, step or speed=TICKS_PER_SECOND"
            )),
        }
    }
}

impl Control {
    /// A run that starts playing at `speed` ticks per second.
    pub fn new(speed: f64) -> Arc<Control> {
        Arc::new(Control {
            state: Mutex::new(State {
                paused: false,
                speed: speed.clamp(0.1, MAX_SPEED),
                steps: 0,
                tick: 0,
                ended: false,
            }),
            changed: Condvar::new(),
            players: Players::new(),
        })
    }

    /// The people playing the run's HumanBots.
    pub fn players(&self) -> &Players {
        &self.players
    }

    /// True when the run is over.
    pub fn ended(&self) -> bool {
        self.lock().ended
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Applies a page's command.
    pub fn apply(&self, c: Command) {
        let mut s = self.lock();
        match c {
            Command::Pause => s.paused = true,
            Command::Play => s.paused = false,
            Command::Step => {
                s.paused = true;
                s.steps += 1;
            }
            Command::Speed(v) => s.speed = v,
        }
        drop(s);
        self.changed.notify_all();
    }

    /// The run is over.
    pub fn end(&self) {
        self.lock().ended = true;
        self.changed.notify_all();
    }

    /// The state as the page shows it: `paused`, `speed`, `tick`, `ended`.
    pub fn to_json(&self) -> Value {
        let s = *self.lock();
        json!({"paused": s.paused, "speed": s.speed, "tick": s.tick, "ended": s.ended})
    }
}

/// The run's side of a [`Control`]: paces rounds, holds the run while paused.
pub struct Pacer {
    control: Arc<Control>,
    /// When the next round may start.
    due: Option<Instant>,
    interrupt: Arc<AtomicUsize>,
}

impl Pacer {
    /// Paces by `control`; a non-zero `interrupt` (Ctrl-C) releases a paused run.
    pub fn new(control: Arc<Control>, interrupt: Arc<AtomicUsize>) -> Pacer {
        Pacer {
            control,
            due: None,
            interrupt,
        }
    }

    fn interrupted(&self) -> bool {
        self.interrupt.load(Ordering::Relaxed) != 0
    }

    /// Called after each round (now at `tick`): waits while paused (until play, a step, or an
    /// interrupt), else until the round's time at the current speed has passed.
    pub fn wait(&mut self, tick: u64) {
        let mut s = self.control.lock();
        s.tick = tick;
        loop {
            if self.interrupted() {
                return;
            }
            if s.paused {
                if s.steps > 0 {
                    s.steps -= 1;
                    self.due = None;
                    return;
                }
                s = match self.control.changed.wait_timeout(s, POLL) {
                    Ok((g, _)) => g,
                    Err(e) => e.into_inner().0,
                };
                continue;
            }
            let period = Duration::from_secs_f64(1.0 / s.speed);
            let now = Instant::now();
            let due = *self.due.get_or_insert(now + period);
            if now >= due {
                // Late (a slow round): start counting again from now rather than rushing.
                let next = due + period;
                self.due = Some(if next < now { now + period } else { next });
                return;
            }
            // Woken early by a change (pause, new speed): look again.
            s = match self.control.changed.wait_timeout(s, (due - now).min(POLL)) {
                Ok((g, r)) if !r.timed_out() => {
                    self.due = None;
                    g
                }
                Ok((g, _)) => g,
                Err(e) => e.into_inner().0,
            };
        }
    }
}
