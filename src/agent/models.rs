//! Mental models of other agents (described in docs/coming-from-goal.md): for each agent that sent this
//! agent a message, the beliefs and goals its messages reveal, and the conditions with
//! selectors other than `this`/`self` (`allother.bel(p)`, `(bob).goal(q)`, ...) that query them.
//! Kept only by programs that use such selectors.

use super::condition::eval;
use super::error::Fault;
use super::goals::{Goal, GoalBase};
use super::kr_bridge::FactBase;
use super::mental_state::MentalState;
use super::message::agent_names;
use super::program::{About, Lit};
use crate::syntax::ast::MentalOp;
use crate::term::{well_known as wk, Subst, Term};
use std::collections::BTreeMap;

/// What this agent believes another agent believes and wants.
#[derive(Clone, Debug, Default)]
pub struct Model {
    pub beliefs: FactBase,
    pub goals: GoalBase,
}

/// The models of the other agents, by name.
#[derive(Clone, Debug, Default)]
pub struct Models {
    /// Messages update the models (set when the program queries them).
    pub enabled: bool,
    /// The name of the agent that keeps the models.
    pub me: String,
    models: BTreeMap<String, Model>,
}

impl Models {
    /// No models yet, kept by agent `me` (not updated until `enabled` is set).
    pub fn new(me: String) -> Models {
        Models {
            me,
            ..Models::default()
        }
    }

    /// The model of `agent`, if it has sent anything.
    pub fn get(&self, agent: &str) -> Option<&Model> {
        self.models.get(agent)
    }

    /// The model of `agent`, to change it.
    pub fn get_mut(&mut self, agent: &str) -> Option<&mut Model> {
        self.models.get_mut(agent)
    }

    /// Updates the model of `sender` from a message with (mood-wrapped) `content`: an
    /// indicative message adds its content to the sender's beliefs (`not(p)` removes `p`), an
    /// imperative one adds a goal and removes it from the beliefs, an interrogative one removes
    /// the content from the beliefs. Non-ground parts are left out.
    pub fn receive(&mut self, sender: &str, content: &Term) {
        let model = self.models.entry(sender.to_string()).or_default();
        let (mood, body) = if content.is_functor(wk::IMP, 1) {
            (wk::IMP, &content.args()[0])
        } else if content.is_functor(wk::INT, 1) {
            (wk::INT, &content.args()[0])
        } else {
            (wk::TRUE, content)
        };
        for lit in body.conjuncts() {
            let (positive, fact) = if lit.is_functor(wk::NOT, 1) {
                (false, &lit.args()[0])
            } else {
                (true, lit)
            };
            if !fact.is_ground() || fact.functor().is_none() || fact.is_functor(wk::TRUE, 0) {
                continue;
            }
            if mood == wk::TRUE && positive {
                model.beliefs.insert(fact.clone());
            } else {
                model.beliefs.delete(fact);
            }
        }
        if mood == wk::IMP && body.is_ground() && !model.goals.contains(body) {
            model.goals.add(Goal::new(body.clone()));
        }
    }
}

/// The answers of `op(q)` about the agents chosen by `about` (`q` already instantiated):
/// `all`, `allother` and agent lists need the same answer in every chosen model, `some` and
/// `someother` take the answers of any of them. `all` and `some` include this agent itself,
/// answered from its own mental state.
pub fn answers(
    ms: &MentalState,
    about: &About,
    op: MentalOp,
    q: &Term,
    theta: &Subst,
) -> Result<Vec<Subst>, Fault> {
    let me = ms.models.me.as_str();
    let (names, every) = match about {
        About::All => (ms.agents.names().to_vec(), true),
        About::AllOther => (others(ms, me), true),
        About::Some => (ms.agents.names().to_vec(), false),
        About::SomeOther => (others(ms, me), false),
        About::Agents(ts) => {
            let ts: Vec<Term> = ts.iter().map(|t| theta.apply(t)).collect();
            let names = agent_names(&ts, theta)?;
            (names.iter().map(|n| n.name().to_string()).collect(), true)
        }
    };
    let mut result: Option<Vec<(Term, Subst)>> = None;
    for name in &names {
        let found: Vec<(Term, Subst)> = one(ms, me, name, op, q)?
            .into_iter()
            .map(|a| (a.apply(q), a))
            .collect();
        result = Some(match result {
            None => found,
            Some(acc) if every => acc
                .into_iter()
                .filter(|(inst, _)| found.iter().any(|(i, _)| i == inst))
                .collect(),
            Some(mut acc) => {
                for f in found {
                    if !acc.iter().any(|(i, _)| *i == f.0) {
                        acc.push(f);
                    }
                }
                acc
            }
        });
    }
    Ok(result
        .unwrap_or_default()
        .into_iter()
        .map(|(_, a)| a)
        .collect())
}

fn others(ms: &MentalState, me: &str) -> Vec<String> {
    ms.agents
        .names()
        .iter()
        .filter(|n| *n != me)
        .cloned()
        .collect()
}

/// The answers of `op(q)` in the model of `name` (this agent's own state when `name` is `me`).
fn one(
    ms: &MentalState,
    me: &str,
    name: &str,
    op: MentalOp,
    q: &Term,
) -> Result<Vec<Subst>, Fault> {
    if name == me {
        let own = Lit::Mental {
            negated: false,
            top_level: false,
            about: None,
            op,
            query: q.clone(),
            plan: Default::default(),
        };
        let cx = super::condition::CondCtx { ms, only: None };
        return eval(&cx, &[own], &Subst::new());
    }
    let empty = Model::default();
    let model = ms.models.get(name).unwrap_or(&empty);
    if op == MentalOp::Bel {
        return ms.bel_in(&model.beliefs, q);
    }
    let mut out = Vec::new();
    for g in model.goals.goals() {
        for a in ms.in_goal(g, q)? {
            if op != MentalOp::Goal {
                let inst = a.apply(q);
                if !inst.is_ground() {
                    return Err(Fault::new(format!(
                        "{inst} is not ground after the goal query on the model of {name}"
                    )));
                }
                if ms.holds_in(&model.beliefs, &inst)? != (op == MentalOp::GoalA) {
                    continue;
                }
            }
            if !out.contains(&a) {
                out.push(a);
            }
        }
    }
    Ok(out)
}
