//! Modular GOAL's actions about time and channels (docs/modular-goal.md): `sleep(Ms)`,
//! `starttimer(Name, IntervalMs, DurationMs)` (percepts `timer(Name, N)`), `canceltimer(Name)`,
//! `subscribe(C)` and `unsubscribe(C)`.
//!
//! Time is the agent's clock: the simulated time of a lock-step run (ticks, never the wall
//! clock, so traces are reproducible), or the time since the agent was created in real-time
//! runs. A channel message is sent to every agent with the channel in it; receivers keep only
//! the channels they subscribed to (so no agent needs the others' subscriptions).

use super::action::Outcome;
use super::condition::show_subst;
use super::cycle::Core;
use super::error::Fault;
use super::mailbox::Message;
use crate::syntax::ast::TimingOp;
use crate::term::{Subst, Term};
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

/// The functor that marks a message sent to a channel: `'$channel'(Channel, Content)`.
pub const CHANNEL: &str = "$channel";

/// A running timer.
#[derive(Clone, Debug)]
struct Timer {
    start_ms: f64,
    interval_ms: f64,
    /// `None`: until cancelled.
    duration_ms: Option<f64>,
    /// Intervals already reported.
    fired: i64,
}

/// An agent's sleep, timers and channel subscriptions.
#[derive(Clone, Debug)]
pub struct Timing {
    created: Instant,
    /// Asleep until this time (milliseconds).
    sleep_until: Option<f64>,
    /// Timers by name (the name's text), in name order.
    timers: BTreeMap<String, (Term, Timer)>,
    /// A timer percept was produced in the last cycle (it must be seen to disappear).
    fired_last: bool,
    /// Channels subscribed to.
    channels: BTreeSet<String>,
    /// Messages that arrived while asleep, delivered when the agent wakes.
    held: Vec<Message>,
}

impl Default for Timing {
    fn default() -> Self {
        Timing {
            created: Instant::now(),
            sleep_until: None,
            timers: BTreeMap::new(),
            fired_last: false,
            channels: BTreeSet::new(),
            held: Vec::new(),
        }
    }
}

impl Timing {
    /// True while the agent must be stepped even without new input (asleep, or a timer runs).
    pub fn busy(&self) -> bool {
        self.sleep_until.is_some() || !self.timers.is_empty() || self.fired_last
    }

    /// True (and the messages kept for later) while the agent sleeps at `now_ms`.
    pub fn asleep(&mut self, now_ms: f64, messages: &[Message]) -> bool {
        match self.sleep_until {
            Some(t) if now_ms < t => {
                self.held.extend_from_slice(messages);
                true
            }
            _ => {
                self.sleep_until = None;
                false
            }
        }
    }

    /// The messages held while asleep followed by `messages`, if any were held.
    pub fn wake_messages(&mut self, messages: &[Message]) -> Option<Vec<Message>> {
        if self.held.is_empty() {
            return None;
        }
        let mut all = std::mem::take(&mut self.held);
        all.extend_from_slice(messages);
        Some(all)
    }

    /// The timer percepts due at `now_ms`: `timer(Name, N)` with N the intervals elapsed;
    /// timers past their duration end.
    pub fn due(&mut self, now_ms: f64) -> Vec<Term> {
        let mut out = Vec::new();
        self.timers.retain(|_, (name, t)| {
            let elapsed = now_ms - t.start_ms;
            let limit = t.duration_ms.map_or(elapsed, |d| d.min(elapsed));
            let n = (limit / t.interval_ms).floor() as i64;
            if n > t.fired {
                t.fired = n;
                out.push(Term::compound("timer", vec![name.clone(), Term::Int(n)]));
            }
            t.duration_ms.is_none_or(|d| elapsed < d)
        });
        self.fired_last = !out.is_empty();
        out
    }

    /// True when `channel` is subscribed to.
    pub fn subscribed(&self, channel: &str) -> bool {
        self.channels.contains(channel)
    }

    /// The content of a received message, or `None` for a channel message of a channel not
    /// subscribed to.
    pub fn accept(&self, content: &Term) -> Option<Term> {
        match content.functor() {
            Some((f, 2)) if f.name() == CHANNEL => {
                let c = content.args()[0].to_print_text();
                self.subscribed(&c).then(|| content.args()[1].clone())
            }
            _ => Some(content.clone()),
        }
    }
}

/// A number of milliseconds (an integer or float, not negative).
fn millis(t: &Term, what: &str) -> Result<f64, Fault> {
    let v = match t {
        Term::Int(i) => *i as f64,
        Term::Float(f) => f.0,
        _ => {
            return Err(Fault::new(format!(
                "{what} must be a number of milliseconds, not {t}"
            )))
        }
    };
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(Fault::new(format!("{what} must not be negative: {t}")))
    }
}

impl Core {
    /// The agent's time in milliseconds: the run's simulated clock when it has one.
    pub fn now_ms(&self) -> f64 {
        match self.clock {
            Some(s) => s * 1000.0,
            None => self.timing.created.elapsed().as_secs_f64() * 1000.0,
        }
    }

    /// Performs `sleep`, `starttimer`, `canceltimer`, `subscribe` or `unsubscribe`.
    pub fn timing_action(
        &mut self,
        op: TimingOp,
        args: &[Term],
        s: &Subst,
    ) -> Result<Outcome, Fault> {
        let args: Vec<Term> = args.iter().map(|a| s.apply(a)).collect();
        if let Some(a) = args.iter().find(|a| !a.is_ground()) {
            return Err(Fault {
                message: format!("{}: argument {a} is not bound", op.name()),
                binding: Some(show_subst(s)),
            });
        }
        let now = self.now_ms();
        match op {
            TimingOp::Sleep => {
                let ms = millis(&args[0], "the time to sleep")?;
                self.timing.sleep_until = Some(now + ms);
            }
            TimingOp::StartTimer => {
                let interval = millis(&args[1], "the timer interval")?;
                if interval == 0.0 {
                    return Err(Fault::new("the timer interval must be more than 0 ms"));
                }
                let duration = millis(&args[2], "the timer duration")?;
                let timer = Timer {
                    start_ms: now,
                    interval_ms: interval,
                    duration_ms: (duration > 0.0).then_some(duration),
                    fired: 0,
                };
                let key = args[0].to_print_text();
                self.timing.timers.insert(key, (args[0].clone(), timer));
            }
            TimingOp::CancelTimer => {
                self.timing.timers.remove(&args[0].to_print_text());
            }
            TimingOp::Subscribe | TimingOp::Unsubscribe => {
                for c in &args {
                    let name = c.to_print_text();
                    if op == TimingOp::Subscribe {
                        self.timing.channels.insert(name);
                    } else {
                        self.timing.channels.remove(&name);
                    }
                }
            }
        }
        self.done_with(|| Term::compound(op.name(), args.clone()));
        Ok(Outcome::Done { real: true })
    }
}
