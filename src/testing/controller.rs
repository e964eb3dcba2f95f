//! The test controller of one tested agent: compiles a named test's sections against the
//! agent's program and runs them in sequence between the agent's cycles: `do` runs actions or module calls as a task, `assert` checks a condition now,
//! `evaluate` runs a task while a [`Monitor`] checks its temporal conditions at every event.

use super::monitor::{Boundary, Cond, Evaluation, Part, Temporal};
use super::report::{Failure, Outcome};
use crate::agent::message::wrap_mood;
use crate::agent::{Agent, Observed, Program, StopReason, Watcher};
use crate::diag::{line_col, Diagnostic, Span};
use crate::syntax::ast::{Action, ActionKind, BuiltinModule, Literal};
use crate::syntax::test2g::ast::{TemporalCondition, TemporalOp, TestCondition, TestSection};
use crate::term::{Subst, Term};
use std::sync::{Arc, Mutex, MutexGuard};

/// One compiled section.
enum Step {
    Do {
        block: usize,
        line: usize,
    },
    Assert {
        cond: Cond,
        message: Option<String>,
        line: usize,
    },
    Evaluate {
        block: usize,
        temporals: Vec<Temporal>,
        boundary: Option<Boundary>,
        line: usize,
    },
}

/// The ground action term an agent reports for an executed action, as a pattern.
fn action_pattern(a: &Action) -> Term {
    match &a.kind {
        ActionKind::Adopt { content, .. } => Term::compound("adopt", vec![content.term.clone()]),
        ActionKind::Drop { content, .. } => Term::compound("drop", vec![content.term.clone()]),
        ActionKind::Insert { content, .. } => Term::compound("insert", vec![content.term.clone()]),
        ActionKind::Delete { content, .. } => Term::compound("delete", vec![content.term.clone()]),
        ActionKind::Send { mood, content, .. } => {
            Term::compound("send", vec![wrap_mood(*mood, content.term.clone())])
        }
        ActionKind::SendOnce { mood, content, .. } => {
            Term::compound("sendonce", vec![wrap_mood(*mood, content.term.clone())])
        }
        ActionKind::Print(t) => Term::compound("print", vec![t.term.clone()]),
        ActionKind::Log(t) => Term::compound("log", vec![t.term.clone()]),
        ActionKind::ExitModule => Term::atom("exit-module"),
        ActionKind::Call { name, args } if args.is_empty() => Term::Atom(name.name),
        ActionKind::Call { name, args } => {
            Term::compound(name.name, args.iter().map(|l| l.term.clone()).collect())
        }
        ActionKind::Timing { op, args } => {
            Term::compound(op.name(), args.iter().map(|l| l.term.clone()).collect())
        }
        ActionKind::BuiltinModule(b) => Term::atom(match b {
            BuiltinModule::Init => "init",
            BuiltinModule::Main => "main",
            BuiltinModule::Event => "event",
        }),
    }
}

/// Collects the code of a test for one `Program::extend` call, remembering indices.
struct Collector<'a> {
    source: &'a str,
    combos: Vec<Vec<Action>>,
    conds: Vec<Vec<Literal>>,
}

/// A condition before compilation: index of its literals, `do` test, text and line.
struct RawCond {
    lits: usize,
    done: Option<(bool, Term)>,
    text: String,
    line: usize,
}

enum RawStep {
    Do(usize, usize),
    Assert(RawCond, Option<String>, usize),
    Evaluate(
        usize,
        Vec<(Vec<(TemporalOp, RawCond)>, String)>,
        Option<(bool, RawCond)>,
        usize,
    ),
}

impl Collector<'_> {
    fn line(&self, span: &Span) -> usize {
        line_col(self.source, span.start).0
    }
    fn text(&self, span: &Span) -> String {
        let t = self.source.get(span.clone()).unwrap_or("");
        // A reaction's span starts at the comma after the trigger.
        let t = t.trim_start_matches(|c: char| c == ',' || c.is_whitespace());
        t.split_whitespace().collect::<Vec<_>>().join(" ")
    }
    fn combo(&mut self, c: &[Action]) -> usize {
        self.combos.push(c.to_vec());
        self.combos.len() - 1
    }
    fn cond(&mut self, c: &TestCondition, span: &Span) -> RawCond {
        self.conds.push(c.literals.clone());
        RawCond {
            lits: self.conds.len() - 1,
            done: c
                .done
                .as_ref()
                .map(|d| (d.negated, action_pattern(&d.action))),
            text: self.text(span),
            line: self.line(span),
        }
    }
    fn section(&mut self, s: &TestSection) -> RawStep {
        match s {
            TestSection::Do { combo, span } => RawStep::Do(self.combo(combo), self.line(span)),
            TestSection::Assert {
                condition,
                message,
                span,
            } => {
                let c = TestCondition {
                    literals: condition.clone(),
                    done: None,
                    span: span.clone(),
                };
                let cond_span = match (condition.first(), condition.last()) {
                    (Some(a), Some(b)) => a.span.start..b.span.end,
                    _ => span.clone(),
                };
                let rc = self.cond(&c, &cond_span);
                let msg = message.as_ref().map(|m| m.value.clone());
                RawStep::Assert(rc, msg, self.line(span))
            }
            TestSection::Evaluate {
                conditions,
                combo,
                boundary,
                span,
            } => {
                let block = self.combo(combo);
                let mut temporals = Vec::new();
                for tc in conditions {
                    match tc {
                        TemporalCondition::Chain { parts, span } => {
                            let ps = parts
                                .iter()
                                .map(|p| (p.op, self.cond(&p.condition, &p.span)))
                                .collect();
                            temporals.push((ps, self.text(span)));
                        }
                        TemporalCondition::ReactTo {
                            trigger,
                            reaction,
                            span,
                        } => {
                            let t = self.cond(trigger, &trigger.span);
                            let r = self.cond(reaction, &reaction.span);
                            temporals.push((
                                vec![(TemporalOp::Always, t), (TemporalOp::Eventually, r)],
                                self.text(span),
                            ));
                        }
                    }
                }
                let b = boundary
                    .as_ref()
                    .map(|b| (b.until, self.cond(&b.condition, &b.condition.span)));
                RawStep::Evaluate(block, temporals, b, self.line(span))
            }
        }
    }
}

/// What the watcher shares with the controller.
#[derive(Default)]
struct Shared {
    last: Option<Term>,
    cycle: u64,
    eval: Option<Evaluation>,
}

struct Hook(Arc<Mutex<Shared>>);

fn lock(m: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Watcher for Hook {
    fn observe(&mut self, ms: &crate::agent::mental_state::MentalState, at: Observed<'_>) {
        let mut g = lock(&self.0);
        let what = match at {
            Observed::Action(t) => {
                g.last = Some(t.clone());
                format!("action {t}")
            }
            Observed::ModuleEntered(m) => format!("entry of module {m}"),
            Observed::ModuleExited(m) => format!("exit of module {m}"),
        };
        let Shared { last, cycle, eval } = &mut *g;
        if let Some(e) = eval.as_mut() {
            e.event(
                ms,
                last.as_ref(),
                matches!(at, Observed::Action(_)),
                *cycle,
                &what,
            );
        }
    }
}

/// Runs one named test (its sections in order) on one agent.
pub struct Controller {
    steps: Vec<Step>,
    pos: usize,
    shared: Arc<Mutex<Shared>>,
    outcome: Option<Outcome>,
    started: bool,
    /// Lines printed by `watch` conditions.
    pub watch: Vec<String>,
}

impl Controller {
    /// Compiles `sections` (from test file `file` with text `source`) against `program`;
    /// returns the extended program the agent must run, and the controller.
    pub fn compile(
        program: &Program,
        file: &str,
        source: &str,
        sections: &[&TestSection],
    ) -> Result<(Arc<Program>, Controller), Vec<Diagnostic>> {
        let mut c = Collector {
            source,
            combos: Vec::new(),
            conds: Vec::new(),
        };
        let raw: Vec<RawStep> = sections.iter().map(|s| c.section(s)).collect();
        let ext = program.extend(file, source, &c.combos, &c.conds)?;
        let cond = |r: RawCond| Cond {
            lits: ext.conditions[r.lits].clone(),
            done: r.done,
            text: r.text,
            line: r.line,
        };
        let steps = raw
            .into_iter()
            .map(|r| match r {
                RawStep::Do(b, line) => Step::Do {
                    block: ext.blocks[b],
                    line,
                },
                RawStep::Assert(rc, message, line) => Step::Assert {
                    cond: cond(rc),
                    message,
                    line,
                },
                RawStep::Evaluate(b, ts, bound, line) => Step::Evaluate {
                    block: ext.blocks[b],
                    temporals: ts
                        .into_iter()
                        .map(|(parts, text)| Temporal {
                            parts: parts
                                .into_iter()
                                .map(|(op, rc)| Part { op, cond: cond(rc) })
                                .collect(),
                            text,
                        })
                        .collect(),
                    boundary: bound.map(|(until, rc)| Boundary {
                        until,
                        cond: cond(rc),
                    }),
                    line,
                },
            })
            .collect();
        let ctl = Controller {
            steps,
            pos: 0,
            shared: Arc::new(Mutex::new(Shared::default())),
            outcome: None,
            started: false,
            watch: Vec::new(),
        };
        Ok((ext.program, ctl))
    }

    /// Takes control of `agent` (call once, before its first cycle).
    pub fn attach(&self, agent: &mut Agent) {
        agent.control();
        agent.set_watcher(Some(Box::new(Hook(self.shared.clone()))));
    }

    /// The outcome once the test is over.
    pub fn outcome(&self) -> Option<&Outcome> {
        self.outcome.as_ref()
    }

    /// 1-based index of the running section (0 before the first).
    pub fn section(&self) -> usize {
        if self.started {
            self.pos + 1
        } else {
            0
        }
    }

    /// True while the agent must be stepped even without new input (a task is running).
    pub fn busy(&self, agent: &Agent) -> bool {
        self.outcome.is_none() && (!self.started || agent.task_running())
    }

    /// Call before each cycle of the agent.
    pub fn before_step(&self, agent: &Agent) {
        lock(&self.shared).cycle = agent.cycles() + 1;
    }

    fn fail(
        &mut self,
        agent: &mut Agent,
        kind: &str,
        line: usize,
        condition: String,
        reason: String,
        bindings: Option<String>,
    ) {
        agent.abort_task();
        lock(&self.shared).eval = None;
        self.outcome = Some(Outcome::Failed(Failure {
            section: self.pos + 1,
            kind: kind.into(),
            line,
            condition,
            reason,
            bindings,
            cycle: agent.cycles(),
        }));
    }

    /// Stops the test because a bound ran out.
    pub fn time_out(&mut self, agent: &mut Agent, reason: &str) {
        if self.outcome.is_some() {
            return;
        }
        agent.abort_task();
        self.collect_watch();
        self.outcome = Some(Outcome::TimedOut {
            reason: reason.into(),
            section: self.section(),
            cycle: agent.cycles(),
        });
    }

    fn collect_watch(&mut self) {
        if let Some(e) = lock(&self.shared).eval.as_mut() {
            self.watch.append(&mut e.watch);
        }
    }

    /// Call after each cycle of the agent: finishes the running section when its task is
    /// done and starts the next ones (asserts run at once).
    pub fn after_step(&mut self, agent: &mut Agent) {
        if self.outcome.is_some() {
            return;
        }
        let line = match self.steps.get(self.pos) {
            Some(
                Step::Do { line, .. } | Step::Assert { line, .. } | Step::Evaluate { line, .. },
            ) => *line,
            None => 0,
        };
        if let Some(StopReason::Error(e)) = agent.stopped() {
            let kind = match self.steps.get(self.pos) {
                Some(Step::Evaluate { .. }) => "evaluate",
                Some(Step::Assert { .. }) => "assert",
                _ => "do",
            };
            let reason = format!("runtime error: {e}");
            self.fail(agent, kind, line, String::new(), reason, None);
            return;
        }
        if self.started {
            match &self.steps[self.pos] {
                Step::Do { .. } => {
                    if agent.task_running() {
                        return;
                    }
                }
                Step::Evaluate { .. } => {
                    let (violation, reached) = {
                        let mut g = lock(&self.shared);
                        let Shared { last, eval, .. } = &mut *g;
                        match eval.as_mut() {
                            Some(e) => (
                                e.violation.clone(),
                                e.check_boundary(agent.mental_state(), last.as_ref()),
                            ),
                            None => (None, false),
                        }
                    };
                    if let Some(v) = violation {
                        self.collect_watch();
                        self.fail(agent, "evaluate", v.line, v.condition, v.reason, v.bindings);
                        self.outcome = self.outcome.take().map(|o| match o {
                            Outcome::Failed(mut f) => {
                                f.cycle = v.cycle;
                                Outcome::Failed(f)
                            }
                            o => o,
                        });
                        return;
                    }
                    if reached && agent.task_running() {
                        agent.abort_task();
                    }
                    if agent.task_running() {
                        return;
                    }
                    if self.end_evaluation(agent) {
                        return;
                    }
                }
                Step::Assert { .. } => {}
            }
            self.pos += 1;
        }
        self.started = true;
        self.start_next(agent);
    }

    /// Ends the running evaluation; true when it failed.
    fn end_evaluation(&mut self, agent: &mut Agent) -> bool {
        let violation = {
            let mut g = lock(&self.shared);
            let Shared { last, cycle, eval } = &mut *g;
            let cycle = (*cycle).max(agent.cycles());
            match eval.as_mut() {
                Some(e) => {
                    e.finish(agent.mental_state(), last.as_ref(), cycle);
                    e.violation.clone()
                }
                None => None,
            }
        };
        self.collect_watch();
        lock(&self.shared).eval = None;
        if let Some(v) = violation {
            self.fail(agent, "evaluate", v.line, v.condition, v.reason, v.bindings);
            if let Some(Outcome::Failed(f)) = self.outcome.as_mut() {
                f.cycle = v.cycle;
            }
            return true;
        }
        false
    }

    fn start_next(&mut self, agent: &mut Agent) {
        loop {
            let Some(step) = self.steps.get(self.pos) else {
                self.outcome = Some(Outcome::Passed);
                return;
            };
            match step {
                Step::Do { block, .. } => {
                    agent.start_task(*block);
                    return;
                }
                Step::Assert {
                    cond,
                    message,
                    line,
                } => {
                    let last = lock(&self.shared).last.clone();
                    match cond.answers(agent.mental_state(), &Subst::new(), last.as_ref()) {
                        Ok(a) if !a.is_empty() => {}
                        Ok(_) => {
                            let reason = match message {
                                Some(m) => format!("assertion failed: {m}"),
                                None => "assertion failed: the condition has no answers".into(),
                            };
                            let (l, t) = (*line, cond.text.clone());
                            self.fail(agent, "assert", l, t, reason, None);
                            return;
                        }
                        Err(e) => {
                            let (l, t) = (*line, cond.text.clone());
                            self.fail(agent, "assert", l, t, format!("error: {e}"), None);
                            return;
                        }
                    }
                    self.pos += 1;
                }
                Step::Evaluate {
                    block,
                    temporals,
                    boundary,
                    ..
                } => {
                    let mut e = Evaluation::new(temporals.clone(), boundary.clone());
                    let last = lock(&self.shared).last.clone();
                    let block = *block;
                    if e.check_boundary(agent.mental_state(), last.as_ref()) {
                        // The boundary holds already: the run is empty.
                        lock(&self.shared).eval = Some(e);
                        if self.end_evaluation(agent) {
                            return;
                        }
                        self.pos += 1;
                        continue;
                    }
                    lock(&self.shared).eval = Some(e);
                    agent.start_task(block);
                    return;
                }
            }
        }
    }
}
