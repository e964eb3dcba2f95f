//! The mental state of one agent: shared knowledge, beliefs, goals (attention stack), typed
//! percepts, mailbox and the `agent/1`, `me/1` facts; with the queries and updates on them.

use super::error::Fault;
use super::goals::{AttentionStack, Goal, GoalBase};
use super::kr_bridge::{query, FactBase, Knowledge, Limits, View};
use super::mailbox::{is_mail_fact, Mailbox};
use super::percepts::PerceptBase;
use super::trace::Event;
use crate::term::{well_known as wk, Subst, Term};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// The stores of an agent.
#[derive(Clone, Debug)]
pub struct MentalState {
    pub knowledge: Arc<Knowledge>,
    pub beliefs: FactBase,
    pub percepts: PerceptBase,
    pub mailbox: Mailbox,
    /// `agent(A)` for every known agent and `me(Self)`.
    pub agents: FactBase,
    pub attention: AttentionStack,
    pub limits: Limits,
}

/// The effect of an update on the belief base and mailbox.
#[derive(Debug, Default)]
pub struct UpdateEffect {
    pub events: Vec<Event>,
}

impl MentalState {
    /// An empty mental state for agent `me` knowing `agents`.
    pub fn new(knowledge: Arc<Knowledge>, me: &Term, agents: &[Term], limits: Limits) -> Self {
        let mut facts = FactBase::new();
        for a in agents {
            facts.insert(Term::compound(wk::AGENT, vec![a.clone()]));
        }
        facts.insert(Term::compound(wk::AGENT, vec![me.clone()]));
        facts.insert(Term::compound(wk::ME, vec![me.clone()]));
        MentalState {
            knowledge,
            beliefs: FactBase::new(),
            percepts: PerceptBase::default(),
            mailbox: Mailbox::default(),
            agents: facts,
            attention: AttentionStack::default(),
            limits,
        }
    }

    /// All answers of `q` against the belief base (knowledge, beliefs, percepts, mail, agents).
    pub fn bel(
        &self,
        q: &Term,
        rng: &mut ChaCha8Rng,
        out: &mut String,
    ) -> Result<Vec<Subst>, Fault> {
        let bases = [
            &self.beliefs,
            self.percepts.facts(),
            self.mailbox.facts(),
            &self.agents,
        ];
        let view = View {
            knowledge: &self.knowledge,
            bases: &bases,
            goal_facts: &[],
        };
        query(&view, q, self.limits, rng, out).map_err(|e| Fault::new(format!("query {q}: {e}")))
    }

    /// True when `q` has an answer in the belief base.
    pub fn believes(
        &self,
        q: &Term,
        rng: &mut ChaCha8Rng,
        out: &mut String,
    ) -> Result<bool, Fault> {
        Ok(!self.bel(q, rng, out)?.is_empty())
    }

    /// All answers of `q` against one goal's facts plus knowledge.
    pub fn in_goal(
        &self,
        g: &Goal,
        q: &Term,
        rng: &mut ChaCha8Rng,
        out: &mut String,
    ) -> Result<Vec<Subst>, Fault> {
        let view = View {
            knowledge: &self.knowledge,
            bases: &[],
            goal_facts: &g.facts,
        };
        query(&view, q, self.limits, rng, out)
            .map_err(|e| Fault::new(format!("goal query {q}: {e}")))
    }

    /// True when some goal of `base` entails `q`.
    pub fn is_goal_in(
        &self,
        base: &GoalBase,
        q: &Term,
        rng: &mut ChaCha8Rng,
        out: &mut String,
    ) -> Result<bool, Fault> {
        for g in base.goals() {
            if !self.in_goal(g, q, rng, out)?.is_empty() {
                return Ok(true);
            }
        }
        Ok(false)
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
        let mut add = Vec::new();
        let mut del = Vec::new();
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

    /// Removes the positive literals of a ground conjunction.
    pub fn delete(&mut self, u: &Term, events: &mut Vec<Event>) -> Result<(), Fault> {
        if !u.is_ground() {
            return Err(Fault::new(format!("delete {u} is not ground")));
        }
        for lit in u.conjuncts() {
            if lit.is_functor(wk::TRUE, 0) {
                continue;
            }
            if lit.is_functor(wk::NOT, 1) {
                return Err(Fault::new(format!(
                    "not(...) is not allowed in delete: {u}"
                )));
            }
            self.remove_fact(lit, events);
        }
        Ok(())
    }

    fn add_fact(&mut self, f: &Term, events: &mut Vec<Event>) {
        if is_mail_fact(f) {
            if self.mailbox.insert(f.clone()) {
                events.push(Event::MailAdded {
                    fact: f.to_string(),
                });
            }
        } else if self.beliefs.insert(f.clone()) {
            events.push(Event::BeliefInserted {
                fact: f.to_string(),
            });
        }
    }

    fn remove_fact(&mut self, f: &Term, events: &mut Vec<Event>) {
        if is_mail_fact(f) {
            if self.mailbox.delete(f) {
                events.push(Event::MailDeleted {
                    fact: f.to_string(),
                });
            }
        } else if self.beliefs.delete(f) {
            events.push(Event::BeliefDeleted {
                fact: f.to_string(),
            });
        }
    }

    /// Blind commitment: removes every goal of the current attention set that is believed.
    pub fn goal_check(
        &mut self,
        rng: &mut ChaCha8Rng,
        out: &mut String,
        events: &mut Vec<Event>,
    ) -> Result<(), Fault> {
        let mut achieved = Vec::new();
        for g in self.attention.current().goals() {
            if self.believes(&g.term, rng, out)? {
                achieved.push(g.term.clone());
            }
        }
        if !achieved.is_empty() {
            self.attention
                .current_mut()
                .remove_where(|g| achieved.contains(&g.term));
            for g in achieved {
                events.push(Event::GoalAchieved {
                    goal: g.to_string(),
                });
            }
        }
        Ok(())
    }
}
