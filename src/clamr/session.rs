//! Sessions: each conversation followed through the seed's session protocols. Request and
//! RequestWhen: acknowledge (accept | refuse), for RequestWhen the requester's start signal, then
//! report (done | failed); Query: one answer; Offer: accept | refuse; Inform: OK (delivery).
//! The runtime keeps one book for the run (trace, stats, violations); each agent keeps its own
//! of what it sent and received (the `session/4` facts).

use super::act::{Act, Answer, SpeechAct};
use crate::term::{Sym, Term};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// The name of the facts `session(Id, With, Act, State)` an agent sees its conversations by.
pub const FACT: &str = "session";

/// Where a conversation stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum State {
    /// Waiting for the partner's first answer.
    Open,
    /// The partner accepted a request; waiting for its report (or, for a RequestWhen, for the
    /// start signal).
    Accepted,
    /// A RequestWhen's start signal was sent; waiting for the report.
    Started,
    /// Ended as the protocol says (answered, done, accepted offer, delivered inform).
    Completed,
    /// The partner refused.
    Refused,
    /// The partner reported failure.
    Failed,
    /// Never finished: the run ended first, or a message of it was lost.
    Abandoned,
}

impl State {
    /// The name agents see in `session/4`, interned.
    fn sym(self) -> Sym {
        static SYMS: OnceLock<Vec<Sym>> = OnceLock::new();
        let all = [
            State::Open,
            State::Accepted,
            State::Started,
            State::Completed,
            State::Refused,
            State::Failed,
            State::Abandoned,
        ];
        SYMS.get_or_init(|| all.iter().map(|s| Sym::intern(s.name())).collect())[self as usize]
    }

    /// The name agents see in `session/4`.
    pub fn name(self) -> &'static str {
        match self {
            State::Open => "open",
            State::Accepted => "accepted",
            State::Started => "started",
            State::Completed => "completed",
            State::Refused => "refused",
            State::Failed => "failed",
            State::Abandoned => "abandoned",
        }
    }

    /// True once the conversation is over.
    pub fn closed(self) -> bool {
        !matches!(self, State::Open | State::Accepted | State::Started)
    }
}

/// One conversation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Session {
    /// N of the id `Initiator-N`: the initiator's N-th conversation with this partner (both
    /// sides count the same way, so both see the same id).
    pub number: u64,
    /// Who opened it.
    pub initiator: Sym,
    /// Who it was opened with.
    pub partner: Sym,
    /// The opening act.
    pub kind: SpeechAct,
    /// Where it stands.
    pub state: State,
    /// Tick of the opening message.
    pub opened: u64,
    /// Tick of the partner's first answer.
    pub answered: Option<u64>,
    /// Tick it closed.
    pub closed: Option<u64>,
    /// The opening message (content text; empty in an agent's own book, which names no
    /// messages).
    pub opening: String,
    /// The message that closed it, with its tick.
    pub closing: Option<(String, u64)>,
    /// The last message that moved it on.
    pub latest: String,
}

impl Session {
    /// The id `Initiator-N`.
    pub fn id(&self) -> String {
        format!("{}-{}", self.initiator, self.number)
    }

    /// The `session(Id, With, Act, State)` fact as agent `me` sees it.
    pub fn fact(&self, me: Sym) -> Term {
        static SESSION: OnceLock<Sym> = OnceLock::new();
        let with = if self.initiator == me {
            self.partner
        } else {
            self.initiator
        };
        let n = i64::try_from(self.number).unwrap_or(i64::MAX);
        let id = Term::compound(
            crate::term::well_known::MINUS,
            vec![Term::Atom(self.initiator), Term::Int(n)],
        );
        Term::compound(
            *SESSION.get_or_init(|| Sym::intern(FACT)),
            vec![
                id,
                Term::Atom(with),
                Term::Atom(self.kind.sym()),
                Term::Atom(self.state.sym()),
            ],
        )
    }
}

/// What a message did to the book.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Change {
    /// Session `index` was opened.
    Opened(usize),
    /// Session `index` moved on from state `from` (or got a progress report, same state).
    Moved(usize, State),
    /// The message broke the protocol; the text names it and the earlier message concerned.
    Violation(String),
}

/// Sessions opened, answered and closed; figures for `--stats`.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SessionStats {
    pub opened: u64,
    pub completed: u64,
    pub refused: u64,
    pub failed: u64,
    pub abandoned: u64,
    /// Protocol violations (each also a warning).
    pub violations: u64,
    /// Ticks from opening to the partner's first answer, over the answered sessions.
    pub response_ticks: ResponseTicks,
    /// Sessions opened per act (`request`, `query`, ...).
    pub by_act: BTreeMap<String, u64>,
}

/// Response times in ticks.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ResponseTicks {
    /// Sessions that got an answer.
    pub answered: u64,
    /// Mean ticks to the answer (0 when none).
    pub mean: f64,
    /// Longest wait for an answer.
    pub max: u64,
}

/// The sessions of a run or of one agent.
#[derive(Clone, Debug, Default)]
pub struct Book {
    sessions: Vec<Session>,
    /// Open sessions per (initiator, partner), oldest first. Keyed by symbol: only looked
    /// up, never iterated in key order.
    open: BTreeMap<(Sym, Sym), Vec<usize>>,
    /// Sessions opened per (initiator, partner), for ids.
    counts: BTreeMap<(Sym, Sym), u64>,
    /// The last message per (sender, receiver), to name it in a violation.
    last: BTreeMap<(Sym, Sym), (String, u64)>,
    /// Track Inform sessions and name messages (the runtime does; an agent's own book lists
    /// no informs and keeps no message texts).
    pub informs: bool,
    violations: u64,
}

fn key(a: Sym, b: Sym) -> (Sym, Sym) {
    (a, b)
}

impl Book {
    /// A book; `informs`: also open (and complete on delivery) a session per Inform.
    pub fn new(informs: bool) -> Book {
        Book {
            informs,
            ..Book::default()
        }
    }

    /// The sessions, in opening order.
    pub fn sessions(&self) -> &[Session] {
        &self.sessions
    }

    /// Session `i`.
    pub fn get(&self, i: usize) -> Option<&Session> {
        self.sessions.get(i)
    }

    /// Follows message `content` (read as `act`) from `from` to `to` at `tick`.
    pub fn observe(
        &mut self,
        from: Sym,
        to: Sym,
        content: &Term,
        act: &Act,
        tick: u64,
    ) -> Vec<Change> {
        let plain_inform = act.answer.is_none() && !act.signal && act.sat == SpeechAct::Inform;
        if plain_inform && !self.informs && self.open.is_empty() {
            // An agent's own book: an Inform matters only as the answer to an open query.
            return Vec::new();
        }
        // Texts name messages in the runtime's trace and warnings; an agent's book shows
        // neither, and writing every message out is most of what following it would cost.
        let text = if self.informs {
            content.to_string()
        } else {
            String::new()
        };
        let change = if let Some(answer) = act.answer {
            self.answer(from, to, answer, &text, tick)
        } else if act.signal {
            self.signal(from, to, &text, tick)
        } else if plain_inform {
            match self.find(to, from, |s| {
                s.kind == SpeechAct::Query && s.state == State::Open
            }) {
                Some(i) => {
                    self.sessions[i].answered = Some(tick);
                    Some(self.moved(i, State::Completed, &text, tick))
                }
                None if self.informs => Some(self.open(from, to, act.sat, &text, tick)),
                None => None,
            }
        } else {
            Some(self.open(from, to, act.sat, &text, tick))
        };
        if self.informs {
            // The runtime's book names earlier messages in its warnings.
            self.last.insert(key(from, to), (text, tick));
        }
        change.into_iter().collect()
    }

    /// Marks session `i` delivered: an Inform is then complete.
    pub fn delivered(&mut self, i: usize, tick: u64) -> Option<Change> {
        let s = self.sessions.get(i)?;
        if s.kind != SpeechAct::Inform || s.state != State::Open {
            return None;
        }
        let text = s.opening.clone();
        Some(self.moved(i, State::Completed, &text, tick))
    }

    /// Marks session `i` abandoned (its opening message was lost).
    pub fn lost(&mut self, i: usize, tick: u64) -> Option<Change> {
        let s = self.sessions.get(i)?;
        if s.state.closed() {
            return None;
        }
        let text = s.opening.clone();
        Some(self.moved(i, State::Abandoned, &text, tick))
    }

    /// Abandons every open session (the run ended); returns the changes.
    pub fn finish(&mut self, tick: u64) -> Vec<Change> {
        let open: Vec<usize> = self.open.values().flatten().copied().collect();
        let mut open = open;
        open.sort_unstable();
        open.into_iter()
            .filter_map(|i| self.lost(i, tick))
            .collect()
    }

    fn open(&mut self, from: Sym, to: Sym, kind: SpeechAct, text: &str, tick: u64) -> Change {
        let n = self.counts.entry(key(from, to)).or_insert(0);
        *n += 1;
        let i = self.sessions.len();
        self.sessions.push(Session {
            number: *n,
            initiator: from,
            partner: to,
            kind,
            state: State::Open,
            opened: tick,
            answered: None,
            closed: None,
            opening: text.to_string(),
            closing: None,
            latest: text.to_string(),
        });
        self.open.entry(key(from, to)).or_default().push(i);
        Change::Opened(i)
    }

    /// The oldest open session from `initiator` to `partner` that `pred` accepts.
    fn find(&self, initiator: Sym, partner: Sym, pred: impl Fn(&Session) -> bool) -> Option<usize> {
        self.open
            .get(&key(initiator, partner))?
            .iter()
            .copied()
            .find(|&i| pred(&self.sessions[i]))
    }

    fn moved(&mut self, i: usize, to: State, text: &str, tick: u64) -> Change {
        let s = &mut self.sessions[i];
        let from = s.state;
        s.state = to;
        s.latest = text.to_string();
        if to.closed() {
            s.closed = Some(tick);
            s.closing = Some((text.to_string(), tick));
            let k = key(s.initiator, s.partner);
            if let Some(v) = self.open.get_mut(&k) {
                v.retain(|&j| j != i);
                if v.is_empty() {
                    self.open.remove(&k);
                }
            }
        }
        Change::Moved(i, from)
    }

    /// An acknowledgement from `from` (the partner) to `to` (the initiator).
    fn answer(&mut self, from: Sym, to: Sym, a: Answer, text: &str, tick: u64) -> Option<Change> {
        use SpeechAct::*;
        // A table of the answers that fit a session, one row per case: clearer than `matches!`.
        #[allow(clippy::match_like_matches_macro)]
        let fits = |s: &Session| match (a, s.kind, s.state) {
            (Answer::Ok, Request | RequestWhen | Query, State::Open) => true,
            (Answer::Accept | Answer::Refuse, Request | RequestWhen | Offer, State::Open) => true,
            (Answer::Admit, Query, State::Open) => true,
            (Answer::Done | Answer::Failed | Answer::Status, Request, _) => true,
            (Answer::Done | Answer::Failed | Answer::Status, RequestWhen, State::Started) => true,
            (Answer::Status, RequestWhen, _) => true,
            _ => false,
        };
        let Some(i) = self.find(to, from, fits) else {
            if a == Answer::Ok && self.find(to, from, |_| true).is_none() {
                // A plain OK needs no session (it acknowledges an Inform).
                return None;
            }
            return Some(self.violation(from, to, a, text, tick));
        };
        let s = &mut self.sessions[i];
        s.answered.get_or_insert(tick);
        let next = match (a, s.kind) {
            (Answer::Ok | Answer::Admit, Query) => State::Completed,
            (Answer::Ok | Answer::Accept, Offer) => State::Completed,
            (Answer::Ok | Answer::Accept, _) => State::Accepted,
            (Answer::Refuse, _) => State::Refused,
            (Answer::Done, _) => State::Completed,
            (Answer::Failed, _) => State::Failed,
            (Answer::Status, _) if s.state == State::Open => State::Accepted,
            _ => s.state,
        };
        Some(self.moved(i, next, text, tick))
    }

    /// The start signal of a RequestWhen, from the requester `from` to `to`.
    fn signal(&mut self, from: Sym, to: Sym, text: &str, tick: u64) -> Option<Change> {
        let waiting = |s: &Session| {
            s.kind == SpeechAct::RequestWhen && !s.state.closed() && s.state != State::Started
        };
        match self.find(from, to, waiting) {
            Some(i) => Some(self.moved(i, State::Started, text, tick)),
            None => {
                self.violations += 1;
                Some(Change::Violation(format!(
                    "{from} sent the start signal {text} to {to} (tick {tick}), but no requestWhen \
                     from {from} to {to} waits for it{}",
                    self.earlier(from, to)
                )))
            }
        }
    }

    fn violation(&mut self, from: Sym, to: Sym, a: Answer, text: &str, tick: u64) -> Change {
        self.violations += 1;
        let answerable = |k: SpeechAct| match a {
            Answer::Done | Answer::Failed | Answer::Status => {
                matches!(k, SpeechAct::Request | SpeechAct::RequestWhen)
            }
            Answer::Accept | Answer::Refuse => {
                matches!(
                    k,
                    SpeechAct::Request | SpeechAct::RequestWhen | SpeechAct::Offer
                )
            }
            Answer::Admit | Answer::Ok => k == SpeechAct::Query,
        };
        // The conversation this answer most recently ended.
        let answered_before = self
            .sessions
            .iter()
            .filter(|s| {
                s.initiator == to
                    && s.partner == from
                    && s.state.closed()
                    && s.state != State::Abandoned
                    && answerable(s.kind)
            })
            .max_by_key(|s| s.closed);
        let waiting_signal = self
            .find(to, from, |s| s.kind == SpeechAct::RequestWhen)
            .map(|i| &self.sessions[i]);
        let why = if let Some(s) = waiting_signal {
            format!(
                "session {} ({} {}, tick {}) has not had its start signal",
                s.id(),
                s.kind.name(),
                s.opening,
                s.opened
            )
        } else if let Some(s) = answered_before {
            let (by, at) = s.closing.clone().unwrap_or_default();
            format!(
                "double answer: session {} ({} {}) was already answered by {by} (tick {at})",
                s.id(),
                s.kind.name(),
                s.opening
            )
        } else {
            format!(
                "{to} asked {from} nothing that awaits it{}",
                self.earlier(to, from)
            )
        };
        let what = match a {
            Answer::Done | Answer::Failed | Answer::Status => "report",
            Answer::Accept | Answer::Refuse => "acknowledgement",
            Answer::Admit => "answer",
            Answer::Ok => "OK",
        };
        Change::Violation(format!(
            "{from} sent the {what} {text} to {to} (tick {tick}) without an open request: {why}"
        ))
    }

    /// "; the last message from `a` to `b` was ..." when there was one.
    fn earlier(&self, a: Sym, b: Sym) -> String {
        match self.last.get(&key(a, b)) {
            Some((m, t)) => format!("; the last message from {a} to {b} was {m} (tick {t})"),
            None => format!("; {a} never sent {b} a message"),
        }
    }

    /// The figures of the book.
    pub fn stats(&self) -> SessionStats {
        let mut st = SessionStats {
            violations: self.violations,
            ..SessionStats::default()
        };
        let mut waits = 0u64;
        for s in &self.sessions {
            st.opened += 1;
            *st.by_act.entry(s.kind.name().to_string()).or_insert(0) += 1;
            match s.state {
                State::Completed => st.completed += 1,
                State::Refused => st.refused += 1,
                State::Failed => st.failed += 1,
                State::Abandoned => st.abandoned += 1,
                _ => {}
            }
            if let Some(t) = s.answered {
                let w = t.saturating_sub(s.opened);
                st.response_ticks.answered += 1;
                st.response_ticks.max = st.response_ticks.max.max(w);
                waits += w;
            }
        }
        if st.response_ticks.answered > 0 {
            st.response_ticks.mean = waits as f64 / st.response_ticks.answered as f64;
        }
        st
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clamr::act::classify;

    fn say(b: &mut Book, from: &str, to: &str, text: &str, tick: u64) -> Vec<Change> {
        let t = crate::syntax::prolog::Reader::new("t")
            .term(text, 0)
            .expect("term")
            .term;
        b.observe(from.into(), to.into(), &t, &classify(from, &t), tick)
    }

    fn state(b: &Book, i: usize) -> State {
        b.sessions()[i].state
    }

    #[test]
    fn request_accept_report() {
        let mut b = Book::new(true);
        assert_eq!(
            say(&mut b, "r2", "r3", "imp(sense(temperature))", 1),
            vec![Change::Opened(0)]
        );
        say(&mut b, "r3", "r2", "ack(accept, sense(temperature))", 2);
        assert_eq!(state(&b, 0), State::Accepted);
        say(&mut b, "r3", "r2", "ack(done, 25)", 4);
        assert_eq!(state(&b, 0), State::Completed);
        let s = &b.sessions()[0];
        assert_eq!(
            (s.id().as_str(), s.opened, s.answered, s.closed),
            ("r2-1", 1, Some(2), Some(4))
        );
        let c = say(&mut b, "r3", "r2", "ack(done, 25)", 5);
        assert!(
            matches!(&c[0], Change::Violation(v) if v.contains("double answer") && v.contains("imp(sense(temperature))"))
        );
        assert_eq!(b.stats().violations, 1);
    }

    #[test]
    fn report_without_request_is_a_violation() {
        let mut b = Book::new(true);
        let c = say(&mut b, "r3", "r2", "ack(done, 1)", 0);
        assert!(matches!(&c[0], Change::Violation(v) if v.contains("without an open request")));
    }
}
