//! The mental state of one agent: shared knowledge, beliefs, goals (attention stack), typed
//! percepts, mailbox and the `agent/1`, `me/1` facts; with the queries and updates on them.

use super::directory::Directory;
use super::error::Fault;
use super::goals::{AttentionStack, Goal, GoalBase};
use super::kr_bridge::{
    AgentEngine, Engine, FactBase, Knowledge, KrError, Limits, NativeEngine, View,
};
use super::lookup;
use super::mailbox::{is_mail_fact, is_mail_predicate, Arrived, Mailbox};
use super::models::Models;
use super::percepts::PerceptBase;
use super::trace::Event;
use crate::kr::native::code::Key;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};
use std::cell::RefCell;
use std::sync::Arc;

mod goal_mark;
mod goal_memo;
mod goal_query;
use goal_mark::GoalMark;
pub use goal_memo::GoalMemo;
pub use goal_query::GoalQuery;

/// The stores of an agent.
#[derive(Clone, Debug)]
pub struct MentalState {
    pub knowledge: Arc<Knowledge>,
    pub beliefs: FactBase,
    pub percepts: PerceptBase,
    pub mailbox: Mailbox,
    /// `agent(A)` for every known agent (shared by the agents of a system).
    pub agents: Arc<Directory>,
    /// `me(Self)`.
    pub me: FactBase,
    pub attention: AttentionStack,
    /// The KR engine (limits, its own seeded RNG and output buffer); interior mutability lets
    /// queries run while conditions hold a shared borrow of the state.
    pub engine: RefCell<AgentEngine>,
    /// Record change events (off when the trace level is `Off`, to save the printing).
    pub record: bool,
    /// Mental models of the other agents (kept when the program queries them).
    pub models: Models,
    /// The state the last goal check saw, kept up to date by this agent's own belief updates
    /// (with the predicates they inserted) while nothing else changed: see
    /// [`MentalState::goal_check`]. `None`: the next check looks at every goal.
    goal_mark: Option<GoalMark>,
    /// Answers of goal literals kept while the module loop only evaluates rules (see
    /// [`GoalMemo`]; read and filled by condition evaluation, emptied by the module loop).
    pub goal_memo: RefCell<GoalMemo>,
}

/// The effect of an update on the belief base and mailbox.
#[derive(Debug, Default)]
pub struct UpdateEffect {
    pub events: Vec<Event>,
}

impl MentalState {
    /// An empty mental state for agent `me` knowing the agents of `agents` (which includes
    /// `me`).
    pub fn new(
        knowledge: Arc<Knowledge>,
        me: &Term,
        agents: Arc<Directory>,
        limits: Limits,
        seed: u64,
    ) -> Self {
        let mut facts = FactBase::new();
        facts.insert(Term::compound(wk::ME, vec![me.clone()]));
        MentalState {
            knowledge,
            beliefs: FactBase::new(),
            percepts: PerceptBase::default(),
            mailbox: Mailbox::default(),
            agents,
            me: facts,
            attention: AttentionStack::default(),
            engine: RefCell::new(AgentEngine::Native(
                NativeEngine::new(seed).with_limits(limits),
            )),
            record: true,
            models: Models::new(match me {
                Term::Atom(a) => a.name().to_string(),
                other => other.to_string(),
            }),
            goal_mark: None,
            goal_memo: RefCell::default(),
        }
    }

    /// All answers of `q` against `facts` plus knowledge (a mental model's beliefs).
    pub fn bel_in(&self, facts: &FactBase, q: &Term) -> Result<Vec<Subst>, Fault> {
        let bases = [facts];
        let view = View::beliefs(&self.knowledge, &bases);
        self.run(|e| e.query(&view, q), q)
    }

    /// True when `q` holds in `facts` plus knowledge (a mental model's beliefs).
    pub fn holds_in(&self, facts: &FactBase, q: &Term) -> Result<bool, Fault> {
        let bases = [facts];
        let view = View::beliefs(&self.knowledge, &bases);
        self.run(|e| e.holds(&view, q), q)
    }

    /// Updates the model of `sender` from a received message (docs/coming-from-goal.md, "Mental models"), then drops the goals of
    /// that model that its beliefs achieve. Nothing happens unless models are kept, or for a
    /// message from this agent itself.
    pub fn update_model(&mut self, sender: Sym, content: &Term) -> Result<(), Fault> {
        // The sender's name is looked up only when models are on (most programs: off).
        if !self.models.enabled {
            return Ok(());
        }
        let sender = sender.name();
        if sender == self.models.me {
            return Ok(());
        }
        self.models.receive(sender, content);
        let Some(model) = self.models.get(sender) else {
            return Ok(());
        };
        let mut achieved = Vec::new();
        for g in model.goals.goals() {
            if self.holds_in(&model.beliefs, &g.term)? {
                achieved.push(g.term.clone());
            }
        }
        if !achieved.is_empty() {
            if let Some(m) = self.models.get_mut(sender) {
                m.goals.remove_where(|g| achieved.contains(&g.term));
            }
        }
        Ok(())
    }

    /// All answers of `q` against the belief base (knowledge, beliefs, percepts, mail, agents).
    ///
    /// A top-level conjunction with negated conjuncts (and no top-level cut) is run in
    /// segments: each negation is checked per answer of the conjuncts before it, as a cheap
    /// `holds` when it is ground. Answers and their order are those of the whole query.
    pub fn bel(&self, q: &Term) -> Result<Vec<Subst>, Fault> {
        Ok(self.bel_upto(q, usize::MAX)?.0)
    }

    /// [`MentalState::bel_upto`] of `theta` applied to `q`: the answers bind the variables of
    /// `q` that `theta` leaves free. The native engine takes a query it runs whole (a
    /// conjunction, a built-in, a knowledge predicate) with `theta` as it is, so the
    /// instantiated query is never built.
    pub fn bel_upto_in(
        &self,
        q: &Term,
        theta: &Subst,
        cap: usize,
    ) -> Result<(Vec<Subst>, bool), Fault> {
        if self.cannot_hold(q) {
            return Ok((Vec::new(), false));
        }
        if let Some(r) = self.without_engine(q, theta, cap) {
            return Ok(r);
        }
        // A plain fact pattern goes the other way (instantiated, a ground one is a lookup), and
        // so does a conjunction with negations that are lookups once instantiated.
        let whole = q
            .functor()
            .is_some_and(|(name, arity)| self.knowledge.resolves(name, arity))
            && first_conjunct(q).functor().is_some()
            && !segmented(q, theta);
        if whole {
            let bases = self.bases();
            let view = View::beliefs(&self.knowledge, &bases);
            let run = match self.engine.try_borrow_mut() {
                Ok(mut e) => match &mut *e {
                    AgentEngine::Native(n) => n.query_upto_in(&view, q, theta, cap),
                    #[allow(unreachable_patterns)]
                    _ => None,
                },
                Err(_) => return Err(Fault::new("the KR engine is busy (re-entrant query)")),
            };
            if let Some(r) = run {
                return r.map_err(|e| Fault::new(format!("query {}: {e}", theta.apply(q))));
            }
        }
        let (found, cut) = self.bel_upto(&theta.apply(q), cap)?;
        Ok((found, cut))
    }

    /// The first `cap` answers of [`MentalState::bel`], and whether the search stopped at `cap`.
    pub fn bel_upto(&self, q: &Term, cap: usize) -> Result<(Vec<Subst>, bool), Fault> {
        if self.cannot_hold(q) {
            return Ok((Vec::new(), false));
        }
        if !segmented(q, &Subst::new()) {
            return self.bel_raw(q, cap);
        }
        let parts = q.conjuncts();
        let negation = |t: &Term| t.is_functor(wk::NOT, 1) || t.is_functor(wk::NAF, 1);
        let mut cut = false;
        let mut answers = vec![Subst::new()];
        let mut i = 0;
        while i < parts.len() && !answers.is_empty() {
            let mut next = Vec::new();
            if negation(parts[i]) {
                let neg = &parts[i].args()[0];
                for theta in answers {
                    if let Some(holds) = self.indexed_holds(neg, &theta) {
                        if !holds {
                            next.push(theta);
                        }
                        continue;
                    }
                    let g = theta.apply(neg);
                    let holds = if g.is_ground() {
                        self.believes_ground(&g)?
                    } else {
                        // `not(G)` has no answer exactly when G holds.
                        self.bel_raw(&Term::compound(wk::NOT, vec![g]), usize::MAX)?
                            .0
                            .is_empty()
                    };
                    if !holds {
                        next.push(theta);
                    }
                }
                i += 1;
            } else {
                let start = i;
                while i < parts.len() && !negation(parts[i]) {
                    i += 1;
                }
                let seg = Term::conjunction(parts[start..i].iter().map(|t| (*t).clone()).collect());
                'each: for theta in &answers {
                    let (found, stopped) = self.bel_raw(&theta.apply(&seg), cap)?;
                    cut |= stopped;
                    for a in found {
                        if next.len() >= cap {
                            cut = true;
                            break 'each;
                        }
                        next.push(theta.extended(&a));
                    }
                }
            }
            answers = next;
        }
        Ok((answers, cut))
    }

    fn bel_raw(&self, q: &Term, cap: usize) -> Result<(Vec<Subst>, bool), Fault> {
        if let Some(r) = self.without_engine(q, &Subst::new(), cap) {
            return Ok(r);
        }
        let bases = self.bases();
        let view = View::beliefs(&self.knowledge, &bases);
        self.run(|e| e.query_upto(&view, q, cap), q)
    }

    /// The answers of `q` under `theta` when they can be had without the engine (see
    /// `lookup.rs`): a fact pattern only facts answer, or a comparison of two integers.
    fn without_engine(&self, q: &Term, theta: &Subst, cap: usize) -> Option<(Vec<Subst>, bool)> {
        let (name, arity) = q.functor()?;
        if !self.native_roomy() {
            return None;
        }
        if self.knowledge.resolves(name, arity) {
            let holds = lookup::int_comparison(q, theta)?;
            let out = if holds {
                vec![Subst::new()]
            } else {
                Vec::new()
            };
            let cut = out.len() >= cap;
            return Some((out, cut));
        }
        if is_mail_fact(q) {
            return None;
        }
        lookup::fact_answers(&self.bases(), q, theta, cap)
    }

    /// Whether the fact pattern `q` under `theta` matches a fact, found without building the
    /// instantiated pattern when its first argument is an atom or integer (then the index
    /// holds few candidates); `None`: not decided here.
    fn indexed_holds(&self, q: &Term, theta: &Subst) -> Option<bool> {
        let (name, arity) = q.functor()?;
        let first = match q.args().first()? {
            Term::Var(v) => theta.get(*v)?,
            t => t,
        };
        if !matches!(first, Term::Atom(_) | Term::Int(_))
            || self.knowledge.resolves(name, arity)
            || is_mail_fact(q)
            || !self.native_roomy()
        {
            return None;
        }
        let (found, _) = lookup::fact_answers(&self.bases(), q, theta, 1)?;
        Some(!found.is_empty())
    }

    /// True when the engine is the native one (which answers a ground fact by a lookup, so
    /// that a lookup here answers alike).
    fn native(&self) -> bool {
        matches!(
            self.engine.try_borrow().as_deref(),
            Ok(AgentEngine::Native(_))
        )
    }

    /// True when the engine is the native one and its limits leave room for a query answered
    /// without it (the scryer engine always answers itself).
    pub(crate) fn native_roomy(&self) -> bool {
        match self.engine.try_borrow() {
            Ok(e) => match &*e {
                AgentEngine::Native(n) => lookup::roomy(&n.limits),
                #[allow(unreachable_patterns)]
                _ => false,
            },
            Err(_) => false,
        }
    }

    /// True when `q` has an answer in the belief base.
    pub fn believes(&self, q: &Term) -> Result<bool, Fault> {
        self.believes_known(q, q.is_ground())
    }

    /// [`MentalState::believes`] of a term known to be ground.
    fn believes_ground(&self, q: &Term) -> Result<bool, Fault> {
        self.believes_known(q, true)
    }

    /// The fact bases that can hold a ground fact of `name/arity`, when whether such a fact is
    /// believed is decided by looking it up in them (only facts answer the predicate and the
    /// engine is the native one, as in [`MentalState::believes`]); `None`: ask `believes`.
    pub(crate) fn fact_holders(&self, name: Sym, arity: usize) -> Option<SmallVec<[&FactBase; 6]>> {
        if is_mail_predicate(name, arity) || self.knowledge.resolves(name, arity) || !self.native()
        {
            return None;
        }
        Some(
            self.bases()
                .into_iter()
                .filter(|b| b.has_pred(name, arity))
                .collect(),
        )
    }

    /// [`MentalState::believes`], told whether `q` is ground.
    fn believes_known(&self, q: &Term, ground: bool) -> Result<bool, Fault> {
        // A ground fact only facts answer: present in some base or not (as the engine finds).
        if let Some((name, arity)) = q.functor() {
            if ground && !self.knowledge.resolves(name, arity) && !is_mail_fact(q) && self.native()
            {
                return Ok(self
                    .bases()
                    .iter()
                    .any(|b| b.has_pred(name, arity) && b.contains(q)));
            }
        }
        if self.cannot_hold(q) {
            return Ok(false);
        }
        let bases = self.bases();
        let view = View::beliefs(&self.knowledge, &bases);
        self.run(|e| e.holds(&view, q), q)
    }

    /// All answers of `q` against one goal's facts plus knowledge.
    pub fn in_goal(&self, g: &Goal, q: &Term) -> Result<Vec<Subst>, Fault> {
        Ok(self.in_goal_upto(g, q, usize::MAX)?.0)
    }

    /// The first `cap` answers of [`MentalState::in_goal`], and whether the search stopped at
    /// `cap`.
    pub fn in_goal_upto(
        &self,
        g: &Goal,
        q: &Term,
        cap: usize,
    ) -> Result<(Vec<Subst>, bool), Fault> {
        self.in_goal_prepared(g, &GoalQuery::new(&self.knowledge, q), cap)
    }

    /// [`MentalState::in_goal_upto`] for a query prepared once for many goals.
    pub fn in_goal_prepared(
        &self,
        g: &Goal,
        gq: &GoalQuery<'_>,
        cap: usize,
    ) -> Result<(Vec<Subst>, bool), Fault> {
        if let Some(answers) = gq.facts_only(g) {
            return Ok((answers, false));
        }
        let view = View::goal(&self.knowledge, &g.facts);
        let q = gq.instance();
        self.run(|e| e.query_upto(&view, &q, cap), &q)
    }

    /// True when one goal's facts plus knowledge entail `q`.
    pub fn goal_holds(&self, g: &Goal, q: &Term) -> Result<bool, Fault> {
        self.goal_holds_prepared(g, &GoalQuery::new(&self.knowledge, q))
    }

    /// [`MentalState::goal_holds`] for a query prepared once for many goals.
    fn goal_holds_prepared(&self, g: &Goal, gq: &GoalQuery<'_>) -> Result<bool, Fault> {
        if let Some(answers) = gq.facts_only(g) {
            return Ok(!answers.is_empty());
        }
        let view = View::goal(&self.knowledge, &g.facts);
        let q = gq.instance();
        self.run(|e| e.holds(&view, &q), &q)
    }

    /// True when some goal of `base` entails `q`. When the first conjunct of `q` is of a
    /// predicate only facts answer, only the goals with a fact of that predicate (and first
    /// argument) are asked: no other goal has an answer.
    pub fn is_goal_in(&self, base: &GoalBase, q: &Term) -> Result<bool, Fault> {
        let gq = GoalQuery::new(&self.knowledge, q);
        let first = first_conjunct(q);
        let at = match first.functor() {
            Some((name, arity))
                if base.exactly_indexed() && !self.knowledge.resolves(name, arity) =>
            {
                match first.args().first().and_then(Key::of_term) {
                    Some(key) => base.positions_with_key(name, arity as u32, key),
                    None => base.positions(name, arity as u32),
                }
            }
            _ => {
                for g in base.goals() {
                    if self.goal_holds_prepared(g, &gq)? {
                        return Ok(true);
                    }
                }
                return Ok(false);
            }
        };
        for &p in at {
            if self.goal_holds_prepared(&base.goals()[p as usize], &gq)? {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// True when the first goal of conjunction `q` can only match facts (no built-in, control
    /// construct or knowledge rule answers to it) and no base has a fact of its predicate: then
    /// `q` has no answer. Skips the engine for the common rule whose first literal looks for
    /// something absent, e.g. `received(S, M)` with an empty mailbox.
    fn cannot_hold(&self, q: &Term) -> bool {
        let Some((name, arity)) = first_conjunct(q).functor() else {
            return false;
        };
        !self.knowledge.resolves(name, arity)
            && !self.bases().iter().any(|b| b.has_pred(name, arity))
    }

    /// The fact bases a belief query reads, in the engine's order.
    pub(crate) fn bases(&self) -> [&FactBase; 7] {
        let [b, p, m, a, me, batch] = self.plan_bases().0;
        [b, p, m, self.mailbox.arrived_base(), a, me, batch]
    }

    /// [`MentalState::bases`] for a condition plan: the mailbox's arrived messages as they
    /// are, not as a fact base of their own (which only the engine needs).
    pub(crate) fn plan_bases(&self) -> ([&FactBase; 6], Arrived<'_>) {
        let bases = [
            &self.beliefs,
            self.percepts.facts(),
            self.mailbox.stored(),
            self.agents.facts(),
            &self.me,
            self.percepts.batch(),
        ];
        let arrived = Arrived {
            received: self.mailbox.arrived(),
            after: 2,
        };
        (bases, arrived)
    }

    fn run<T>(
        &self,
        f: impl FnOnce(&mut AgentEngine) -> Result<T, KrError>,
        q: &Term,
    ) -> Result<T, Fault> {
        match self.engine.try_borrow_mut() {
            Ok(mut e) => f(&mut e).map_err(|e| Fault::new(format!("query {q}: {e}"))),
            Err(_) => Err(Fault::new("the KR engine is busy (re-entrant query)")),
        }
    }

    /// Appends to `to` the text written by Prolog output built-ins since the last call.
    pub fn move_output_to(&self, to: &mut String) {
        if let Ok(mut e) = self.engine.try_borrow_mut() {
            // Most cycles print nothing: no empty string is taken, appended and dropped then.
            if e.has_output() {
                to.push_str(&e.take_output());
            }
        }
    }

    /// Applies an update (a ground conjunction of literals; `not(p)` deletes `p`): deletes
    /// first, then adds. Mail facts go to the mailbox.
    pub fn update(
        &mut self,
        u: &Term,
        allow_negative: bool,
        events: &mut Vec<Event>,
    ) -> Result<(), Fault> {
        if !u.is_ground() {
            return Err(Fault::new(format!("update {u} is not ground")));
        }
        self.update_ground(u, allow_negative, events)
    }

    /// [`MentalState::update`] of an update the caller found ground.
    pub fn update_ground(
        &mut self,
        u: &Term,
        allow_negative: bool,
        events: &mut Vec<Event>,
    ) -> Result<(), Fault> {
        let mut add: SmallVec<[&Term; 4]> = SmallVec::new();
        let mut del: SmallVec<[&Term; 4]> = SmallVec::new();
        for lit in u.conjuncts() {
            if lit.is_functor(wk::TRUE, 0) {
                continue;
            }
            if lit.is_functor(wk::NOT, 1) {
                if !allow_negative {
                    return Err(Fault::new(format!(
                        "not(...) is not allowed in delete: {u}"
                    )));
                }
                del.push(&lit.args()[0]);
            } else if lit.functor().is_some() {
                add.push(lit);
            } else {
                return Err(Fault::new(format!("{lit} cannot be a belief")));
            }
        }
        for d in del {
            self.remove_fact(d, events);
        }
        for a in add {
            self.add_fact(a, events);
        }
        Ok(())
    }

    /// Removes the positive literals of a ground conjunction. A literal with variables is
    /// allowed only where it names a stored message that has them itself (an open question):
    /// that very message is removed.
    pub fn delete(&mut self, u: &Term, events: &mut Vec<Event>) -> Result<(), Fault> {
        let lits = u.conjuncts();
        // The stored messages that the open literals name (allocated only when there are any).
        let mut open = Vec::new();
        // Which literals are ground (each walked once).
        let mut ground: SmallVec<[bool; 4]> = SmallVec::with_capacity(lits.len());
        for lit in &lits {
            if lit.is_functor(wk::NOT, 1) {
                return Err(Fault::new(format!(
                    "not(...) is not allowed in delete: {u}"
                )));
            }
            ground.push(lit.is_ground());
            if !ground[ground.len() - 1] {
                match is_mail_fact(lit).then(|| self.mailbox.variant_of(lit)) {
                    Some(Some(stored)) => open.push(stored),
                    _ => return Err(Fault::new(format!("delete({u}) is not ground"))),
                }
            }
        }
        for (lit, ground) in lits.into_iter().zip(ground) {
            if ground && !lit.is_functor(wk::TRUE, 0) {
                self.remove_fact(lit, events);
            }
        }
        for f in &open {
            self.remove_fact(f, events);
        }
        Ok(())
    }

    fn add_fact(&mut self, f: &Term, events: &mut Vec<Event>) {
        if is_mail_fact(f) {
            if self.mailbox.insert(f.clone()) {
                self.record_into(events, || Event::MailAdded {
                    fact: f.to_string(),
                });
            }
        } else if self.beliefs.insert(f.clone()) {
            self.mark_belief_edit(Some(f));
            self.record_into(events, || Event::BeliefInserted {
                fact: f.to_string(),
            });
        }
    }

    /// Removes the belief `q` stands for, found without building it (see
    /// [`FactBase::take_instance`]): as deleting that ground fact, which must be no mail fact.
    pub fn delete_belief_instance<Q>(&mut self, q: &Q, events: &mut Vec<Event>)
    where
        Q: std::hash::Hash + hashbrown::Equivalent<Term>,
    {
        if let Some(f) = self.beliefs.take_instance(q) {
            self.mark_belief_edit(None);
            self.record_into(events, || Event::BeliefDeleted {
                fact: f.to_string(),
            });
        }
    }

    fn remove_fact(&mut self, f: &Term, events: &mut Vec<Event>) {
        if is_mail_fact(f) {
            if self.mailbox.delete(f) {
                self.record_into(events, || Event::MailDeleted {
                    fact: f.to_string(),
                });
            }
        } else if self.beliefs.delete(f) {
            self.mark_belief_edit(None);
            self.record_into(events, || Event::BeliefDeleted {
                fact: f.to_string(),
            });
        }
    }

    fn record_into(&self, events: &mut Vec<Event>, e: impl FnOnce() -> Event) {
        if self.record {
            events.push(e());
        }
    }
}

/// The first goal of a conjunction (the term itself when it is not one).
fn first_conjunct(q: &Term) -> &Term {
    let mut first = q;
    while first.is_functor(wk::COMMA, 2) {
        first = &first.args()[0];
    }
    first
}

/// True when [`MentalState::bel_upto`] runs `q` in segments: a conjunction without a cut with a
/// negated conjunct (`not/1`, `\+/1`) whose variables `theta` or the conjuncts before it bind.
/// Such a negation, once instantiated, is usually a ground lookup; one with a variable of its
/// own (`not(p(X, _))`) is not, and the engine runs the whole conjunction at once.
fn segmented(q: &Term, theta: &Subst) -> bool {
    let negation = |t: &Term| t.is_functor(wk::NOT, 1) || t.is_functor(wk::NAF, 1);
    let mut parts: SmallVec<[&Term; 8]> = SmallVec::new();
    let mut cur = q;
    loop {
        let (part, rest) = if cur.is_functor(wk::COMMA, 2) {
            (&cur.args()[0], Some(&cur.args()[1]))
        } else {
            (cur, None)
        };
        if part.is_functor(wk::CUT, 0) {
            return false;
        }
        parts.push(part);
        match rest {
            Some(r) => cur = r,
            None => break,
        }
    }
    // Asked for every condition: most have no negation, and walk no variables.
    parts.len() > 1
        && parts.iter().enumerate().any(|(i, part)| {
            negation(part)
                && all_vars(part, |v| {
                    theta.get(v).is_some() || parts[..i].iter().any(|b| mentions(b, v))
                })
        })
}

/// True when `ok` holds for every variable of `t` (walked without allocating while shallow).
fn all_vars(t: &Term, mut ok: impl FnMut(Sym) -> bool) -> bool {
    let mut stack: SmallVec<[&Term; 16]> = smallvec![t];
    while let Some(t) = stack.pop() {
        match t {
            Term::Var(v) if !ok(*v) => return false,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    true
}

/// True when `t` is ground and has no float (whose equality is not plain: a value compared as
/// a whole may be the very term it is compared with).
fn plain_ground(t: &Term) -> bool {
    let mut stack: SmallVec<[&Term; 16]> = smallvec![t];
    while let Some(t) = stack.pop() {
        match t {
            Term::Var(_) | Term::Float(_) => return false,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    true
}

/// True when variable `v` occurs in `t`.
fn mentions(t: &Term, v: Sym) -> bool {
    !all_vars(t, |w| w != v)
}
