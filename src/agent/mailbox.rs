//! The mailbox: `received(Sender, Content)` and `sent(Receiver, Content)` facts, and the
//! message type exchanged between agents.

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Term};

/// A message from one agent to one receiver; `content` already carries the mood wrapper
/// (`p`, `imp(p)` or `int(p)`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// Name of the sending agent.
    pub sender: String,
    /// Name of the receiving agent.
    pub receiver: String,
    /// Mood-wrapped content.
    pub content: Term,
}

/// The mailbox of one agent.
#[derive(Clone, Debug, Default)]
pub struct Mailbox {
    facts: FactBase,
    /// The agent's conversations (their `session/4` facts are among `facts`).
    pub sessions: crate::clamr::session::Book,
}

/// True for `received/2` and `sent/2` facts (which insert/delete route to the mailbox).
pub fn is_mail_fact(t: &Term) -> bool {
    t.is_functor(wk::RECEIVED, 2) || t.is_functor(wk::SENT, 2)
}

impl Mailbox {
    /// The facts for queries.
    pub fn facts(&self) -> &FactBase {
        &self.facts
    }

    /// Adds a mail fact; false when already present.
    pub fn insert(&mut self, fact: Term) -> bool {
        self.facts.insert(fact)
    }

    /// Removes a mail fact; false when absent.
    pub fn delete(&mut self, fact: &Term) -> bool {
        self.facts.delete(fact)
    }

    /// True when the agent already sent `content` to `receiver`.
    pub fn has_sent(&self, receiver: &Term, content: &Term) -> bool {
        self.facts.contains(&sent(receiver, content))
    }
}

/// `sent(Receiver, Content)`.
pub fn sent(receiver: &Term, content: &Term) -> Term {
    Term::compound(wk::SENT, vec![receiver.clone(), content.clone()])
}

/// `received(Sender, Content)`.
pub fn received(sender: &Term, content: &Term) -> Term {
    Term::compound(wk::RECEIVED, vec![sender.clone(), content.clone()])
}
