//! Why / why not: what each rule did in one cycle of an agent (fired with its bindings, the
//! first condition literal that failed, the action whose precondition failed, or not
//! evaluated). A [`Recorder`] installed in an agent (`Agent::set_why`) is told by small hooks
//! in the evaluation (`module.rs`, `rule.rs`, `cycle.rs`) what happened; without one the hooks
//! cost a branch each. Recording never queries in a way the agent could notice: the few
//! queries it adds (naming the failed precondition literal) run on a copy of the engine's
//! state, so a recorded run is the same run.

use crate::agent::condition::{evaluate, show_subst, CondCtx, Evaluation};

mod report;
mod text;
use crate::agent::cycle::Core;
use crate::agent::module::Frame;
use crate::agent::program::{Act, Lit, Program};
use crate::syntax::ast::MentalOp;
use crate::term::{Subst, Term};
pub use report::{lit_text, LiteralWhy, Outcome, RuleWhy};
use std::sync::{Arc, Mutex};
pub(crate) use text::{one_line, rule_text};

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
            plan: Default::default(),
        })
        .collect()
}

/// Where in the program the top of `stack` runs: phase (from the bottom module), module frames,
/// innermost named module.
fn place(prog: &Program, stack: &[Frame]) -> (&'static str, usize, String) {
    use crate::agent::program::ModuleKind;
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
