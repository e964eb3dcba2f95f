//! Sending messages: receivers by selector, mood wrapping, `sent/2` bookkeeping, `sendonce`;
//! and receiving them into `received/2`.

use super::action::Outcome;
use super::condition::show_subst;
use super::cycle::Core;
use super::error::Fault;
use super::mailbox::{received, sent, Message};
use super::mental_state::MentalState;
use super::program::{Act, ActionDef, Receivers};
use super::timing::CHANNEL;
use super::trace::{Event, TraceLevel};
use crate::syntax::ast::Mood;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::SmallVec;

/// Wraps content in its mood: `p`, `imp(p)` or `int(p)`.
pub fn wrap_mood(mood: Mood, content: Term) -> Term {
    match mood {
        Mood::Declarative => content,
        Mood::Imperative => Term::compound(wk::IMP, vec![content]),
        Mood::Interrogative => Term::compound(wk::INT, vec![content]),
    }
}

/// Agent names; a send's usual one receiver stays inline (no allocation per send).
pub type Names = SmallVec<[Sym; 2]>;

/// The agent names that the terms `ts` of a selector stand for under `s` (atoms, strings and
/// lists of them); an unbound variable is an error.
pub fn agent_names(ts: &[Term], s: &Subst) -> Result<Names, Fault> {
    // The usual selector, one name (`(Next).send(...)`), without building a work list.
    if let [t] = ts {
        match s.walk(t) {
            Term::Atom(a) if *a == wk::NIL => return Ok(Names::new()),
            Term::Atom(a) => return Ok(smallvec::smallvec![*a]),
            _ => {}
        }
    }
    let mut work: Vec<Term> = ts.iter().rev().map(|t| s.apply(t)).collect();
    let mut names = Names::new();
    while let Some(t) = work.pop() {
        match &t {
            Term::Atom(a) if *a != wk::NIL => names.push(*a),
            Term::Atom(_) => {}
            Term::Str(x) => names.push(Sym::intern(x)),
            Term::Compound(_) if t.is_cons() => {
                if let Some(items) = t.list_items() {
                    work.extend(items.into_iter().rev());
                }
            }
            Term::Var(v) => {
                return Err(Fault {
                    message: format!("variable {} in selector not bound", v.name()),
                    binding: Some(show_subst(s)),
                })
            }
            _ => return Err(Fault::new(format!("{t} does not name an agent"))),
        }
    }
    Ok(names)
}

/// Pattern nesting up to which [`atomic_instance`] builds a message's content.
pub(super) const CONTENT_DEPTH: u32 = 32;

/// The content a send of `content` with `mood` sends under `s`: instantiated, checked ground
/// (but for a question) and valid in the content language (`clamr::content::validate`), and
/// wrapped in its mood.
#[cfg(test)]
pub(super) fn message_content(mood: Mood, content: &Term, s: &Subst) -> Result<Term, Fault> {
    built_content(mood, content, s).map(|(c, _)| c)
}

/// [`message_content`] with whether it was built by [`atomic_instance`] (so its size is the
/// pattern's, and worth keeping as the agent's spare: see `spare.rs`).
fn built_content(mood: Mood, content: &Term, s: &Subst) -> Result<(Term, bool), Fault> {
    let mut suspect = false;
    let (c, checked, atomic) = match atomic_instance(s, content, CONTENT_DEPTH, &mut suspect) {
        // Ground by construction; and `validate` can only reject a message at a compound whose
        // functor `may_reject` names: the instance's compounds are the pattern's own (the
        // mood's wrapper is none of them), so without a suspect one it passes as it is.
        Some((c, _)) => (c, !suspect, true),
        None => {
            let c = s.apply(content);
            if mood != Mood::Interrogative && !c.is_ground() {
                return Err(Fault {
                    message: format!("message content {c} is not ground"),
                    binding: Some(show_subst(s)),
                });
            }
            (c, false, false)
        }
    };
    let wrapped = wrap_mood(mood, c);
    if !checked {
        crate::clamr::content::validate(&wrapped).map_err(|e| Fault {
            message: format!("message content: {e}"),
            binding: Some(show_subst(s)),
        })?;
    }
    Ok((wrapped, atomic))
}

/// The content a send of `content` with `mood` sends under `s` ([`message_content`]), written
/// over the agent's spare content when it can be (see `spare.rs`); the result is kept as the
/// next spare when it has the pattern's size.
fn content_for(ms: &mut MentalState, mood: Mood, content: &Term, s: &Subst) -> Result<Term, Fault> {
    let reused = ms
        .mailbox
        .take_spare()
        .and_then(|spare| super::spare::refilled(mood, content, s, spare));
    let (wrapped, keep) = match reused {
        Some(w) => (w, true),
        None => built_content(mood, content, s)?,
    };
    if keep && matches!(wrapped, Term::Compound(_)) {
        ms.mailbox.keep_spare(wrapped.clone());
    }
    Ok(wrapped)
}

/// `t` under `s` with whether it differs from `t`, when each variable in it is bound to an
/// atomic term and it nests at most `depth` deep (the usual message: `token(T, R)`); `None`
/// otherwise (the caller applies `s` the general way). Sets `suspect` on meeting a compound
/// that content validation may reject. Unchanged arguments are shared, as `Subst::apply` does.
pub(super) fn atomic_instance(
    s: &Subst,
    t: &Term,
    depth: u32,
    suspect: &mut bool,
) -> Option<(Term, bool)> {
    match t {
        Term::Var(_) => Some((atomic_value(s, t)?, true)),
        Term::Compound(_) if depth == 0 => None,
        Term::Compound(c) => {
            *suspect |= crate::clamr::content::may_reject(c.name);
            let mut args: Option<Vec<Term>> = None;
            for (i, a) in c.args.iter().enumerate() {
                // The argument's instance when it differs from the argument. Leaves are taken
                // here, without a call per argument (a message's arguments are mostly leaves).
                let x = match a {
                    Term::Var(_) => Some(atomic_value(s, a)?),
                    Term::Compound(_) => match atomic_instance(s, a, depth - 1, suspect)? {
                        (x, true) => Some(x),
                        (_, false) => None,
                    },
                    _ => None,
                };
                match (x, args.as_mut()) {
                    (Some(x), Some(v)) => v.push(x),
                    (None, Some(v)) => v.push(a.clone()),
                    (Some(x), None) => {
                        let mut v = Vec::with_capacity(c.args.len());
                        v.extend(c.args[..i].iter().cloned());
                        v.push(x);
                        args = Some(v);
                    }
                    (None, None) => {}
                }
            }
            Some(match args {
                Some(v) => (Term::compound(c.name, v), true),
                None => (t.clone(), false),
            })
        }
        other => Some((other.clone(), false)),
    }
}

/// The value of variable `v` under `s` when it is bound to an atomic term; `None` otherwise.
pub(super) fn atomic_value(s: &Subst, v: &Term) -> Option<Term> {
    match s.walk(v) {
        Term::Var(_) | Term::Compound(_) => None,
        x => Some(x.clone()),
    }
}

/// True when the `sent/2` fact this send held (if it held one) is, under `s`, the instance of
/// `sent(R, M)` for its one receiver term `R` and its mood-wrapped content pattern `M` (the form
/// [`link_sent_deletes`] looks for): `R` stands for one atom (not a list, not `[]`), so the
/// send had at most that one receiver, and the content is ground, as a `delete`'s match needs.
fn names_its_sent_fact(to: &Receivers, s: &Subst, mood: Mood, wrapped: &Term) -> bool {
    let one = matches!(to, Receivers::Agents(ts) if ts.len() == 1
        && matches!(s.walk(&ts[0]), Term::Atom(a) if *a != wk::NIL));
    // Only a question may be sent with variables (`message_content`).
    one && (mood != Mood::Interrogative || wrapped.is_ground())
}

/// Links each `delete` of a combo whose pattern is, by its form, `sent(R, M)` for the nearest
/// earlier send of the combo, sent to the one term `R` with content `C` and `M` the mood-wrapped
/// `C` (`(Next).send(!token(T, R)) + delete(sent(Next, imp(token(T, R))))`).
///
/// Why the mark the send leaves then finds the fact exactly: a combo's actions run in order
/// under one substitution `s`, so the delete's pattern under `s` is `sent(R·s, wrap(C·s))`, the
/// fact the send held when it held one ([`names_its_sent_fact`]); no other send runs between
/// them (it is the nearest), every send forgets the mark first, and any change to the held
/// facts after the mark (a delete of one, a settle before another action or a module call)
/// makes it stale, so a valid mark is that fact at that position. Held facts are distinct, so
/// matching would have found that one. Without a valid mark the delete matches as before.
pub fn link_sent_deletes(actions: &mut [ActionDef]) {
    let mut last_send: Option<Term> = None;
    for a in actions.iter_mut() {
        match &mut a.kind {
            Act::Send {
                to: Receivers::Agents(ts),
                mood,
                content,
                ..
            } if ts.len() == 1 => {
                last_send = Some(sent(&ts[0], &wrap_mood(*mood, content.clone())));
            }
            Act::Send { .. } => last_send = None,
            Act::Delete(d) => d.of_send = last_send.as_ref() == Some(&d.fact),
            _ => {}
        }
    }
}

impl Core {
    /// The receiver names of a selector under `s`.
    fn receivers(&self, to: &Receivers, s: &Subst) -> Result<Names, Fault> {
        Ok(match to {
            Receivers::All => self.known.syms().iter().copied().collect(),
            Receivers::AllOther => self
                .known
                .syms()
                .iter()
                .copied()
                .filter(|n| *n != self.me)
                .collect(),
            Receivers::SelfAgent => smallvec::smallvec![self.me],
            Receivers::Agents(ts) => agent_names(ts, s)?,
        })
    }

    /// `send` / `sendonce`; with `channels`, a receiver name that is no agent is a channel.
    pub fn send(
        &mut self,
        to: &Receivers,
        mood: Mood,
        content: &Term,
        once: bool,
        channels: bool,
        s: &Subst,
    ) -> Result<Outcome, Fault> {
        let wrapped = content_for(&mut self.ms, mood, content, s)?;
        self.ms.mailbox.unmark_sent();
        let record = self.level >= TraceLevel::Changes;
        let mut ev = Vec::new();
        for r in self.receivers(to, s)? {
            let known = self.known.knows(r);
            if !known && channels {
                self.send_to_channel(r, &wrapped, &mut ev);
                continue;
            }
            if !known {
                ev.push(Event::Warning {
                    message: format!("message {wrapped} to unknown agent {r} dropped"),
                });
                continue;
            }
            let rt = Term::Atom(r);
            if once && self.ms.mailbox.has_sent(&rt, &wrapped) {
                continue;
            }
            self.converse(self.me, r, &wrapped);
            if record {
                ev.push(Event::MessageSent {
                    to: rt.to_string(),
                    content: wrapped.to_string(),
                });
            }
            self.out.messages.push(Message {
                sender: self.me,
                receiver: r,
                content: wrapped.clone(),
            });
            // Held back while the combo runs: a `delete` of it later in the combo then costs
            // nothing (see `Mailbox::hold_sent`).
            if self.ms.mailbox.hold_sent(r, wrapped.clone()) && record {
                ev.push(Event::MailAdded {
                    fact: sent(&rt, &wrapped).to_string(),
                });
            }
        }
        if !names_its_sent_fact(to, s, mood, &wrapped) {
            self.ms.mailbox.unmark_sent();
        }
        for e in ev {
            self.event(e);
        }
        let name = if once { "sendonce" } else { "send" };
        self.done_with(|| Term::compound(name, vec![wrapped]));
        self.check_goals()?;
        Ok(Outcome::Done { real: true })
    }

    /// A message to channel `c`: sent to every agent marked with the channel; each keeps it
    /// only when subscribed (`timing.rs`), so the sender needs no one's subscriptions.
    fn send_to_channel(&mut self, c: Sym, wrapped: &Term, ev: &mut Vec<Event>) {
        if self.level >= TraceLevel::Changes {
            ev.push(Event::MessageSent {
                to: c.name().to_string(),
                content: wrapped.to_string(),
            });
        }
        let marked = Term::compound(CHANNEL, vec![Term::Atom(c), wrapped.clone()]);
        for &r in self.known.syms() {
            self.out.messages.push(Message {
                sender: self.me,
                receiver: r,
                content: marked.clone(),
            });
        }
    }

    /// Follows the conversation a message from `from` to `to` belongs to, keeping the
    /// `session/4` facts in the mailbox up to date (no trace events: runtime bookkeeping).
    fn converse(&mut self, from: Sym, to: Sym, content: &Term) {
        use crate::clamr::session::Change;
        let Some(book) = self.ms.mailbox.sessions.as_mut() else {
            return;
        };
        let act = crate::clamr::classify(from.name(), content);
        let changes = book.observe(from, to, content, &act, 0);
        for c in changes {
            let (i, old) = match c {
                Change::Opened(i) => (i, None),
                Change::Moved(i, old) => (i, Some(old)),
                Change::Violation(_) => continue,
            };
            let Some(s) = self.ms.mailbox.sessions.as_ref().and_then(|b| b.get(i)) else {
                continue;
            };
            let new = s.fact(self.me);
            let old = old.map(|state| {
                let mut was = s.clone();
                was.state = state;
                was.fact(self.me)
            });
            if let Some(f) = old {
                self.ms.mailbox.delete(&f);
            }
            self.ms.mailbox.insert(new);
        }
    }

    /// Stores incoming messages as `received(Sender, Content)` and updates the senders' mental
    /// models; true when there were any.
    pub fn receive(&mut self, messages: &[Message]) -> Result<bool, Fault> {
        let record = self.level >= TraceLevel::Changes;
        let mut ev = Vec::new();
        for m in messages {
            // A channel message counts only when this agent subscribed to the channel.
            let Some(content) = self.timing.accept(&m.content) else {
                continue;
            };
            self.ms.update_model(m.sender, &content)?;
            self.converse(m.sender, m.receiver, &content);
            let sender = Term::Atom(m.sender);
            if record {
                let f = received(&sender, &content);
                if self.ms.mailbox.receive(sender, content) {
                    ev.push(Event::MailAdded {
                        fact: f.to_string(),
                    });
                }
            } else {
                self.ms.mailbox.receive(sender, content);
            }
        }
        if !ev.is_empty() {
            self.changes(ev);
        }
        Ok(!messages.is_empty())
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::agent::mailbox::tests::term;

    /// A substitution binding each `(variable, term text)`.
    pub(in crate::agent) fn subst(pairs: &[(&str, &str)]) -> Subst {
        let mut s = Subst::new();
        for (v, t) in pairs {
            s.bind(Sym::intern(v), term(t));
        }
        s
    }

    /// The content the general way: apply, check ground (but for a question), wrap, validate.
    fn general(mood: Mood, content: &Term, s: &Subst) -> Result<Term, String> {
        let c = s.apply(content);
        if mood != Mood::Interrogative && !c.is_ground() {
            return Err(format!("message content {c} is not ground"));
        }
        let wrapped = wrap_mood(mood, c);
        crate::clamr::content::validate(&wrapped).map_err(|e| format!("message content: {e}"))?;
        Ok(wrapped)
    }

    #[test]
    fn message_content_is_the_general_instance_checked_the_same_way() {
        let s = subst(&[
            ("T", "1"),
            ("R", "4"),
            ("A", "foo"),
            ("U", "T"),
            ("G", "greater(foo)"),
            ("L", "[a, b]"),
            ("N", "-3"),
        ]);
        let moods = [Mood::Declarative, Mood::Imperative, Mood::Interrogative];
        let cases = [
            "token(T, R)",
            "token(U, f(R, [A]))",
            "p",
            // Forms validation rejects, with atomic values bound inside them.
            "greater(A)",
            "f(g(range(R, T)))",
            "when(go, N)",
            "ack(A, T)",
            "ack(accept, T)",
            // Values that are compounds or unbound: the general way.
            "f(G)",
            "f(L)",
            "token(T, X)",
            "X",
        ];
        for text in cases {
            for mood in moods {
                let got = message_content(mood, &term(text), &s).map_err(|f| f.message);
                let want = general(mood, &term(text), &s);
                assert_eq!(got, want, "{text} as {mood:?}");
            }
        }
        // Some of them pass and some fail each way.
        let passes = |text: &str| message_content(Mood::Declarative, &term(text), &s).is_ok();
        assert!(passes("token(T, R)") && passes("ack(accept, T)"));
        assert!(!passes("greater(A)") && !passes("ack(A, T)") && !passes("token(T, X)"));
        assert!(!passes("f(g(range(R, T)))") && !passes("when(go, N)") && !passes("f(G)"));
    }

    /// Which deletes of the combo `text` (actions joined by `+`) [`link_sent_deletes`] links.
    fn linked(text: &str) -> Vec<bool> {
        let src = format!("main module {{ program {{ if true then {text}. }} }}");
        let prog = crate::agent::program::Program::from_source("t.goal", &src).expect("program");
        let rule = prog.blocks.iter().flat_map(|b| &b.rules).next();
        let Some(crate::agent::program::Body::Combo(acts)) = rule.map(|r| &r.body) else {
            panic!("a combo")
        };
        acts.iter()
            .filter_map(|a| match &a.kind {
                Act::Delete(d) => Some(d.of_send),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn a_delete_is_linked_to_the_nearest_send_of_its_sent_fact_only() {
        let ring = "(N).send(!token(T, R)) + delete(received(S, imp(token(T, K)))) \
                    + delete(sent(N, imp(token(T, R))))";
        assert_eq!(linked(ring), [false, true]);
        // A nested argument, the mood, the receiver or the predicate differs.
        assert_eq!(
            linked("(N).send(!t(T, R)) + delete(sent(N, imp(t(T, K))))"),
            [false]
        );
        assert_eq!(
            linked("(N).send(?t(T)) + delete(sent(N, imp(t(T))))"),
            [false]
        );
        assert_eq!(linked("(N).send(t) + delete(sent(M, t))"), [false]);
        assert_eq!(linked("(N).send(t) + delete(received(N, t))"), [false]);
        // Another send between, or one with more receivers: no link.
        assert_eq!(
            linked("(N).send(t) + (M).send(u) + delete(sent(N, t))"),
            [false]
        );
        assert_eq!(
            linked("(N).send(t) + all.send(t) + delete(sent(N, t))"),
            [false]
        );
        assert_eq!(linked("(N, M).send(t) + delete(sent(N, t))"), [false]);
        // Each delete after the send, and a plain (declarative) one.
        assert_eq!(
            linked("(N).send(t) + delete(sent(N, t)) + delete(sent(N, t))"),
            [true, true]
        );
    }

    #[test]
    fn message_content_shares_what_the_substitution_leaves_alone() {
        let s = subst(&[("T", "1")]);
        let pattern = term("f(g(a), T, h(b))");
        let got = message_content(Mood::Declarative, &pattern, &s).expect("valid");
        assert_eq!(got, term("f(g(a), 1, h(b))"));
        let shared = |k: usize| match (&got.args()[k], &pattern.args()[k]) {
            (Term::Compound(a), Term::Compound(b)) => std::sync::Arc::ptr_eq(a, b),
            _ => false,
        };
        assert!(shared(0) && shared(2));
        // Nothing bound in it: the pattern itself.
        let ground = term("f(g(a))");
        match (message_content(Mood::Declarative, &ground, &s), &ground) {
            (Ok(Term::Compound(a)), Term::Compound(b)) => assert!(std::sync::Arc::ptr_eq(&a, b)),
            other => panic!("{other:?}"),
        }
    }
}
