//! The mailbox: `received(Sender, Content)` and `sent(Receiver, Content)` facts, and the
//! message type exchanged between agents.

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Subst, Sym, Term};

/// How many facts of a predicate [`Mailbox::delete_matching`] compares before it leaves a
/// delete to the fact base's hash lookup.
const SCAN: usize = 8;

/// True when `pattern` under `s` is the ground term `fact` (walked side by side, nothing built).
fn same_under(s: &Subst, pattern: &Term, fact: &Term) -> bool {
    if pattern.functor() != fact.functor() {
        return false;
    }
    // Messages are small: the walk's stack stays inline.
    let mut work: smallvec::SmallVec<[(&Term, &Term); 16]> = smallvec::smallvec![(pattern, fact)];
    while let Some((p, f)) = work.pop() {
        match (s.walk(p), f) {
            (Term::Var(_), _) => return false,
            (Term::Compound(a), Term::Compound(b)) => {
                if a.name != b.name || a.args.len() != b.args.len() {
                    return false;
                }
                work.extend(a.args.iter().zip(b.args.iter()));
            }
            (a, b) => {
                if a != b {
                    return false;
                }
            }
        }
    }
    true
}

/// A message from one agent to one receiver; `content` already carries the mood wrapper
/// (`p`, `imp(p)` or `int(p)`). Agents are named by their interned names: routing a message
/// compares and looks up symbols, and the text is read only where a name is shown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// Name of the sending agent.
    pub sender: Sym,
    /// Name of the receiving agent.
    pub receiver: Sym,
    /// Mood-wrapped content.
    pub content: Term,
}

/// The mailbox of one agent.
#[derive(Clone, Debug, Default)]
pub struct Mailbox {
    facts: FactBase,
    /// `sent/2` facts of sends in the running combo, not yet in `facts` (each surely new
    /// there): a combo that sends and then deletes its own `sent/2` fact — the usual way to
    /// pass something on — then never touches the fact base for it. Moved into `facts` by
    /// [`Mailbox::settle`] before anything can read the mailbox.
    held: Vec<Term>,
    /// The agent's conversations (their `session/4` facts are among `facts`); `None` when
    /// nothing in the program can see them (`Program::uses_sessions`): then they are not
    /// followed at all, which keeps a long-running agent's mailbox from growing with them.
    pub sessions: Option<crate::clamr::session::Book>,
}

/// True for `received/2` and `sent/2` facts (which insert/delete route to the mailbox).
pub fn is_mail_fact(t: &Term) -> bool {
    t.is_functor(wk::RECEIVED, 2) || t.is_functor(wk::SENT, 2)
}

impl Mailbox {
    /// The facts for queries (callers settle held facts first: see [`Mailbox::settle`]).
    pub fn facts(&self) -> &FactBase {
        debug_assert!(self.held.is_empty(), "mailbox read with held sent/2 facts");
        &self.facts
    }

    /// Adds a mail fact; false when already present.
    pub fn insert(&mut self, fact: Term) -> bool {
        // Held facts come first, so the base keeps the order the facts were added in.
        self.settle();
        self.facts.insert(fact)
    }

    /// Removes a mail fact; false when absent.
    pub fn delete(&mut self, fact: &Term) -> bool {
        if let Some(k) = self.held.iter().position(|h| h == fact) {
            self.held.remove(k);
            return true;
        }
        self.facts.delete(fact)
    }

    /// The stored mail fact `fact` is a variant of: an interrogative message may be open
    /// (`int(at(_, red))`), and a rule deleting it names it with variables.
    pub fn variant_of(&self, fact: &Term) -> Option<Term> {
        let (name, arity) = fact.functor()?;
        self.held
            .iter()
            .chain(self.facts.facts_of(name, arity))
            .find(|f| f.is_variant(fact))
            .cloned()
    }

    /// Removes the mail fact that `pattern` stands for under `s`, found without building it:
    /// a rule deleting the message its condition matched. `None` when `pattern` is no mail
    /// fact held or among the first [`SCAN`] facts of its predicate; the caller then takes the
    /// general way (building the fact, which also reports what is not ground).
    pub fn delete_matching(&mut self, pattern: &Term, s: &Subst) -> Option<Term> {
        if !is_mail_fact(pattern) {
            return None;
        }
        if let Some(k) = self.held.iter().position(|h| same_under(s, pattern, h)) {
            return Some(self.held.remove(k));
        }
        let (name, arity) = pattern.functor()?;
        let f = self
            .facts
            .facts_of(name, arity)
            .take(SCAN)
            .find(|f| same_under(s, pattern, f))?
            .clone();
        self.facts.delete(&f);
        Some(f)
    }

    /// Adds the `sent/2` fact of a send; false when already present. The fact is held back
    /// (not yet in the fact base) while it is surely new: no `sent/2` fact is in the base and
    /// none held is equal. Whoever reads the mailbox calls [`Mailbox::settle`] first.
    pub fn hold_sent(&mut self, fact: Term) -> bool {
        if self.held.contains(&fact) {
            return false;
        }
        if self.facts.has_pred(wk::SENT, 2) {
            self.settle();
            return self.facts.insert(fact);
        }
        self.held.push(fact);
        true
    }

    /// Moves the held `sent/2` facts into the fact base, in the order they were sent.
    pub fn settle(&mut self) {
        for f in std::mem::take(&mut self.held) {
            self.facts.insert(f);
        }
    }

    /// True when the agent already sent `content` to `receiver`.
    pub fn has_sent(&self, receiver: &Term, content: &Term) -> bool {
        let f = sent(receiver, content);
        self.held.contains(&f) || self.facts.contains(&f)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn term(text: &str) -> Term {
        crate::syntax::prolog::Reader::new("t")
            .term(text, 0)
            .expect("term")
            .term
    }

    #[test]
    fn deletes_the_fact_a_pattern_stands_for_without_building_it() {
        let mut mb = Mailbox::default();
        mb.insert(term("received(a, imp(token(1, 5)))"));
        mb.insert(term("received(a, imp(token(2, 5)))"));
        assert!(mb.hold_sent(term("sent(b, imp(token(1, 4)))")));
        let mut s = Subst::new();
        s.bind(Sym::intern("T"), Term::Int(2));
        s.bind(Sym::intern("K"), Term::Int(5));
        let pattern = term("received(a, imp(token(T, K)))");
        assert_eq!(
            mb.delete_matching(&pattern, &s),
            Some(term("received(a, imp(token(2, 5)))"))
        );
        // Gone: the same pattern now finds nothing.
        assert_eq!(mb.delete_matching(&pattern, &s), None);
        s.bind(Sym::intern("R"), Term::Int(4));
        let held = term("sent(b, imp(token(1, R)))");
        assert_eq!(
            mb.delete_matching(&held, &s),
            Some(term("sent(b, imp(token(1, 4)))"))
        );
        mb.settle();
        assert_eq!(mb.facts().len(), 1);
        // An unbound variable or a fact of another kind: left to the general way.
        let open = term("received(a, imp(token(1, X)))");
        assert_eq!(mb.delete_matching(&open, &s), None);
        assert_eq!(mb.delete_matching(&term("at(a)"), &s), None);
        assert_eq!(mb.facts().len(), 1);
    }
}
