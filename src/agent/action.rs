//! Performing one action: the built-ins (insert, delete, adopt, drop, print, log), user action
//! specs (`pre`/`post`, `@env` actions handed to the caller) and sends (see `message.rs`).

use super::condition::{compose, show_subst};
use super::cycle::Core;
use super::error::Fault;
use super::goals::Goal;
use super::mailbox::is_mail_fact;
use super::program::{Act, Program, SpecDef};
use super::trace::{Event, TraceLevel};
use super::watch::Observed;
use crate::term::instance::{Instance, Value};
use crate::term::{print::Style, well_known as wk, Subst, Sym, Term};
use rand::Rng;
use smallvec::{smallvec, SmallVec};

/// What happened when an action was tried.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The action could not run (precondition false); a combo stops here.
    NotRun,
    /// The action ran; `real` tells whether it counts as a performed action.
    Done { real: bool },
}

impl Core {
    /// Performs a built-in action or a user action spec (not module calls or exit-module).
    pub fn perform(&mut self, prog: &Program, act: &Act, s: &Subst) -> Result<Outcome, Fault> {
        match act {
            Act::Insert(t) => {
                let u = ground(s, t, "insert")?;
                let mut ev = Vec::new();
                self.ms.update_ground(&u, true, &mut ev)?;
                self.changes(ev);
                self.done_with(|| Term::compound("insert", vec![u.clone()]));
                self.check_goals()?;
                Ok(Outcome::Done { real: true })
            }
            Act::Delete(d) => {
                let t = &d.fact;
                if let Some(f) = self.ms.mailbox.delete_matching(t, s, d.of_send) {
                    // The message the rule matched, deleted without building it first.
                    if self.ms.record {
                        self.changes(vec![Event::MailDeleted {
                            fact: f.clone().term().to_string(),
                        }]);
                    }
                    self.done_with(|| Term::compound("delete", vec![f.term()]));
                    self.check_goals()?;
                    return Ok(Outcome::Done { real: true });
                }
                if let Some(inst) = belief_instance(t, s) {
                    // One belief, ground under `s`: found and removed in place, never built.
                    let mut ev = Vec::new();
                    self.ms.delete_belief_instance(&inst, &mut ev);
                    self.changes(ev);
                    self.done_with(|| Term::compound("delete", vec![s.apply(t)]));
                    self.check_goals()?;
                    return Ok(Outcome::Done { real: true });
                }
                // Not `ground`: a received open question is deleted with its variables (the
                // mental state checks the rest).
                let u = s.apply(t);
                let mut ev = Vec::new();
                self.ms.delete(&u, &mut ev).map_err(|mut f| {
                    f.binding.get_or_insert_with(|| show_subst(s));
                    f
                })?;
                self.changes(ev);
                self.done_with(|| Term::compound("delete", vec![u.clone()]));
                self.check_goals()?;
                Ok(Outcome::Done { real: true })
            }
            Act::Adopt { top_level, content } => {
                self.adopt(&ground(s, content, "adopt")?, *top_level)
            }
            Act::Drop(t) => {
                let q = s.apply(t);
                self.drop_goals(&q)?;
                self.done_with(|| Term::compound("drop", vec![q.clone()]));
                Ok(Outcome::Done { real: true })
            }
            Act::Print(t) => {
                let text = s.apply(t).to_print_text();
                self.out.printed.push(text.clone());
                self.changes(vec![Event::Print { text }]);
                Ok(Outcome::Done { real: true })
            }
            Act::Log(t) => {
                let t = s.apply(t);
                let text = match t.to_text(Style::WRITE).as_str() {
                    "bb" => join(self.ms.beliefs.iter()),
                    "pb" => join(self.ms.percepts.facts().iter()),
                    "mb" => join(self.ms.mailbox.facts().iter()),
                    "gb" => join(self.ms.attention.current().goals().iter().map(|g| &g.term)),
                    "kb" => format!("{} knowledge clauses", self.ms.knowledge.len()),
                    other => other.to_string(),
                };
                self.changes(vec![Event::Log { text }]);
                Ok(Outcome::Done { real: false })
            }
            Act::Send {
                to,
                mood,
                content,
                once,
            } => self.send(to, *mood, content, *once, prog.channels, s),
            Act::Spec { spec, args } => self.user_action(&prog.specs[*spec], args, s),
            Act::Timing { op, args } => self.timing_action(*op, args, s),
            Act::ExitModule | Act::Module { .. } => Ok(Outcome::Done { real: false }),
        }
    }

    /// Counts a performed action; builds its term only when the trace records changes or a
    /// watcher (`goal test`) observes actions.
    pub fn done_with(&mut self, action: impl FnOnce() -> Term) {
        if self.level >= TraceLevel::Changes || self.watcher.is_some() {
            // A watcher may read the mailbox.
            self.ms.mailbox.settle();
            let t = action();
            self.watch(Observed::Action(&t));
            if self.level >= TraceLevel::Changes {
                // `event` counts the action.
                self.event(Event::ActionPerformed {
                    action: t.to_string(),
                });
                return;
            }
        }
        self.out.actions += 1;
    }

    /// Records an `ActionPerformed` event.
    pub fn done(&mut self, action: &Term) -> Result<(), Fault> {
        self.done_with(|| action.clone());
        Ok(())
    }

    fn failed(&mut self, action: &Term, reason: &str) {
        self.changes(vec![Event::ActionFailed {
            action: action.to_string(),
            reason: reason.to_string(),
        }]);
    }

    /// Adopts `g` as one goal unless believed or already a goal.
    pub fn adopt(&mut self, g: &Term, top_level: bool) -> Result<Outcome, Fault> {
        let act = Term::compound("adopt", vec![g.clone()]);
        for lit in g.conjuncts() {
            if lit.is_functor(crate::term::well_known::NOT, 1) || lit.functor().is_none() {
                return Err(Fault::new(format!("adopt needs positive facts: {g}")));
            }
        }
        let base = if top_level {
            self.ms.attention.top_level()
        } else {
            self.ms.attention.current()
        };
        if self.ms.is_goal_in(base, g)? {
            self.failed(&act, "already a goal");
            return Ok(Outcome::NotRun);
        }
        if self.ms.believes(g)? {
            self.failed(&act, "already believed");
            return Ok(Outcome::NotRun);
        }
        let base = if top_level {
            self.ms.attention.top_level_mut()
        } else {
            self.ms.attention.current_mut()
        };
        // Found not believed just now: later goal checks need not look at it unless an update
        // concerns its facts.
        base.add_unbelieved(Goal::new(g.clone()));
        let attention = if top_level {
            0
        } else {
            self.ms.attention.depth() - 1
        };
        if self.level >= TraceLevel::Changes {
            self.changes(vec![Event::GoalAdopted {
                goal: g.to_string(),
                attention,
            }]);
        }
        self.done(&act)?;
        Ok(Outcome::Done { real: true })
    }

    /// Removes from every goal base each goal that entails `q`.
    fn drop_goals(&mut self, q: &Term) -> Result<(), Fault> {
        let mut victims: Vec<(usize, Term)> = Vec::new();
        let depth = self.ms.attention.depth();
        for i in 0..depth {
            let goals = self.ms.attention.all_mut()[i].goals().to_vec();
            for g in goals {
                if !self.ms.in_goal(&g, q)?.is_empty() {
                    victims.push((i, g.term.clone()));
                }
            }
        }
        let mut ev = Vec::new();
        for (i, t) in victims {
            let removed = self.ms.attention.all_mut()[i].remove_where(|g| g.term == t);
            for g in removed {
                ev.push(Event::GoalDropped {
                    goal: g.term.to_string(),
                    attention: i,
                });
            }
        }
        self.changes(ev);
        Ok(())
    }

    /// Runs a user action spec: unify with the head, pick one grounding answer of `pre` at
    /// random, hand `@env` actions to the caller, apply `post`.
    fn user_action(&mut self, spec: &SpecDef, args: &[Term], s: &Subst) -> Result<Outcome, Fault> {
        let call = Term::compound(spec.name, args.iter().map(|a| s.apply(a)).collect());
        let mut m = Subst::new();
        for (p, a) in spec.params.iter().zip(call.args()) {
            if !m.unify(p, a, false) {
                return Err(Fault::new(format!(
                    "{call} does not match its action specification"
                )));
            }
        }
        let head = Term::compound(spec.name, spec.params.clone());
        let pre = m.apply(&spec.pre);
        let answers = self.ms.bel(&pre)?;
        let grounding: Vec<Subst> = answers
            .iter()
            .map(|a| compose(&m, a))
            .filter(|full| full.apply(&head).is_ground())
            .collect();
        if grounding.is_empty() {
            if !answers.is_empty() {
                return Err(Fault {
                    message: format!("action {call} is not ground after its precondition"),
                    binding: Some(show_subst(s)),
                });
            }
            self.failed(&call, "precondition does not hold");
            return Ok(Outcome::NotRun);
        }
        let pick = if grounding.len() == 1 {
            0
        } else {
            self.rng.gen_range(0..grounding.len())
        };
        let full = &grounding[pick];
        let inst = full.apply(&head);
        if spec.env {
            self.out.env_actions.push(inst.clone());
            if self.level >= TraceLevel::Changes {
                self.event(Event::EnvAction {
                    action: inst.to_string(),
                });
            }
        }
        let post = full.apply(&spec.post);
        if !post.is_ground() {
            return Err(Fault {
                message: format!("postcondition {post} of {inst} is not ground"),
                binding: Some(show_subst(full)),
            });
        }
        let mut ev = Vec::new();
        self.ms.update_ground(&post, true, &mut ev)?;
        self.done(&inst)?;
        self.changes(ev);
        self.check_goals()?;
        Ok(Outcome::Done { real: true })
    }

    /// Blind commitment on the current attention set.
    pub fn check_goals(&mut self) -> Result<(), Fault> {
        if self.ms.attention.current().goals().is_empty() {
            return Ok(());
        }
        // Goals are checked against the beliefs, mailbox included.
        self.ms.mailbox.settle();
        let mut ev = Vec::new();
        self.ms
            .goal_check(&mut ev, self.level >= TraceLevel::Changes)?;
        self.changes(ev);
        Ok(())
    }
}

/// Facts printed one per line (for `log(bb)` and friends).
fn join<'a>(facts: impl Iterator<Item = &'a Term>) -> String {
    facts.map(|f| f.to_string()).collect::<Vec<_>>().join("\n")
}

/// The fact `t` stands for under `s`, when `t` is one fact pattern of the beliefs (no
/// conjunction, negation, `true` or mail fact) whose every variable `s` binds to a ground
/// term; `None`: build the instance and let the mental state check it.
fn belief_instance<'a>(
    t: &'a Term,
    s: &'a Subst,
) -> Option<Instance<'a, impl Fn(Sym) -> Option<Value<'a>> + 'a>> {
    let (name, arity) = t.functor()?;
    if matches!((name, arity), (wk::COMMA, 2) | (wk::NOT, 1) | (wk::TRUE, 0)) || is_mail_fact(t) {
        return None;
    }
    let mut stack: SmallVec<[&Term; 8]> = smallvec![t];
    while let Some(x) = stack.pop() {
        match x {
            Term::Var(v) if !s.get(*v).is_some_and(Term::is_ground) => return None,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    Some(Instance::new(t, move |v| s.get(v).map(Value::Term)))
}

fn ground(s: &Subst, t: &Term, what: &str) -> Result<Term, Fault> {
    let u = s.apply(t);
    if u.is_ground() {
        Ok(u)
    } else {
        Err(Fault {
            message: format!("{what}({u}) is not ground"),
            binding: Some(show_subst(s)),
        })
    }
}
