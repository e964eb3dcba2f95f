//! Message routing: messages collected in a round are delivered for the next round in (sender
//! name, sequence) order; messages to unknown agents are reported, not delivered. Under the
//! routing sits a [`Transport`]: in-process delivery by default, or a simulated network
//! (`clamr::ring`) that may delay or lose messages.

use crate::agent::directory::{position, sym_table};
use crate::agent::Message;
use crate::term::Sym;

/// Routes messages between the agents of a system (index = position in name order). Agents
/// are found by their interned names: a search over integers per message, no text.
#[derive(Clone, Debug)]
pub struct Router {
    index: Vec<(u32, u32)>,
}

impl Router {
    /// A router for agents `names` (index = position).
    pub fn new(names: &[String]) -> Router {
        let syms: Vec<Sym> = names.iter().map(|n| Sym::intern(n)).collect();
        Router {
            index: sym_table(&syms),
        }
    }

    /// The index of agent `name`.
    pub fn index(&self, name: Sym) -> Option<usize> {
        position(&self.index, name)
    }

    /// Appends `sent` (each sender's messages in sending order) to the receivers' inboxes, in
    /// (sender name, sequence) order; returns the messages whose receiver is unknown.
    pub fn route(&self, mut sent: Vec<Message>, inbox: &mut [Vec<Message>]) -> Vec<Message> {
        // Stable: keeps each sender's own sequence. By name, never by symbol id.
        sent.sort_by(|a, b| a.sender.name().cmp(b.sender.name()));
        let mut unknown = Vec::new();
        for m in sent {
            match self.index(m.receiver).and_then(|i| inbox.get_mut(i)) {
                Some(b) => b.push(m),
                None => unknown.push(m),
            }
        }
        unknown
    }
}

/// What a transport did with messages in one round.
#[derive(Debug, Default)]
pub struct Carried {
    /// Messages arriving now (delivered for the next round), in arrival order.
    pub arrived: Vec<Message>,
    /// Messages the transport lost.
    pub lost: Vec<Message>,
    /// What happened on the network worth a warning (e.g. a ring re-formed).
    pub notes: Vec<String>,
}

/// How messages travel between agents.
pub trait Transport: Send {
    /// Takes the round's sent messages (in (sender, sequence) order) at `tick`; returns what
    /// arrives now and what was lost.
    fn carry(&mut self, tick: u64, sent: Vec<Message>) -> Carried;
    /// True while messages are on their way (the run is not idle).
    fn busy(&self) -> bool;
    /// The transport's figures for `--stats`.
    fn stats(&self) -> serde_json::Value;
}

/// In-process delivery: every message arrives at once, in sending order.
#[derive(Debug, Default)]
pub struct InProcess;

impl Transport for InProcess {
    fn carry(&mut self, _tick: u64, sent: Vec<Message>) -> Carried {
        Carried {
            arrived: sent,
            ..Carried::default()
        }
    }
    fn busy(&self) -> bool {
        false
    }
    fn stats(&self) -> serde_json::Value {
        serde_json::json!({"transport": "in-process", "lost": 0})
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::term::Term;

    fn m(s: &str, r: &str, c: &str) -> Message {
        Message {
            sender: s.into(),
            receiver: r.into(),
            content: Term::atom(c),
        }
    }

    #[test]
    fn sender_then_sequence_order_and_unknown_receivers() {
        let router = Router::new(&["a".into(), "b".into(), "c".into()]);
        let mut inbox = vec![Vec::new(); 3];
        let sent = vec![
            m("c", "a", "c1"),
            m("b", "a", "b1"),
            m("c", "a", "c2"),
            m("b", "zed", "lost"),
            m("b", "a", "b2"),
        ];
        let unknown = router.route(sent, &mut inbox);
        let got: Vec<String> = inbox[0].iter().map(|m| m.content.to_string()).collect();
        assert_eq!(got, ["b1", "b2", "c1", "c2"]);
        assert_eq!(unknown, vec![m("b", "zed", "lost")]);
        assert!(inbox[1].is_empty() && inbox[2].is_empty());
    }
}
