//! The mailbox: `received(Sender, Content)` and `sent(Receiver, Content)` facts, and the
//! message type exchanged between agents.

use super::kr_bridge::FactBase;
use crate::term::{well_known as wk, Subst, Sym, Term};

/// How many facts of a predicate [`Mailbox::delete_matching`] compares before it leaves a
/// delete to the fact base's hash lookup.
const SCAN: usize = 8;

/// Most `received/2` facts kept aside in [`Mailbox::arrived`]; more go into the fact base.
const ARRIVED: usize = 8;

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
    /// An arrived `received(sender, content)`.
    Received(Term, Term),
}

impl Deleted {
    /// The fact as a term.
    pub fn term(self) -> Term {
        match self {
            Deleted::Fact(f) => f,
            Deleted::Sent(r, c) => sent(&Term::Atom(r), &c),
            Deleted::Received(s, c) => Term::compound(wk::RECEIVED, vec![s, c]),
        }
    }
}

/// Removes item `k` of `v`, keeping the order of the rest: the usual one held fact, the
/// last, is popped without a general remove.
fn take_at<T>(v: &mut Vec<T>, k: usize) -> T {
    if k + 1 == v.len() {
        if let Some(x) = v.pop() {
            return x;
        }
    }
    v.remove(k)
}

/// True when `fact` is the held `sent(receiver, content)`.
fn is_held((r, c): &(Sym, Term), fact: &Term) -> bool {
    fact.is_functor(wk::SENT, 2) && fact.args()[0] == Term::Atom(*r) && fact.args()[1] == *c
}

/// True when `pattern` under `s` is the held `sent(receiver, content)`.
fn held_under(s: &Subst, pattern: &Term, (r, c): &(Sym, Term)) -> bool {
    pattern.is_functor(wk::SENT, 2)
        && matches!(s.walk(&pattern.args()[0]), Term::Atom(a) if a == r)
        && same_under(s, &pattern.args()[1], c)
}

/// Most messages a message buffer kept for reuse may have room for: the buffers of messages
/// passed on circulate (an agent's outgoing buffer becomes a receiver's inbox, an emptied inbox
/// the agent's next outgoing buffer), and a larger one (a broadcast's) is freed instead.
const REUSED_ROOM: usize = 16;

/// True when `buffer` is worth keeping for reuse: it has room, and not a broadcast's.
pub fn reusable(buffer: &Vec<Message>) -> bool {
    (1..=REUSED_ROOM).contains(&buffer.capacity())
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
    /// Changes of `held` so far (push, take, settle): a mark taken after a change is valid
    /// while the count stays the same.
    held_edits: u64,
    /// Where the last send left its held fact: `(held_edits, position in held)` just after the
    /// push (see [`Mailbox::mark_sent`] and [`Mailbox::delete_matching`]).
    sent_mark: Option<(u64, usize)>,
    /// The content of the agent's last send, kept so that the next send may write its own
    /// over it (see `spare.rs`).
    spare: Option<Term>,
    /// The `received(Sender, Content)` facts of messages that arrived this cycle, as their
    /// arguments, in arrival order, not yet in `facts` (each surely new there, at most
    /// [`ARRIVED`]): an agent that reads a message by a condition plan and deletes it in the
    /// same cycle — the usual way to handle one — then neither builds the fact nor hashes it
    /// into the fact base's indexes. Plans read them directly ([`Mailbox::arrived`]), the
    /// engine through [`Mailbox::arrived_base`]; moved into `facts` by [`Mailbox::settle`] in
    /// arrival order, before the held `sent/2` facts (sent later).
    arrived: Vec<[Term; 2]>,
    /// `arrived` as a fact base, built only when a reader needs one (a query the engine
    /// answers) and dropped whenever `arrived` changes.
    arrived_base: std::sync::OnceLock<FactBase>,
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

/// Received facts a reader takes beside a list of fact bases: the `received/2` facts of
/// `received`, read right after the base at position `after` of the list (the mailbox's own
/// base).
#[derive(Clone, Copy, Debug, Default)]
pub struct Arrived<'a> {
    /// The facts' arguments (sender, content), in arrival order.
    pub received: &'a [[Term; 2]],
    /// The position of the base they follow.
    pub after: usize,
}

impl Mailbox {
    /// All facts, for readers that list the mailbox (callers settle first: see
    /// [`Mailbox::settle`]).
    pub fn facts(&self) -> &FactBase {
        debug_assert!(
            self.arrived.is_empty(),
            "mailbox read with arrived facts aside"
        );
        self.stored()
    }

    /// The fact base without the facts kept aside, for readers that also read
    /// [`Mailbox::arrived`] or [`Mailbox::arrived_base`] (held `sent/2` facts are settled
    /// before any read).
    pub fn stored(&self) -> &FactBase {
        debug_assert!(self.held.is_empty(), "mailbox read with held sent/2 facts");
        &self.facts
    }

    /// The arguments (sender, content) of the `received/2` facts of this cycle not yet in
    /// [`Mailbox::stored`], in arrival order.
    pub fn arrived(&self) -> &[[Term; 2]] {
        &self.arrived
    }

    /// [`Mailbox::arrived`] as a fact base (for the engine), built on first use after a change.
    pub fn arrived_base(&self) -> &FactBase {
        self.arrived_base.get_or_init(|| {
            let mut base = FactBase::new();
            for [sender, content] in &self.arrived {
                base.insert(received(sender, content));
            }
            base
        })
    }

    /// Adds the fact `received(sender, content)` of an arriving message; false when already
    /// present. Kept aside, not built (see [`Mailbox::arrived`]), while the fact base holds
    /// no `received/2` fact, so that it is surely new there, and fewer than [`ARRIVED`] are
    /// aside.
    pub fn receive(&mut self, sender: Term, content: Term) -> bool {
        // Sends held now were made before this message arrived: they go first.
        if !self.held.is_empty() {
            self.settle();
        }
        if self.arrived.len() >= ARRIVED || self.facts.has_pred(wk::RECEIVED, 2) {
            return self.insert(received(&sender, &content));
        }
        if self
            .arrived
            .iter()
            .any(|[s, c]| *s == sender && *c == content)
        {
            return false;
        }
        self.arrived_base.take();
        self.arrived.push([sender, content]);
        true
    }

    /// Removes held fact `k`.
    fn take_held(&mut self, k: usize) -> (Sym, Term) {
        self.held_edits += 1;
        take_at(&mut self.held, k)
    }

    /// Removes arrived fact `k`.
    fn take_arrived(&mut self, k: usize) -> [Term; 2] {
        self.arrived_base.take();
        take_at(&mut self.arrived, k)
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
            self.take_held(k);
            return true;
        }
        if fact.is_functor(wk::RECEIVED, 2) {
            if let Some(k) = self.arrived.iter().position(|a| a[..] == *fact.args()) {
                self.take_arrived(k);
                return true;
            }
        }
        self.facts.delete(fact)
    }

    /// The stored mail fact `fact` is a variant of: an interrogative message may be open
    /// (`int(at(_, red))`), and a rule deleting it names it with variables.
    pub fn variant_of(&self, fact: &Term) -> Option<Term> {
        let (name, arity) = fact.functor()?;
        let held = self.held.iter().map(|(r, c)| sent(&Term::Atom(*r), c));
        held.chain(self.facts.facts_of(name, arity).cloned())
            .chain(
                self.arrived
                    .iter()
                    .filter(|_| (name, arity) == (wk::RECEIVED, 2))
                    .map(|[s, c]| received(s, c)),
            )
            .find(|f| f.is_variant(fact))
    }

    /// Removes the mail fact that `pattern` stands for under `s`, found without building it:
    /// a rule deleting the message its condition matched. `None` when `pattern` is no mail
    /// fact held or among the first [`SCAN`] facts of its predicate; the caller then takes the
    /// general way (building the fact, which also reports what is not ground). `of_send`: the
    /// pattern is by its form the `sent/2` fact of the last send (see
    /// [`Mailbox::mark_sent`]), whose mark, while valid, finds it without matching.
    pub fn delete_matching(&mut self, pattern: &Term, s: &Subst, of_send: bool) -> Option<Deleted> {
        if of_send {
            if let Some(k) = self.marked_sent() {
                debug_assert!(held_under(s, pattern, &self.held[k]), "stale sent mark");
                let (r, c) = self.take_held(k);
                return Some(Deleted::Sent(r, c));
            }
        }
        if !is_mail_fact(pattern) {
            return None;
        }
        if let Some(k) = self.held.iter().position(|h| held_under(s, pattern, h)) {
            let (r, c) = self.take_held(k);
            return Some(Deleted::Sent(r, c));
        }
        // A ground pattern matches one fact at most: where it is looked for first is no matter.
        if pattern.is_functor(wk::RECEIVED, 2) {
            let p = pattern.args();
            let at = |[sender, content]: &[Term; 2]| {
                same_under(s, &p[0], sender) && same_under(s, &p[1], content)
            };
            if let Some(k) = self.arrived.iter().position(at) {
                let [sender, content] = self.take_arrived(k);
                return Some(Deleted::Received(sender, content));
            }
        }
        let (name, arity) = pattern.functor()?;
        let f = self
            .facts
            .facts_of(name, arity)
            .take(SCAN)
            .find(|f| same_under(s, pattern, f))?
            .clone();
        if self.facts.len() == 1 {
            // The base's only fact (a mailbox passing one message on): emptying the base is
            // deleting it, without hashing the fact or updating its indexes one by one.
            self.facts.delete_all();
        } else {
            self.facts.delete(&f);
        }
        Some(Deleted::Fact(f))
    }

    /// Takes the kept content of the last send (see `spare.rs`).
    pub fn take_spare(&mut self) -> Option<Term> {
        self.spare.take()
    }

    /// Keeps `content`, just sent, for the next send to write over.
    pub fn keep_spare(&mut self, content: Term) {
        self.spare = Some(content);
    }

    /// Forgets where the last send left its held fact (called as a send starts, and after one
    /// whose fact a `delete` cannot name by its form).
    pub fn unmark_sent(&mut self) {
        self.sent_mark = None;
    }

    /// Marks the held fact the last [`Mailbox::hold_sent`] pushed (if it pushed one since
    /// [`Mailbox::unmark_sent`]) as the one the send just made.
    fn mark_sent(&mut self) {
        self.sent_mark = Some((self.held_edits, self.held.len() - 1));
    }

    /// The position in `held` of the marked fact while no change to `held` came after the
    /// mark (so it is still there, at that position).
    fn marked_sent(&self) -> Option<usize> {
        match self.sent_mark {
            Some((edits, k)) if edits == self.held_edits => Some(k),
            _ => None,
        }
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
        self.held_edits += 1;
        self.mark_sent();
        true
    }

    /// Moves the arrived `received/2` facts and then the held `sent/2` facts into the fact
    /// base, each in the order they came.
    #[inline]
    pub fn settle(&mut self) {
        // Called before every read and after every combo, nearly always with nothing aside.
        if !self.arrived.is_empty() {
            self.settle_arrived();
        }
        if !self.held.is_empty() {
            self.settle_held();
        }
    }

    fn settle_arrived(&mut self) {
        self.arrived_base.take();
        for [sender, content] in self.arrived.drain(..) {
            self.facts
                .insert(Term::compound(wk::RECEIVED, vec![sender, content]));
        }
    }

    fn settle_held(&mut self) {
        self.held_edits += 1;
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
pub(super) mod tests {
    use super::*;

    /// The term written in `text` (for the agent's unit tests).
    pub(in crate::agent) fn term(text: &str) -> Term {
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
            mb.delete_matching(&term("received(b, imp(token(T, K)))"), &s, false),
            None
        );
        assert_eq!(
            mb.delete_matching(&term("received(a, imp(token(T, 6)))"), &s, false),
            None
        );
        let pattern = term("received(a, imp(token(T, K)))");
        assert_eq!(
            mb.delete_matching(&pattern, &s, false).map(Deleted::term),
            Some(term("received(a, imp(token(2, 5)))"))
        );
        // Gone: the same pattern now finds nothing.
        assert_eq!(mb.delete_matching(&pattern, &s, false), None);
        s.bind(Sym::intern("R"), Term::Int(4));
        let held = term("sent(b, imp(token(1, R)))");
        assert_eq!(
            mb.delete_matching(&held, &s, false).map(Deleted::term),
            Some(term("sent(b, imp(token(1, 4)))"))
        );
        mb.settle();
        assert_eq!(mb.facts().len(), 1);
        // An unbound variable or a fact of another kind: left to the general way.
        let open = term("received(a, imp(token(1, X)))");
        assert_eq!(mb.delete_matching(&open, &s, false), None);
        assert_eq!(mb.delete_matching(&term("at(a)"), &s, false), None);
        assert_eq!(mb.facts().len(), 1);
    }

    #[test]
    fn a_sent_mark_finds_its_fact_until_the_held_facts_change() {
        let (b, c) = (Sym::intern("b"), Sym::intern("c"));
        let mut s = Subst::new();
        s.bind(Sym::intern("X"), Term::Int(1));
        let of_b = term("sent(b, imp(go(X)))");
        let of_c = term("sent(c, y)");
        // The mark of the last push finds that fact.
        let mut mb = Mailbox::default();
        assert!(mb.hold_sent(b, term("imp(go(1))")));
        assert_eq!(
            mb.delete_matching(&of_b, &s, true).map(Deleted::term),
            Some(term("sent(b, imp(go(1)))"))
        );
        // A fact before the marked one taken away: the mark is stale (its position moved), and
        // the delete matches instead.
        mb.hold_sent(b, term("imp(go(1))"));
        mb.hold_sent(c, term("y"));
        assert!(mb.delete(&term("sent(b, imp(go(1)))")));
        assert_eq!(
            mb.delete_matching(&of_c, &s, true).map(Deleted::term),
            Some(term("sent(c, y)"))
        );
        // Settled into the fact base: found there by matching.
        mb.hold_sent(c, term("y"));
        mb.settle();
        assert_eq!(
            mb.delete_matching(&of_c, &s, true),
            Some(Deleted::Fact(term("sent(c, y)")))
        );
        // Forgotten: nothing is taken without a match.
        mb.hold_sent(c, term("y"));
        mb.unmark_sent();
        assert_eq!(mb.delete_matching(&of_b, &s, true), None);
        assert_eq!(mb.held.len(), 1);
    }

    #[test]
    fn deleting_the_only_fact_by_pattern_is_a_plain_delete() {
        let fact = term("received(a, imp(token(1, 5)))");
        let (mut by_pattern, mut by_term) = (Mailbox::default(), Mailbox::default());
        by_pattern.insert(fact.clone());
        by_term.insert(fact.clone());
        // `T` is bound through another variable: the chain is followed to its value.
        let mut s = Subst::new();
        s.bind(Sym::intern("T"), Term::Var(Sym::intern("U")));
        s.bind(Sym::intern("U"), Term::Int(1));
        s.bind(Sym::intern("K"), Term::Int(5));
        s.bind(Sym::intern("S"), Term::atom("a"));
        let pattern = term("received(S, imp(token(T, K)))");
        assert_eq!(
            by_pattern.delete_matching(&pattern, &s, false),
            Some(Deleted::Fact(fact.clone()))
        );
        assert!(by_term.delete(&fact));
        // The same empty base, the same count of edits (readers compare counts).
        assert_eq!(by_pattern.facts().len(), 0);
        assert_eq!(by_pattern.facts().edits(), by_term.facts().edits());
        // The emptied base takes the next message as a new one.
        assert!(by_pattern.insert(fact.clone()));
        assert!(by_pattern.facts().contains(&fact));
        assert_eq!(
            by_pattern
                .delete_matching(&pattern, &s, false)
                .map(Deleted::term),
            Some(fact)
        );
        // With two facts, the matched one goes and the other stays.
        by_pattern.insert(term("received(a, imp(token(1, 5)))"));
        by_pattern.insert(term("received(b, imp(token(1, 5)))"));
        assert!(by_pattern.delete_matching(&pattern, &s, false).is_some());
        let left: Vec<&Term> = by_pattern.facts().iter().collect();
        assert_eq!(left, [&term("received(b, imp(token(1, 5)))")]);
    }

    /// Receives the message of the fact `received(Sender, Content)` written in `text`.
    fn arrive(mb: &mut Mailbox, text: &str) -> bool {
        let f = term(text);
        mb.receive(f.args()[0].clone(), f.args()[1].clone())
    }

    /// A mental state for agent `me` with knowledge `text`.
    fn mental_state(text: &str) -> crate::agent::mental_state::MentalState {
        let mut r = crate::syntax::prolog::Reader::new("t");
        let (clauses, _) = r.clauses(text, 0);
        let clauses: Vec<Term> = clauses.into_iter().map(|c| c.term).collect();
        let kn = crate::agent::kr_bridge::Knowledge::load(&clauses).expect("knowledge");
        let agents = crate::agent::directory::Directory::new(&["me".into(), "a".into()]);
        crate::agent::mental_state::MentalState::new(
            kn,
            &Term::atom("me"),
            agents,
            crate::agent::kr_bridge::Limits::default(),
            1,
        )
    }

    #[test]
    fn arriving_messages_wait_aside_and_settle_in_arrival_order() {
        let mut mb = Mailbox::default();
        assert!(arrive(&mut mb, "received(a, imp(go(1)))"));
        assert!(arrive(&mut mb, "received(b, hi)"));
        // The same message again is no new fact.
        assert!(!arrive(&mut mb, "received(a, imp(go(1)))"));
        assert_eq!(mb.arrived().len(), 2);
        assert_eq!(mb.stored().len(), 0);
        assert_eq!(mb.arrived_base().len(), 2);
        // Deleted by pattern or by the fact itself, without reaching the fact base.
        let mut s = Subst::new();
        s.bind(Sym::intern("X"), Term::Int(1));
        assert_eq!(
            mb.delete_matching(&term("received(a, imp(go(X)))"), &s, false)
                .map(Deleted::term),
            Some(term("received(a, imp(go(1)))"))
        );
        assert_eq!(mb.arrived_base().len(), 1, "the engine's view follows");
        assert!(arrive(&mut mb, "received(c, one)"));
        mb.settle();
        assert!(mb.arrived().is_empty());
        let order: Vec<String> = mb.facts().iter().map(|f| f.to_string()).collect();
        assert_eq!(order, ["received(b,hi)", "received(c,one)"]);
        // With `received/2` facts stored, the next message goes to the fact base at once, after
        // them; a duplicate of a stored one is refused there.
        assert!(arrive(&mut mb, "received(d, two)"));
        assert!(!arrive(&mut mb, "received(b, hi)"));
        assert!(mb.arrived().is_empty());
        assert!(mb.delete(&term("received(b, hi)")));
        let order: Vec<String> = mb.facts().iter().map(|f| f.to_string()).collect();
        assert_eq!(order, ["received(c,one)", "received(d,two)"]);
    }

    #[test]
    fn at_most_a_few_messages_wait_aside() {
        let mut mb = Mailbox::default();
        for i in 0..ARRIVED + 3 {
            assert!(mb.receive(Term::atom("a"), Term::Int(i as i64)));
        }
        // The first one past the limit settled the waiting ones, then went in after them.
        assert!(mb.arrived().is_empty());
        let got: Vec<String> = mb.facts().iter().map(|f| f.to_string()).collect();
        let want: Vec<String> = (0..ARRIVED + 3)
            .map(|i| format!("received(a,{i})"))
            .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn held_sends_and_arrived_messages_keep_the_order_they_came_in() {
        let mut mb = Mailbox::default();
        // An open question waiting aside is found by a variant, as a stored one is.
        assert!(arrive(&mut mb, "received(a, int(at(_, red)))"));
        let open = mb.variant_of(&term("received(a, int(at(X, red)))"));
        let open = open.expect("a variant");
        assert!(
            open.to_string().starts_with("received(a,int(at(_"),
            "{open}"
        );
        assert!(mb.delete(&open));
        assert!(mb.arrived().is_empty());
        assert!(mb.hold_sent(Sym::intern("b"), term("first")));
        assert!(arrive(&mut mb, "received(a, second)"));
        assert!(mb.hold_sent(Sym::intern("b"), term("third")));
        assert!(arrive(&mut mb, "received(a, fourth)"));
        mb.settle();
        let got: Vec<String> = mb.facts().iter().map(|f| f.to_string()).collect();
        assert_eq!(
            got,
            [
                "sent(b,first)",
                "received(a,second)",
                "sent(b,third)",
                "received(a,fourth)"
            ]
        );
    }

    #[test]
    fn plans_and_the_engine_see_the_messages_waiting_aside() {
        use crate::agent::conjunction::Plan;
        use crate::agent::mental_state::MentalState;
        let mut ms = mental_state("k(1).");
        arrive(&mut ms.mailbox, "received(a, imp(go(1)))");
        arrive(&mut ms.mailbox, "received(b, hi)");
        let show = |found: &[Subst]| -> Vec<String> {
            let value = |s: &Subst, v: &str| s.get(Sym::intern(v)).map(|t| t.to_string());
            found
                .iter()
                .map(|s| format!("{:?} {:?}", value(s, "S"), value(s, "M")))
                .collect()
        };
        // The engine (asked with a built-in no plan takes) and a plan give the same answers in
        // the same order, before and after the messages are settled into the fact base.
        let engine =
            |ms: &MentalState| show(&ms.bel(&term("received(S, M), atom(S)")).expect("engine"));
        let plan = Plan::prepare(&term("received(S, M)"), &ms.knowledge.clone()).expect("plan");
        let planned =
            |ms: &MentalState| show(&plan.answers(ms, &Subst::new(), 9).expect("planned").0);
        let (e1, p1) = (engine(&ms), planned(&ms));
        assert_eq!(
            p1,
            [r#"Some("a") Some("imp(go(1))")"#, r#"Some("b") Some("hi")"#]
        );
        assert_eq!(e1, p1);
        ms.mailbox.settle();
        assert_eq!((engine(&ms), planned(&ms)), (e1, p1));
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
        assert_eq!(mb.delete_matching(&deep("X"), &s, false), None);
        s = Subst::new();
        s.bind(Sym::intern("X"), Term::Int(1));
        assert_eq!(
            mb.delete_matching(&deep("X"), &s, false).map(Deleted::term),
            Some(deep("1"))
        );
        assert_eq!(mb.facts().len(), 0);
    }
}
