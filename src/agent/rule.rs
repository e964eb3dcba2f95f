//! Rule kinds: computing the answers a rule body runs for (`if`: shuffled, one acting answer;
//! `forall`: all answers computed up front; `listall`: one answer binding the list).

use super::condition::{answers_upto, evaluate, first_lookup_fails, show_subst, CondCtx, Found};
use super::cycle::Core;
use super::error::Fault;
use super::goals::Goal;
use super::program::{RuleDef, RuleKind};
use super::trace::{Event, TraceLevel};
use crate::term::{Subst, Sym, Term};
use rand::seq::SliceRandom;
use smallvec::{smallvec, SmallVec};

/// One answer of a rule condition, with the goals that produced it (for focus=select).
#[derive(Clone, Debug)]
pub struct Answer {
    pub subst: Subst,
    pub goals: Vec<Goal>,
}

/// The answers a rule's body runs for: mostly none or one, kept inline.
pub type Answers = SmallVec<[Answer; 1]>;

/// Most answers of its condition an `if` rule considers: the condition's evaluation stops
/// there (with a warning), so a generator with infinitely many answers (`between(1, inf, X)`,
/// `length(L, N)`) does not run into the answer budget. `forall` and `listall` take all answers.
pub const IF_ANSWERS: usize = 1_000;

impl Core {
    /// True (and the evaluation recorded, with no answers) when the rule provably has no
    /// answer under `base` without running its condition (exactly: see `first_lookup_fails`);
    /// else [`Core::rule_answers`] evaluates it.
    #[inline]
    pub fn rule_inapplicable(&mut self, rule: &RuleDef, base: &Subst) -> bool {
        if self.why.is_none() && first_lookup_fails(&self.ms, &rule.cond, base) {
            self.evaluated(rule, 0);
            return true;
        }
        false
    }

    /// The answers the rule's body runs for, in the order to try them (empty: not applicable),
    /// of a rule [`Core::rule_inapplicable`] did not rule out; `file` is the program file,
    /// named in warnings.
    pub fn rule_answers(
        &mut self,
        rule: &RuleDef,
        base: &Subst,
        file: &str,
    ) -> Result<Answers, Fault> {
        let cap = match rule.kind {
            RuleKind::If => IF_ANSWERS,
            RuleKind::Forall | RuleKind::Listall(_) => usize::MAX,
        };
        let mut cut = false;
        let mut answers = Answers::new();
        if rule.per_goal {
            // focus=select: evaluate per single goal and remember which goals gave each answer.
            let goals = self.ms.attention.current().goals().to_vec();
            for g in &goals {
                let cx = CondCtx {
                    ms: &self.ms,
                    only: Some(g),
                };
                let e = evaluate(&cx, &rule.cond, base, cap)?;
                if self.why.is_some() {
                    self.why_condition(&rule.cond, &e);
                }
                cut |= e.cut;
                for s in e.answers {
                    let full = answers.len() >= cap;
                    match answers.iter_mut().find(|a| a.subst == s) {
                        Some(a) => a.goals.push(g.clone()),
                        None if full => cut = true,
                        None => answers.push(Answer {
                            subst: s,
                            goals: vec![g.clone()],
                        }),
                    }
                }
            }
        } else {
            let cx = CondCtx {
                ms: &self.ms,
                only: None,
            };
            let found;
            if self.why.is_some() {
                let e = evaluate(&cx, &rule.cond, base, cap)?;
                self.why_condition(&rule.cond, &e);
                (found, cut) = (e.answers, e.cut);
            } else {
                // Where the condition failed is recorded for `goal why` alone.
                (found, cut) = answers_upto(&cx, &rule.cond, base, cap)?;
            }
            answers = answers_of(found);
        }
        if cut {
            self.warn_truncated(rule, file);
        }
        if let Some(w) = &self.why {
            w.answers(answers.len());
        }
        self.evaluated(rule, answers.len());
        match &rule.kind {
            RuleKind::If => answers.shuffle(&mut self.rng),
            RuleKind::Forall => {}
            RuleKind::Listall(v) => {
                if answers.is_empty() {
                    return Ok(answers);
                }
                let free = free_vars(rule, base);
                let items: Vec<Term> = answers
                    .iter()
                    .map(|a| match free.len() {
                        1 => a.subst.apply(&Term::Var(free[0])),
                        _ => Term::list(
                            free.iter()
                                .map(|f| a.subst.apply(&Term::Var(*f)))
                                .collect::<Vec<_>>(),
                        ),
                    })
                    .collect();
                let mut s = base.clone();
                s.bind(*v, Term::list(items));
                return Ok(smallvec![Answer {
                    subst: s,
                    goals: Vec::new(),
                }]);
            }
        }
        Ok(answers)
    }

    /// Warns (once per rule) that an `if` rule considered only the first [`IF_ANSWERS`]
    /// answers of its condition.
    fn warn_truncated(&mut self, rule: &RuleDef, file: &str) {
        let at = format!("{file}:{}", rule.line);
        if !self.truncated_rules.insert(format!("{at} {}", rule.label)) {
            return;
        }
        self.event(Event::Warning {
            message: format!(
                "{at}: the condition of rule {} has {IF_ANSWERS} answers or more; only the \
                 first {IF_ANSWERS} were considered (the condition may have infinitely many: \
                 bound its variables or use a finite generator)",
                rule.label
            ),
        });
    }

    /// Records that a rule's condition was evaluated, with its number of answers.
    #[inline(always)]
    pub(super) fn evaluated(&mut self, rule: &RuleDef, answers: usize) {
        // The level check inline, the recording out of line: most runs do not trace rules.
        if self.level >= TraceLevel::Rules {
            self.record_evaluated(rule, answers);
        }
    }

    /// [`Core::evaluated`]'s event.
    #[cold]
    #[inline(never)]
    fn record_evaluated(&mut self, rule: &RuleDef, answers: usize) {
        self.event(Event::RuleEvaluated {
            rule: rule.label.to_string(),
            answers,
        });
    }

    /// Records that a rule's body runs for an answer.
    #[inline(always)]
    pub fn fired(&mut self, rule: &RuleDef, s: &Subst) {
        if self.level >= TraceLevel::Rules {
            self.record_fired(rule, s);
        }
    }

    /// [`Core::fired`]'s event.
    #[cold]
    #[inline(never)]
    fn record_fired(&mut self, rule: &RuleDef, s: &Subst) {
        self.event(Event::RuleFired {
            rule: rule.label.to_string(),
            bindings: show_subst(s),
        });
    }
}

/// The answers a rule's body runs for from its condition's answers (no goals: no focus=select).
fn answers_of(mut found: Found) -> Answers {
    // Mostly one answer: moved over without an iterator over the inline array.
    if found.len() == 1 {
        if let Some(subst) = found.pop() {
            return smallvec![Answer {
                subst,
                goals: Vec::new(),
            }];
        }
    }
    found
        .into_iter()
        .map(|subst| Answer {
            subst,
            goals: Vec::new(),
        })
        .collect()
}

/// The variables of a rule's condition not bound by `base`, in order of occurrence.
fn free_vars(rule: &RuleDef, base: &Subst) -> Vec<Sym> {
    let mut out: Vec<Sym> = Vec::new();
    for l in &rule.cond {
        if let super::program::Lit::Mental {
            negated: false,
            query,
            ..
        } = l
        {
            for v in query.vars() {
                if base.get(v).is_none() && !out.contains(&v) && !v.name().starts_with('_') {
                    out.push(v);
                }
            }
        }
    }
    out
}
