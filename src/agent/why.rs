//! Why / why not: what each rule did in one cycle of an agent (fired with its bindings, the
//! first condition literal that failed, the action whose precondition failed, or not
//! evaluated). A [`Recorder`] installed in an agent (`Agent::set_why`) is told by small hooks
//! in the evaluation (`module.rs`, `rule.rs`, `cycle.rs`) what happened; without one the hooks
//! cost a branch each. Recording never queries in a way the agent could notice: the few
//! queries it adds (naming the failed precondition literal) run on a copy of the engine's
//! state, so a recorded run is the same run.

use super::condition::{evaluate, show_subst, CondCtx, Evaluation};
use super::cycle::Core;
use super::module::Frame;
use super::program::{Act, Lit, Program};
use crate::syntax::ast::{self, MentalOp};
use crate::term::{Subst, Term};
use serde::Serialize;
use std::sync::{Arc, Mutex};

/// How many of the answers before a failed literal are kept (the rest are counted).
const KEPT_BEFORE: usize = 10;

/// Collects what one agent's rules did in its latest cycle; shared between the agent (which
/// runs on a worker thread) and whoever asked (cheap to clone).
#[derive(Clone, Debug, Default)]
pub struct Recorder {
    shared: Arc<Mutex<Shared>>,
}

#[derive(Debug, Default)]
struct Shared {
    tick: u64,
    cycle: Option<CycleRecord>,
}

/// What the rules did in one cycle (raw; [`CycleRecord::explain`] makes the report).
#[derive(Clone, Debug, Default)]
pub struct CycleRecord {
    /// The agent's cycle number (1 = its first cycle).
    pub cycle: u64,
    /// The tick the cycle ran at.
    pub tick: u64,
    evals: Vec<Eval>,
    /// Every firing in order: rule label and bindings (as the trace's `rule_fired` events).
    pub fired: Vec<(String, String)>,
}

/// One evaluation of a rule (or a firing of a rule evaluated in an earlier cycle).
#[derive(Clone, Debug)]
struct Eval {
    phase: &'static str,
    /// Module frames on the stack (1: the bottom module).
    depth: usize,
    block: usize,
    rule: usize,
    /// The innermost named module.
    module: String,
    /// The first failed literal, the answers before it (at most [`KEPT_BEFORE`]) and how many
    /// there were.
    failed: Option<(usize, Vec<Subst>, usize)>,
    /// The first conjunct of the failed `bel` literal's query that failed (instantiated) and
    /// the bindings up to it.
    conjunct: Option<(String, String)>,
    /// Answers of the condition; `None`: the evaluation did not finish (a runtime error), or
    /// the condition was evaluated in an earlier cycle.
    answers: Option<usize>,
    firings: Vec<Firing>,
    /// Fired in this cycle for answers computed in an earlier one.
    resumed: bool,
}

#[derive(Clone, Debug)]
struct Firing {
    bindings: String,
    not_run: Option<NotRun>,
}

/// An action of a combo that did not run.
#[derive(Clone, Debug)]
struct NotRun {
    /// The action as called.
    call: String,
    /// The precondition literal that failed (instantiated), when one can be named.
    literal: Option<String>,
    reason: String,
}

impl Recorder {
    /// A recorder with nothing recorded.
    pub fn new() -> Recorder {
        Recorder::default()
    }

    /// Sets the tick the next cycles run at (the run's driver calls it between rounds).
    pub fn set_tick(&self, tick: u64) {
        if let Ok(mut s) = self.shared.lock() {
            s.tick = tick;
        }
    }

    /// The latest cycle recorded.
    pub fn latest(&self) -> Option<CycleRecord> {
        self.shared.lock().ok()?.cycle.clone()
    }

    /// A cycle begins: it replaces the one recorded before.
    pub(crate) fn begin(&self, cycle: u64) {
        if let Ok(mut s) = self.shared.lock() {
            let tick = s.tick;
            s.cycle = Some(CycleRecord {
                cycle,
                tick,
                ..CycleRecord::default()
            });
        }
    }

    fn with(&self, f: impl FnOnce(&mut CycleRecord)) {
        if let Ok(mut s) = self.shared.lock() {
            if let Some(c) = s.cycle.as_mut() {
                f(c);
            }
        }
    }

    /// The condition of the rule being evaluated was evaluated (once, or once per goal):
    /// remembers the failure that got furthest.
    fn condition(&self, e: &Evaluation, conjunct: Option<(String, String)>) {
        let Some((i, before)) = &e.failed else { return };
        self.with(|c| {
            let Some(ev) = c.evals.last_mut() else { return };
            if ev.failed.as_ref().is_none_or(|f| f.0 < *i) {
                let kept = before.iter().take(KEPT_BEFORE).cloned().collect();
                ev.failed = Some((*i, kept, before.len()));
                ev.conjunct = conjunct;
            }
        });
    }

    /// The rule being evaluated has `n` answers.
    pub(crate) fn answers(&self, n: usize) {
        self.with(|c| {
            if let Some(ev) = c.evals.last_mut() {
                ev.answers = Some(n);
            }
        });
    }
}

/// `bel(q)` for each query `q`.
fn bel_literals(queries: &[Term]) -> Vec<Lit> {
    queries
        .iter()
        .map(|q| Lit::Mental {
            negated: false,
            top_level: false,
            about: None,
            op: MentalOp::Bel,
            query: q.clone(),
        })
        .collect()
}

/// Where in the program the top of `stack` runs: phase (from the bottom module), module frames,
/// innermost named module.
fn place(prog: &Program, stack: &[Frame]) -> (&'static str, usize, String) {
    use super::program::ModuleKind;
    let phase = match stack.first() {
        Some(Frame::Module(f)) => match f.module.map(|m| prog.modules[m].kind) {
            Some(ModuleKind::Init) => "init",
            Some(ModuleKind::Event) => "event",
            Some(ModuleKind::Main) => "main",
            _ => "task",
        },
        _ => "task",
    };
    let depth = stack
        .iter()
        .filter(|f| matches!(f, Frame::Module(_)))
        .count();
    let module = stack
        .iter()
        .rev()
        .find_map(|f| match f {
            Frame::Module(m) => m.module.map(|i| prog.modules[i].name.clone()),
            _ => None,
        })
        .unwrap_or_default();
    (phase, depth, module)
}

impl Core {
    /// Hook: rule `rule` of block `block` is about to be evaluated on top of `stack`.
    pub(crate) fn why_evaluating(
        &mut self,
        prog: &Program,
        stack: &[Frame],
        block: usize,
        rule: usize,
    ) {
        let Some(w) = &self.why else { return };
        let (phase, depth, module) = place(prog, stack);
        w.with(|c| {
            c.evals.push(Eval {
                phase,
                depth,
                block,
                rule,
                module,
                failed: None,
                conjunct: None,
                answers: None,
                firings: Vec::new(),
                resumed: false,
            })
        });
    }

    /// Hook: the condition `cond` of the rule being evaluated was evaluated to `e`. When a
    /// `bel` literal with a conjunction failed, its conjuncts are evaluated one at a time (on
    /// a copy of the engine state) to name the first that failed.
    pub(crate) fn why_condition(&self, cond: &[Lit], e: &Evaluation) {
        let Some(w) = &self.why else { return };
        let conjunct = match &e.failed {
            Some((i, before)) => {
                let saved = self.ms.engine.borrow().clone();
                let found = self.failed_conjunct(&cond[*i], before);
                *self.ms.engine.borrow_mut() = saved;
                found
            }
            None => None,
        };
        w.condition(e, conjunct);
    }

    /// The first conjunct of `lit`'s query that fails after the answers `before` (the one
    /// that got furthest), instantiated, with the bindings up to it.
    fn failed_conjunct(&self, lit: &Lit, before: &[Subst]) -> Option<(String, String)> {
        let Lit::Mental {
            negated: false,
            about: None,
            op: MentalOp::Bel,
            query,
            ..
        } = lit
        else {
            return None;
        };
        let parts: Vec<Term> = query.conjuncts().into_iter().cloned().collect();
        if parts.len() < 2 {
            return None;
        }
        let lits = bel_literals(&parts);
        let cx = CondCtx {
            ms: &self.ms,
            only: None,
        };
        let mut best: Option<(usize, Subst)> = None;
        for base in before.iter().take(KEPT_BEFORE) {
            if let Ok(Evaluation {
                failed: Some((j, at)),
                ..
            }) = evaluate(&cx, &lits, base, crate::agent::rule::IF_ANSWERS)
            {
                if best.as_ref().is_none_or(|b| b.0 < j) {
                    best = at.into_iter().next().map(|s| (j, s));
                }
            }
        }
        let (j, s) = best?;
        Some((s.apply(&parts[j]).to_string(), show_subst(&s)))
    }

    /// Hook: the rule fires for answer `s` (its rule frame is on top of `stack`).
    pub(crate) fn why_fired(
        &mut self,
        prog: &Program,
        stack: &[Frame],
        (block, rule): (usize, usize),
        s: &Subst,
    ) {
        let Some(w) = &self.why else { return };
        let (phase, depth, module) = place(prog, stack);
        let label = prog.blocks[block].rules[rule].label.to_string();
        let bindings = show_subst(s);
        w.with(|c| {
            c.fired.push((label, bindings.clone()));
            let at = c
                .evals
                .iter()
                .rposition(|e| (e.depth, e.block, e.rule) == (depth, block, rule));
            let ev = match at {
                Some(i) => &mut c.evals[i],
                None => {
                    c.evals.push(Eval {
                        phase,
                        depth,
                        block,
                        rule,
                        module,
                        failed: None,
                        conjunct: None,
                        answers: None,
                        firings: Vec::new(),
                        resumed: true,
                    });
                    let last = c.evals.len() - 1;
                    &mut c.evals[last]
                }
            };
            ev.firings.push(Firing {
                bindings,
                not_run: None,
            });
        });
    }

    /// Hook: action `act` of the rule's combo did not run for answer `s` (precondition false,
    /// or an `adopt` of a goal already there or believed). Names the precondition literal
    /// that failed by evaluating the conjuncts one at a time on a copy of the engine state.
    pub(crate) fn why_not_run(
        &mut self,
        prog: &Program,
        stack: &[Frame],
        (block, rule): (usize, usize),
        act: &Act,
        s: &Subst,
    ) {
        if self.why.is_none() {
            return;
        }
        let saved = self.ms.engine.borrow().clone();
        let not_run = self.not_run(prog, act, s);
        *self.ms.engine.borrow_mut() = saved;
        let depth = place(prog, stack).1;
        let Some(w) = &self.why else { return };
        w.with(|c| {
            let ev = c
                .evals
                .iter_mut()
                .rev()
                .find(|e| (e.depth, e.block, e.rule) == (depth, block, rule));
            if let Some(f) = ev.and_then(|e| e.firings.last_mut()) {
                f.not_run = Some(not_run);
            }
        });
    }

    fn not_run(&self, prog: &Program, act: &Act, s: &Subst) -> NotRun {
        match act {
            Act::Spec { spec, args } => {
                let spec = &prog.specs[*spec];
                let call = Term::compound(spec.name, args.iter().map(|a| s.apply(a)).collect());
                let mut m = Subst::new();
                for (p, a) in spec.params.iter().zip(call.args()) {
                    m.unify(p, a, false);
                }
                let pre = m.apply(&spec.pre);
                let parts: Vec<Term> = pre.conjuncts().into_iter().cloned().collect();
                let lits = bel_literals(&parts);
                let cx = CondCtx {
                    ms: &self.ms,
                    only: None,
                };
                let literal = match evaluate(&cx, &lits, &Subst::new(), usize::MAX) {
                    Ok(Evaluation {
                        failed: Some((i, before)),
                        ..
                    }) => before.first().map(|b| b.apply(&parts[i]).to_string()),
                    _ => None,
                };
                NotRun {
                    call: call.to_string(),
                    literal,
                    reason: "its precondition does not hold".into(),
                }
            }
            Act::Adopt { top_level, content } => {
                let g = s.apply(content);
                let base = if *top_level {
                    self.ms.attention.top_level()
                } else {
                    self.ms.attention.current()
                };
                let reason = if self.ms.is_goal_in(base, &g).unwrap_or(false) {
                    "it is already a goal"
                } else {
                    "it is already believed"
                };
                NotRun {
                    call: Term::compound("adopt", vec![g]).to_string(),
                    literal: None,
                    reason: reason.into(),
                }
            }
            _ => NotRun {
                call: String::new(),
                literal: None,
                reason: "it did not run".into(),
            },
        }
    }
}

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
    use super::program::Body;
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
    use super::program::About;
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

/// The source text of a rule on one line; a nested block's rules are elided (`{ ... }`).
pub(crate) fn rule_text(source: &str, r: &ast::Rule) -> String {
    let end = match &r.body {
        ast::RuleBody::Block(rules) => rules.first().map(|f| f.span.start),
        ast::RuleBody::Combo(_) => None,
    };
    match end.and_then(|e| source.get(r.span.start..e)) {
        Some(head) => format!("{} ... }}", one_line(head)),
        None => one_line(source.get(r.span.clone()).unwrap_or("")),
    }
}

/// `text` on one line: comments (`% ...`, `/* ... */`) left out, each run of white space one
/// space; quoted text is kept as written.
pub(crate) fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut quote: Option<char> = None;
    let mut space = false;
    while let Some(c) = chars.next() {
        if let Some(q) = quote {
            out.push(c);
            if c == '\\' {
                if let Some(n) = chars.next() {
                    out.push(n);
                }
            } else if c == q {
                quote = None;
            }
            continue;
        }
        match c {
            '%' => {
                for n in chars.by_ref() {
                    if n == '\n' {
                        break;
                    }
                }
                space = true;
                continue;
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                let mut prev = ' ';
                for n in chars.by_ref() {
                    if prev == '*' && n == '/' {
                        break;
                    }
                    prev = n;
                }
                space = true;
                continue;
            }
            c if c.is_whitespace() => {
                space = true;
                continue;
            }
            _ => {}
        }
        if space && !out.is_empty() {
            out.push(' ');
        }
        space = false;
        if matches!(c, '\'' | '"' | '`') {
            quote = Some(c);
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::one_line;

    #[test]
    fn one_line_drops_comments_and_keeps_quotes() {
        let text = "if bel(a), % why\n   bel('x  % y') /* c */ then\n\tinsert(\"b  c\").";
        assert_eq!(
            one_line(text),
            "if bel(a), bel('x  % y') then insert(\"b  c\")."
        );
    }
}
