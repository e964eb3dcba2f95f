//! The mailbox: `received(Sender, Content)` and `sent(Receiver, Content)` facts, and the
//! message type exchanged between agents.

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Subst, Sym, Term};

/// How many facts of a predicate [`Mailbox::delete_matching`] compares before it leaves a
/// delete to the fact base's hash lookup.
const SCAN: usize = 8;

/// True when `pattern` under `s` is the ground term `fact` (walked side by side, nothing built).
fn same_under(s: &Subst, pattern: &Term, fact: &Term) -> bool {
    // Messages are small: the walk's stack stays inline. The walk goes down the first argument
    // of each compound at once and stacks only the others (most have one or two), and shared
    // sub-terms are equal without a look inside.
    let mut work: smallvec::SmallVec<[(&Term, &Term); 8]> = smallvec::SmallVec::new();
    let (mut p, mut f) = (pattern, fact);
    loop {
        match (s.walk(p), f) {
            (Term::Var(_), _) => return false,
            (Term::Compound(a), Term::Compound(b)) if !std::sync::Arc::ptr_eq(a, b) => {
                if a.name != b.name || a.args.len() != b.args.len() {
                    return false;
                }
                for k in (1..a.args.len()).rev() {
                    work.push((&a.args[k], &b.args[k]));
                }
                // Compounds have at least one argument.
                if let (Some(x), Some(y)) = (a.args.first(), b.args.first()) {
                    (p, f) = (x, y);
                    continue;
                }
            }
            (Term::Compound(_), Term::Compound(_)) => {}
            // Atoms and integers, nearly every leaf of a message, compared in place.
            (Term::Atom(a), Term::Atom(b)) if a != b => return false,
            (Term::Int(a), Term::Int(b)) if a != b => return false,
            (Term::Atom(_), Term::Atom(_)) | (Term::Int(_), Term::Int(_)) => {}
            (a, b) => {
                if a != b {
                    return false;
                }
            }
        }
        match work.pop() {
            Some((x, y)) => (p, f) = (x, y),
            None => return true,
        }
    }
}

/// A mail fact [`Mailbox::delete_matching`] removed; a held `sent/2` fact is built only when
/// someone asks for it (a trace, a watcher).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Deleted {
    /// A fact of the fact base.
    Fact(Term),
    /// A held `sent(receiver, content)`.
    Sent(Sym, Term),
}

impl Deleted {
    /// The fact as a term.
    pub fn term(self) -> Term {
        match self {
            Deleted::Fact(f) => f,
            Deleted::Sent(r, c) => sent(&Term::Atom(r), &c),
        }
    }
}

/// True when `fact` is the held `sent(receiver, content)`.
fn is_held((r, c): &(Sym, Term), fact: &Term) -> bool {
    fact.is_functor(wk::SENT, 2) && fact.args()[0] == Term::Atom(*r) && fact.args()[1] == *c
}

/// True when `pattern` under `s` is the held `sent(receiver, content)`.
fn held_under(s: &Subst, pattern: &Term, (r, c): &(Sym, Term)) -> bool {
    pattern.is_functor(wk::SENT, 2)
        && *s.walk(&pattern.args()[0]) == Term::Atom(*r)
        && same_under(s, &pattern.args()[1], c)
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
    /// `sent/2` facts of sends in the running combo as (receiver, content), not yet in `facts`
    /// (each surely new there): a combo that sends and then deletes its own `sent/2` fact —
    /// the usual way to pass something on — then neither builds the fact nor touches the fact
    /// base for it. Moved into `facts` by [`Mailbox::settle`] before anything can read the
    /// mailbox.
    held: Vec<(Sym, Term)>,
    /// The agent's conversations (their `session/4` facts are among `facts`); `None` when
    /// nothing in the program can see them (`Program::uses_sessions`): then they are not
    /// followed at all, which keeps a long-running agent's mailbox from growing with them.
    pub sessions: Option<crate::clamr::session::Book>,
}

/// True for `received/2` and `sent/2` facts (which insert/delete route to the mailbox).
pub fn is_mail_fact(t: &Term) -> bool {
    t.is_functor(wk::RECEIVED, 2) || t.is_functor(wk::SENT, 2)
}

/// True for the predicates whose facts the mailbox holds: `received/2`, `sent/2` and the
/// conversations' `session/4`.
pub fn is_mail_predicate(name: Sym, arity: usize) -> bool {
    matches!((name, arity), (wk::RECEIVED | wk::SENT, 2))
        || (arity == 4 && name.name() == "session")
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
        if let Some(k) = self.held.iter().position(|h| is_held(h, fact)) {
            self.held.remove(k);
            return true;
        }
        self.facts.delete(fact)
    }

    /// The stored mail fact `fact` is a variant of: an interrogative message may be open
    /// (`int(at(_, red))`), and a rule deleting it names it with variables.
    pub fn variant_of(&self, fact: &Term) -> Option<Term> {
        let (name, arity) = fact.functor()?;
        let held = self.held.iter().map(|(r, c)| sent(&Term::Atom(*r), c));
        held.chain(self.facts.facts_of(name, arity).cloned())
            .find(|f| f.is_variant(fact))
    }

    /// Removes the mail fact that `pattern` stands for under `s`, found without building it:
    /// a rule deleting the message its condition matched. `None` when `pattern` is no mail
    /// fact held or among the first [`SCAN`] facts of its predicate; the caller then takes the
    /// general way (building the fact, which also reports what is not ground).
    pub fn delete_matching(&mut self, pattern: &Term, s: &Subst) -> Option<Deleted> {
        if !is_mail_fact(pattern) {
            return None;
        }
        if let Some(k) = self.held.iter().position(|h| held_under(s, pattern, h)) {
            let (r, c) = self.held.remove(k);
            return Some(Deleted::Sent(r, c));
        }
        let (name, arity) = pattern.functor()?;
        let f = self
            .facts
            .facts_of(name, arity)
            .take(SCAN)
            .find(|f| same_under(s, pattern, f))?
            .clone();
        self.facts.delete(&f);
        Some(Deleted::Fact(f))
    }

    /// Adds the fact `sent(receiver, content)` of a send; false when already present. The
    /// fact is held back (not built, not yet in the fact base) while it is surely new: no
    /// `sent/2` fact is in the base and none held is equal. Whoever reads the mailbox calls
    /// [`Mailbox::settle`] first.
    pub fn hold_sent(&mut self, receiver: Sym, content: Term) -> bool {
        if self
            .held
            .iter()
            .any(|(r, c)| *r == receiver && *c == content)
        {
            return false;
        }
        if self.facts.has_pred(wk::SENT, 2) {
            self.settle();
            return self.facts.insert(sent(&Term::Atom(receiver), &content));
        }
        self.held.push((receiver, content));
        true
    }

    /// Moves the held `sent/2` facts into the fact base, in the order they were sent.
    pub fn settle(&mut self) {
        // Drained, not taken: the buffer is kept for the next combo's sends.
        for (r, c) in self.held.drain(..) {
            self.facts.insert(sent(&Term::Atom(r), &c));
        }
    }

    /// True when the agent already sent `content` to `receiver`.
    pub fn has_sent(&self, receiver: &Term, content: &Term) -> bool {
        let f = sent(receiver, content);
        self.held.iter().any(|h| is_held(h, &f)) || self.facts.contains(&f)
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
        assert!(mb.hold_sent(Sym::intern("b"), term("imp(token(1, 4))")));
        assert!(!mb.hold_sent(Sym::intern("b"), term("imp(token(1, 4))")));
        assert!(mb.has_sent(&term("b"), &term("imp(token(1, 4))")));
        let mut s = Subst::new();
        s.bind(Sym::intern("T"), Term::Int(2));
        s.bind(Sym::intern("K"), Term::Int(5));
        // Another sender (an atom differs) or another token (an integer differs): no match.
        assert_eq!(
            mb.delete_matching(&term("received(b, imp(token(T, K)))"), &s),
            None
        );
        assert_eq!(
            mb.delete_matching(&term("received(a, imp(token(T, 6)))"), &s),
            None
        );
        let pattern = term("received(a, imp(token(T, K)))");
        assert_eq!(
            mb.delete_matching(&pattern, &s).map(Deleted::term),
            Some(term("received(a, imp(token(2, 5)))"))
        );
        // Gone: the same pattern now finds nothing.
        assert_eq!(mb.delete_matching(&pattern, &s), None);
        s.bind(Sym::intern("R"), Term::Int(4));
        let held = term("sent(b, imp(token(1, R)))");
        assert_eq!(
            mb.delete_matching(&held, &s).map(Deleted::term),
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

    #[test]
    fn deep_messages_are_compared_to_the_bottom() {
        let deep = |x: &str| {
            let mut t = x.to_string();
            for _ in 0..24 {
                t = format!("f({t}, g)");
            }
            term(&format!("received(a, {t})"))
        };
        let mut mb = Mailbox::default();
        mb.insert(deep("1"));
        let mut s = Subst::new();
        s.bind(Sym::intern("X"), Term::Int(2));
        // A difference at the bottom, then a match there.
        assert_eq!(mb.delete_matching(&deep("X"), &s), None);
        s = Subst::new();
        s.bind(Sym::intern("X"), Term::Int(1));
        assert_eq!(
            mb.delete_matching(&deep("X"), &s).map(Deleted::term),
            Some(deep("1"))
        );
        assert_eq!(mb.facts().len(), 0);
    }
}
