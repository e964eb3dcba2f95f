//! The report of a recorded cycle: every rule of every module (and nested block) run, in
//! source order, with what it did (`goal why`'s text and JSON are made from it).

use super::{CycleRecord, Eval, NotRun};
use crate::agent::condition::show_subst;
use crate::agent::program::{Lit, Program};
use crate::syntax::ast::MentalOp;
use serde::Serialize;

/// What one rule did in the cycle, as `goal why` reports it (JSON field names are shared with
/// the browser view: do not rename them).
#[derive(Clone, Debug, Serialize)]
pub struct RuleWhy {
    /// `module:line`.
    pub rule: String,
    /// The rule's source text on one line.
    pub text: String,
    pub outcome: Outcome,
    /// The bindings it fired with, or those up to the failed literal or action.
    pub bindings: String,
    pub failed_literal: Option<String>,
    pub failed_action: Option<String>,
    /// The first conjunct of the failed `bel(...)` literal's query that failed, instantiated
    /// with `conjunct_bindings`, the bindings up to it.
    pub failed_conjunct: Option<String>,
    pub conjunct_bindings: Option<String>,
    /// The precondition literal of `failed_action` that failed, when it can be named.
    pub failed_precondition: Option<String>,
    /// Why, in words (for not evaluated, failed actions and errors).
    pub reason: Option<String>,
    /// The file and line the rule is written at.
    pub file: String,
    pub line: usize,
    /// The named module the rule was run in (its nested blocks included), and `init`,
    /// `event` or `main` (the part of the cycle).
    pub module: String,
    pub phase: String,
    /// Module nesting (1: the module the phase started in).
    pub depth: usize,
    /// For a rule of a nested block: the rule (`module:line`) whose body the block is.
    pub block_of: Option<String>,
    /// The condition's literals (macros expanded) and how each fared.
    pub literals: Vec<LiteralWhy>,
    /// Answers of the condition (fired), or partial answers that reached the failed literal.
    pub answers: usize,
    /// The bindings of every firing, in order (a `forall` fires once per answer).
    pub fired_with: Vec<String>,
}

/// How a rule fared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    Fired,
    Failed,
    PreconditionFailed,
    NotEvaluated,
    /// Evaluating the rule raised a runtime error (the agent stopped).
    Error,
}

/// One literal of a condition and how it fared.
#[derive(Clone, Debug, Serialize)]
pub struct LiteralWhy {
    pub text: String,
    /// `held`, `failed` or `not_reached`.
    pub status: &'static str,
}

/// Most firings listed per rule.
const FIRINGS_SHOWN: usize = 20;

impl CycleRecord {
    /// The rules of every module (and nested block) the cycle ran, each in source order with
    /// what it did; and the module the cycle ended in.
    pub fn explain(&self, prog: &Program) -> (String, Vec<RuleWhy>) {
        let mut sections: Vec<(&'static str, usize, usize)> = Vec::new();
        for e in &self.evals {
            let key = (e.phase, e.depth, e.block);
            if !sections.contains(&key) {
                sections.push(key);
            }
        }
        let mut out = Vec::new();
        for key in &sections {
            let evals: Vec<&Eval> = self
                .evals
                .iter()
                .filter(|e| (e.phase, e.depth, e.block) == *key)
                .collect();
            let acted = evals
                .iter()
                .rev()
                .find(|e| e.firings.iter().any(|f| f.not_run.is_none()))
                .map(|e| prog.blocks[e.block].rules[e.rule].label.to_string());
            let block = &prog.blocks[key.2];
            for (ri, rule) in block.rules.iter().enumerate() {
                let mine: Vec<&&Eval> = evals.iter().filter(|e| e.rule == ri).collect();
                if mine.is_empty() {
                    let mut r = base(prog, evals[0], ri);
                    r.literals = literals(&rule.cond, usize::MAX);
                    r.reason = Some(match &acted {
                        Some(l) => format!("not reached in this cycle: rule {l} fired first"),
                        None => "not reached in this cycle".into(),
                    });
                    out.push(r);
                }
                for e in mine {
                    out.push(rule_why(prog, e));
                }
            }
        }
        let module = self
            .evals
            .iter()
            .rev()
            .find(|e| e.phase == "main")
            .or(self.evals.last())
            .map(|e| e.module.clone())
            .unwrap_or_else(|| prog.modules[prog.main].name.clone());
        (module, out)
    }
}

/// The label of the rule whose body is the nested block `block`, if it is one.
fn block_owner(prog: &Program, block: usize) -> Option<String> {
    use crate::agent::program::Body;
    prog.blocks
        .iter()
        .flat_map(|b| &b.rules)
        .find(|r| matches!(r.body, Body::Block(i) if i == block))
        .map(|r| r.label.to_string())
}

/// A not-evaluated entry for rule `ri` of the block `e` ran in.
fn base(prog: &Program, e: &Eval, ri: usize) -> RuleWhy {
    let rule = &prog.blocks[e.block].rules[ri];
    RuleWhy {
        rule: rule.label.to_string(),
        text: rule.text.to_string(),
        outcome: Outcome::NotEvaluated,
        bindings: String::new(),
        failed_literal: None,
        failed_action: None,
        failed_conjunct: None,
        conjunct_bindings: None,
        failed_precondition: None,
        reason: None,
        file: rule.file.to_string(),
        line: rule.line,
        module: e.module.clone(),
        phase: e.phase.to_string(),
        depth: e.depth,
        block_of: block_owner(prog, e.block),
        literals: Vec::new(),
        answers: 0,
        fired_with: Vec::new(),
    }
}

fn rule_why(prog: &Program, e: &Eval) -> RuleWhy {
    let cond = &prog.blocks[e.block].rules[e.rule].cond;
    let mut r = base(prog, e, e.rule);
    r.answers = e.answers.unwrap_or(0);
    r.fired_with = e
        .firings
        .iter()
        .take(FIRINGS_SHOWN)
        .map(|f| f.bindings.clone())
        .collect();
    if let Some(f) = e.firings.iter().find(|f| f.not_run.is_none()) {
        r.outcome = Outcome::Fired;
        r.bindings = f.bindings.clone();
        r.literals = literals(cond, cond.len());
    } else if let Some(f) = e.firings.last() {
        let n = f.not_run.clone().unwrap_or(NotRun {
            call: String::new(),
            literal: None,
            reason: String::new(),
        });
        r.outcome = Outcome::PreconditionFailed;
        r.bindings = f.bindings.clone();
        r.failed_action = Some(n.call);
        r.failed_precondition = n.literal;
        r.reason = Some(n.reason);
        r.literals = literals(cond, cond.len());
    } else if let Some((i, before, n)) = &e.failed {
        r.outcome = Outcome::Failed;
        r.bindings = before.first().map(show_subst).unwrap_or_default();
        r.answers = *n;
        r.failed_literal = cond.get(*i).map(lit_text);
        if let Some((c, b)) = &e.conjunct {
            r.failed_conjunct = Some(c.clone());
            r.conjunct_bindings = Some(b.clone());
        }
        r.literals = literals(cond, *i);
    } else {
        match e.answers {
            Some(0) => {
                r.outcome = Outcome::Failed;
                r.reason = Some(
                    "its body calls a focus=select module and there is no current goal to \
                     evaluate it for"
                        .into(),
                );
            }
            Some(_) => {
                r.reason = Some("its condition held, but the cycle ended before it fired".into())
            }
            None => {
                r.outcome = Outcome::Error;
                r.reason = Some("evaluating it raised a runtime error (the agent stopped)".into());
            }
        }
        r.literals = literals(cond, usize::MAX);
    }
    if e.resumed {
        r.reason = Some("fired with answers of its condition evaluated in an earlier cycle".into());
    }
    r
}

/// The literals of a condition: those before `failed` held, `failed` failed, the rest were
/// not reached (`usize::MAX`: none reached; `cond.len()`: all held).
fn literals(cond: &[Lit], failed: usize) -> Vec<LiteralWhy> {
    cond.iter()
        .enumerate()
        .map(|(i, l)| LiteralWhy {
            text: lit_text(l),
            status: if failed == usize::MAX || i > failed {
                "not_reached"
            } else if i == failed {
                "failed"
            } else {
                "held"
            },
        })
        .collect()
}

/// A compiled literal as GOAL text, e.g. `not(bel(at(X)))` or `self.goal(g)`.
pub fn lit_text(l: &Lit) -> String {
    let Lit::Mental {
        negated,
        top_level,
        about,
        op,
        query,
        ..
    } = l
    else {
        return "true".into();
    };
    let op = match op {
        MentalOp::Bel => "bel",
        MentalOp::Goal => "goal",
        MentalOp::AGoal => "a-goal",
        MentalOp::GoalA => "goal-a",
    };
    use crate::agent::program::About;
    let who = match about {
        None if *top_level => "self.".to_string(),
        None => String::new(),
        Some(About::All) => "all.".into(),
        Some(About::AllOther) => "allother.".into(),
        Some(About::Some) => "some.".into(),
        Some(About::SomeOther) => "someother.".into(),
        Some(About::Agents(names)) => {
            let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
            format!("{}.", names.join(","))
        }
    };
    let inner = format!("{who}{op}({query})");
    if *negated {
        format!("not({inner})")
    } else {
        inner
    }
}
