//! The run's communication layer: a transport (in-process or the simulated ring) with the
//! run's session book on top. The round driver hands it each round's messages; it follows the
//! sessions, writes their trace records, warns of protocol violations and network events, and
//! returns what arrives. Without any CLAMR option the driver does not create one at all.

use super::act::classify;
use super::ring::{Faults, Ring};
use super::session::{Book, Change, SessionStats};
use crate::agent::Message;
use crate::mas::routing::{InProcess, Transport};
use crate::mas::trace::TraceWriter;
use crate::term::Sym;
use serde_json::{json, Value};
use std::collections::{BTreeMap, VecDeque};

/// Which transport carries the messages.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Kind {
    /// In-process delivery (the default).
    #[default]
    InProcess,
    /// The simulated token ring.
    Ring,
}

/// The communication options of a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CommOptions {
    /// The transport.
    pub kind: Kind,
    /// Faults injected into the ring.
    pub faults: Faults,
    /// Follow sessions (for `--stats`).
    pub sessions: bool,
    /// Write session records into the trace.
    pub trace_sessions: bool,
}

impl CommOptions {
    /// True when the run needs a communication layer (anything but plain in-process routing).
    pub fn wanted(&self) -> bool {
        self.kind != Kind::InProcess || self.sessions || self.trace_sessions
    }
}

/// Parses `--comm-fail NAME@TICK`.
pub fn parse_fail(s: &str) -> Result<(String, u64), String> {
    let (name, tick) = s
        .rsplit_once('@')
        .ok_or_else(|| format!("`{s}`: write AGENT@TICK, e.g. Bot2@500"))?;
    let tick = tick
        .parse::<u64>()
        .map_err(|_| format!("`{s}`: the tick after @ must be a whole number, e.g. Bot2@500"))?;
    if name.is_empty() {
        return Err(format!("`{s}`: name the agent before @, e.g. Bot2@500"));
    }
    Ok((name.to_string(), tick))
}

/// The transport with the run's session book.
pub struct Comm {
    transport: Box<dyn Transport>,
    book: Book,
    trace_sessions: bool,
    /// Sessions opened by a message on its way: (from, to, content text) -> sessions.
    pending: BTreeMap<(Sym, Sym, String), VecDeque<usize>>,
    lost_warned: bool,
}

/// Warnings go to the run's observer.
pub type Warn<'a> = &'a mut dyn FnMut(&str);

impl Comm {
    /// The communication layer for agents `names` (name order), or `None` when not wanted.
    pub fn new(names: &[String], opts: &CommOptions, seed: u64) -> Result<Option<Comm>, String> {
        if !opts.wanted() {
            return Ok(None);
        }
        let transport: Box<dyn Transport> = match opts.kind {
            Kind::InProcess => Box::new(InProcess),
            Kind::Ring => Box::new(Ring::new(names, &opts.faults, seed)?),
        };
        Ok(Some(Comm {
            transport,
            book: Book::new(true),
            trace_sessions: opts.trace_sessions,
            pending: BTreeMap::new(),
            lost_warned: false,
        }))
    }

    /// True while messages are on their way.
    pub fn busy(&self) -> bool {
        self.transport.busy()
    }

    /// Carries a round's messages (in (sender, sequence) order): follows their sessions and
    /// returns (arrived, lost).
    pub fn carry(
        &mut self,
        (round, tick): (u64, u64),
        sent: Vec<Message>,
        mut trace: Option<&mut TraceWriter>,
        warn: Warn<'_>,
    ) -> (Vec<Message>, Vec<Message>) {
        for m in &sent {
            let act = classify(m.sender.name(), &m.content);
            let changes = self
                .book
                .observe(m.sender, m.receiver, &m.content, &act, tick);
            for c in &changes {
                if let Change::Opened(i) = c {
                    let text = m.content.to_string();
                    self.pending
                        .entry((m.sender, m.receiver, text))
                        .or_default()
                        .push_back(*i);
                }
            }
            self.report(&changes, (round, tick), trace.as_deref_mut(), warn);
        }
        let carried = self.transport.carry(tick, sent);
        for n in &carried.notes {
            warn(n);
            if let Some(t) = trace.as_deref_mut() {
                t.record("network", round, tick, json!({ "note": n }));
            }
        }
        for (m, delivered) in carried
            .arrived
            .iter()
            .map(|m| (m, true))
            .chain(carried.lost.iter().map(|m| (m, false)))
        {
            let key = (m.sender, m.receiver, m.content.to_string());
            let Some(i) = self.pending.get_mut(&key).and_then(|q| q.pop_front()) else {
                continue;
            };
            let change = if delivered {
                self.book.delivered(i, tick)
            } else {
                self.book.lost(i, tick)
            };
            self.report(
                &change.into_iter().collect::<Vec<_>>(),
                (round, tick),
                trace.as_deref_mut(),
                warn,
            );
        }
        self.pending.retain(|_, q| !q.is_empty());
        if !carried.lost.is_empty() && !self.lost_warned {
            self.lost_warned = true;
            let m = &carried.lost[0];
            warn(&format!(
                "message {} from {} to {} lost on the network (round {round}); further losses \
                 are counted in --stats (comm.lost)",
                m.content, m.sender, m.receiver
            ));
        }
        (carried.arrived, carried.lost)
    }

    /// Writes the trace records of `changes` and warns of violations.
    fn report(
        &self,
        changes: &[Change],
        (round, tick): (u64, u64),
        mut trace: Option<&mut TraceWriter>,
        warn: Warn<'_>,
    ) {
        for c in changes {
            if let Change::Violation(text) = c {
                warn(&format!("protocol violation: {text}"));
            }
            if !self.trace_sessions {
                continue;
            }
            let Some(t) = trace.as_deref_mut() else {
                continue;
            };
            t.record("session", round, tick, self.record(c));
        }
    }

    /// The fields of a session record.
    fn record(&self, c: &Change) -> Value {
        let (i, event) = match c {
            Change::Violation(text) => return json!({"event": "violation", "message": text}),
            Change::Opened(i) => (*i, "opened"),
            Change::Moved(i, _) => {
                let closed = self.book.get(*i).is_some_and(|s| s.state.closed());
                (*i, if closed { "closed" } else { "changed" })
            }
        };
        let Some(s) = self.book.get(i) else {
            return Value::Null;
        };
        json!({
            "event": event,
            "id": s.id(),
            "act": s.kind.name(),
            "initiator": s.initiator.name(),
            "partner": s.partner.name(),
            "state": s.state.name(),
            "message": s.latest,
            "opened": s.opened,
            "closed": s.closed,
        })
    }

    /// Ends the run: open sessions are abandoned; returns the session and transport figures.
    pub fn finish(
        &mut self,
        (round, tick): (u64, u64),
        trace: Option<&mut TraceWriter>,
        warn: Warn<'_>,
    ) -> (SessionStats, Value) {
        let changes = self.book.finish(tick);
        self.report(&changes, (round, tick), trace, warn);
        (self.book.stats(), self.transport.stats())
    }
}
