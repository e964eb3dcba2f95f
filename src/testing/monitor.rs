//! Test conditions and the temporal conditions of `evaluate` sections (the README's
//! "Testing agents"), checked at every observable event: `always`, `never`, `eventually`, `atend`,
//! `watch`, chains `P -> Q` and `reactTo(P, Q)`.

use crate::agent::condition::{eval, show_subst, CondCtx};
use crate::agent::mental_state::MentalState;
use crate::agent::program::Lit;
use crate::syntax::test2g::ast::TemporalOp;
use crate::term::{Subst, Term};

/// A compiled test condition: mental literals plus an optional `do(Action)` test.
#[derive(Clone, Debug)]
pub struct Cond {
    pub lits: Vec<Lit>,
    /// `(negated, action pattern)`.
    pub done: Option<(bool, Term)>,
    /// The condition as written in the test file.
    pub text: String,
    /// 1-based line in the test file.
    pub line: usize,
}

impl Cond {
    /// The answers of the condition now, extending `base`; `last` is the last executed action.
    pub fn answers(
        &self,
        ms: &MentalState,
        base: &Subst,
        last: Option<&Term>,
    ) -> Result<Vec<Subst>, String> {
        let mut start = base.clone();
        if let Some((false, pattern)) = &self.done {
            match last {
                Some(a) if start.unify(pattern, a, false) => {}
                _ => return Ok(Vec::new()),
            }
        }
        let cx = CondCtx { ms, only: None };
        let mut answers = eval(&cx, &self.lits, &start).map_err(|f| f.message)?;
        if let Some((true, pattern)) = &self.done {
            answers.retain(|s| match last {
                None => true,
                Some(a) => !s.clone().unify(pattern, a, false),
            });
        }
        Ok(answers)
    }
}

/// One part of a chain: an operator and its condition.
#[derive(Clone, Debug)]
pub struct Part {
    pub op: TemporalOp,
    pub cond: Cond,
}

/// A temporal condition: a chain of parts (`reactTo(P, Q)` is `P -> eventually Q`).
#[derive(Clone, Debug)]
pub struct Temporal {
    pub parts: Vec<Part>,
    /// The whole condition as written.
    pub text: String,
}

/// `until C` (stop when C holds) or `while C` (stop when C no longer holds).
#[derive(Clone, Debug)]
pub struct Boundary {
    pub until: bool,
    pub cond: Cond,
}

/// Why an evaluation failed.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    pub condition: String,
    pub line: usize,
    pub reason: String,
    pub bindings: Option<String>,
    pub cycle: u64,
}

/// A live instance of a chain part, with the bindings of the trigger that created it.
struct Instance {
    temporal: usize,
    part: usize,
    base: Subst,
    /// Trigger parts: the answers at the previous event (only new answers start instances).
    previous: Vec<String>,
    finished: bool,
}

/// Bound on live instances per evaluation (memory stays bounded on long runs).
const MAX_INSTANCES: usize = 10_000;
/// Bound on recorded `watch` lines.
const MAX_WATCH: usize = 1_000;

/// The state of one `evaluate` section while its action runs.
pub struct Evaluation {
    temporals: Vec<Temporal>,
    instances: Vec<Instance>,
    boundary: Option<Boundary>,
    /// Set once the boundary was reached (later events are ignored).
    pub boundary_reached: bool,
    /// Set at the first violation (later events are ignored).
    pub violation: Option<Violation>,
    /// Lines printed by `watch` conditions.
    pub watch: Vec<String>,
    /// Number of actions seen, to tell two equal actions in a row apart.
    actions: u64,
}

fn key(s: &Subst, action: u64, with_do: bool) -> String {
    if with_do {
        format!("{}#{action}", show_subst(s))
    } else {
        show_subst(s)
    }
}

fn bindings(s: &Subst) -> Option<String> {
    let text = show_subst(s);
    (!text.is_empty()).then_some(text)
}

impl Evaluation {
    /// Starts evaluating `temporals` with an optional boundary.
    pub fn new(temporals: Vec<Temporal>, boundary: Option<Boundary>) -> Evaluation {
        let instances = (0..temporals.len())
            .map(|t| Instance {
                temporal: t,
                part: 0,
                base: Subst::new(),
                previous: Vec::new(),
                finished: false,
            })
            .collect();
        Evaluation {
            temporals,
            instances,
            boundary,
            boundary_reached: false,
            violation: None,
            watch: Vec::new(),
            actions: 0,
        }
    }

    fn active(&self) -> bool {
        !self.boundary_reached && self.violation.is_none()
    }

    fn violate(&mut self, cond: &Cond, whole: &str, reason: String, b: Option<String>, cycle: u64) {
        let condition = if whole == cond.text {
            cond.text.clone()
        } else {
            format!("{} (in `{whole}`)", cond.text)
        };
        self.violation = Some(Violation {
            condition,
            line: cond.line,
            reason,
            bindings: b,
            cycle,
        });
    }

    /// Checks every live instance at an observable event (`what` describes it).
    pub fn event(
        &mut self,
        ms: &MentalState,
        last: Option<&Term>,
        is_action: bool,
        cycle: u64,
        what: &str,
    ) {
        if !self.active() {
            return;
        }
        if is_action {
            self.actions += 1;
        }
        let mut i = 0;
        while i < self.instances.len() && self.violation.is_none() {
            if self.instances[i].finished {
                i += 1;
                continue;
            }
            let (t, p) = (self.instances[i].temporal, self.instances[i].part);
            let part = self.temporals[t].parts[p].clone();
            let whole = self.temporals[t].text.clone();
            let answers = match part.cond.answers(ms, &self.instances[i].base, last) {
                Ok(a) => a,
                Err(e) => {
                    let b = bindings(&self.instances[i].base);
                    self.violate(&part.cond, &whole, format!("error: {e}"), b, cycle);
                    return;
                }
            };
            if p + 1 < self.temporals[t].parts.len() {
                // A trigger: each new answer starts an instance of the next part.
                let with_do = part.cond.done.is_some();
                let keys: Vec<String> = answers
                    .iter()
                    .map(|a| key(a, self.actions, with_do))
                    .collect();
                for (a, k) in answers.iter().zip(&keys) {
                    if !self.instances[i].previous.contains(k)
                        && self.instances.len() < MAX_INSTANCES
                    {
                        self.instances.push(Instance {
                            temporal: t,
                            part: p + 1,
                            base: a.clone(),
                            previous: Vec::new(),
                            finished: false,
                        });
                    }
                }
                self.instances[i].previous = keys;
                i += 1;
                continue;
            }
            let base = self.instances[i].base.clone();
            match part.op {
                TemporalOp::Always if answers.is_empty() => {
                    let reason = format!("`always` condition did not hold at {what}");
                    self.violate(&part.cond, &whole, reason, bindings(&base), cycle);
                }
                TemporalOp::Never => {
                    if let Some(a) = answers.first() {
                        let reason = format!("`never` condition held at {what}");
                        self.violate(&part.cond, &whole, reason, bindings(a), cycle);
                    }
                }
                TemporalOp::Eventually if !answers.is_empty() => {
                    self.instances[i].finished = true;
                }
                TemporalOp::AtStart => {
                    if answers.is_empty() {
                        let reason = format!("`atstart` condition did not hold at {what}");
                        self.violate(&part.cond, &whole, reason, bindings(&base), cycle);
                    }
                    self.instances[i].finished = true;
                }
                TemporalOp::Watch if self.watch.len() < MAX_WATCH => {
                    for a in &answers {
                        let b = bindings(a).unwrap_or_else(|| "true".into());
                        self.watch.push(format!(
                            "cycle {cycle}, {what}: {} with {b}",
                            part.cond.text
                        ));
                    }
                }
                _ => {}
            }
            i += 1;
        }
        self.instances.retain(|x| !x.finished);
        self.check_boundary(ms, last);
    }

    /// Checks the boundary now; true once it has been reached.
    pub fn check_boundary(&mut self, ms: &MentalState, last: Option<&Term>) -> bool {
        if self.boundary_reached {
            return true;
        }
        if let Some(b) = &self.boundary {
            // An error in the boundary counts as "does not hold".
            let holds = b
                .cond
                .answers(ms, &Subst::new(), last)
                .is_ok_and(|a| !a.is_empty());
            if holds == b.until {
                self.boundary_reached = true;
            }
        }
        self.boundary_reached
    }

    /// The end of the evaluated run: `eventually` parts that never held fail, `atend` parts
    /// are checked now.
    pub fn finish(&mut self, ms: &MentalState, last: Option<&Term>, cycle: u64) {
        if self.violation.is_some() {
            return;
        }
        let pending: Vec<(usize, usize, Subst)> = self
            .instances
            .iter()
            .filter(|x| !x.finished && x.part + 1 == self.temporals[x.temporal].parts.len())
            .map(|x| (x.temporal, x.part, x.base.clone()))
            .collect();
        for (t, p, base) in pending {
            let part = self.temporals[t].parts[p].clone();
            let whole = self.temporals[t].text.clone();
            match part.op {
                TemporalOp::Eventually => {
                    let reason = "`eventually` condition never held before the run ended".into();
                    self.violate(&part.cond, &whole, reason, bindings(&base), cycle);
                }
                TemporalOp::AtEnd => match part.cond.answers(ms, &base, last) {
                    Ok(a) if !a.is_empty() => {}
                    Ok(_) => {
                        let reason = "`atend` condition did not hold when the run ended".into();
                        self.violate(&part.cond, &whole, reason, bindings(&base), cycle);
                    }
                    Err(e) => {
                        self.violate(&part.cond, &whole, format!("error: {e}"), None, cycle);
                    }
                },
                _ => {}
            }
            if self.violation.is_some() {
                return;
            }
        }
    }
}
