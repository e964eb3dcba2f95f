//! The scryer engine: the [`Engine`] trait over scryer-prolog 0.10, for agents whose knowledge
//! needs full ISO Prolog (`catch/3`, `throw/1`, DCGs, ...).
//!
//! * Knowledge is printed once per agent (with the prelude: SWI's meaning for what scryer
//!   lacks or reads differently, see `prelude.pl` and `text.rs`) and loaded into the agent's own
//!   machines, which live on the agent's own thread (`machine.rs`; scryer machines cannot
//!   move between threads).
//! * Facts stay in scryer's database: one machine per kind of view (beliefs with percepts,
//!   mailbox and `agent/1`/`me/1`; one goal's facts; other fact bases such as mental models).
//!   Before each query the engine sends only the difference between the view's facts and
//!   what that machine holds.
//! * Memory: scryer never frees a retracted clause (about 3-4 KB each). After
//!   [`REBUILD_AFTER`] retractions a machine is started afresh and given the current facts, so
//!   belief churn costs bounded memory.
//! * Limits: the inference budget is scryer's `call_with_inference_limit/3`; the sandbox of
//!   `text.rs` keeps file, process, network and database built-ins out of reach; a panic in
//!   scryer is caught on the machine's thread and comes back as an error of the agent.

mod machine;
pub mod text;

use super::error::{KrResult, Limits};
use super::fxhash::FxHashMap;
use super::{Engine, View};
use crate::term::{Subst, Sym, Term};
use machine::{Request, Worker};
use std::time::{Duration, Instant};

/// The longest a query may run on scryer when the limits set no earlier deadline: the
/// backstop for work scryer's inference count does not bound.
pub const BACKSTOP: Duration = Duration::from_secs(60);

/// Retracted clauses a machine may leak before it is rebuilt (about 3.4 KB each: ~70 MB).
pub const REBUILD_AFTER: u64 = 20_000;

const PRELUDE: &str = include_str!("prelude.pl");

/// The facts one machine holds, in the order it holds them (a fact in two bases is there
/// twice and answers twice, as on the native engine).
#[derive(Default)]
struct Mirror {
    facts: Vec<Term>,
    retracted: u64,
}

/// A scryer-backed engine for one agent.
pub struct ScryerEngine {
    /// Resource limits (the inference budget is applied by scryer).
    pub limits: Limits,
    program: String,
    worker: Option<Worker>,
    /// The worker whose query outlived its time and still runs: scryer cannot stop it, so
    /// no new thread starts while it runs (one per agent at most, never a pile of them).
    stuck: Option<Worker>,
    mirrors: Vec<Mirror>,
    output: String,
    /// Number of machines rebuilt because of leaked memory (for reports and tests).
    pub rebuilds: u64,
    /// Retractions after which a machine is rebuilt ([`REBUILD_AFTER`]).
    pub rebuild_after: u64,
    /// The longest one query may run ([`BACKSTOP`]; an earlier deadline of the limits wins).
    pub backstop: Duration,
}

impl std::fmt::Debug for ScryerEngine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScryerEngine")
            .field("limits", &self.limits)
            .finish()
    }
}

impl ScryerEngine {
    /// An engine for knowledge `clauses` (as written: DCG rules, `catch/3`, ...). Refuses
    /// clauses that call built-ins outside the sandbox.
    pub fn new(clauses: &[Term]) -> KrResult<ScryerEngine> {
        let mut program = String::from(PRELUDE);
        program.push_str(&text::denied_facts());
        program.push_str(&text::table_facts());
        for c in group_by_predicate(clauses) {
            program.push_str(&text::clause(c)?);
        }
        Ok(ScryerEngine {
            limits: Limits::default(),
            program,
            worker: None,
            stuck: None,
            mirrors: (0..machine::WORLDS).map(|_| Mirror::default()).collect(),
            output: String::new(),
            rebuilds: 0,
            rebuild_after: REBUILD_AFTER,
            backstop: BACKSTOP,
        })
    }

    /// The same engine with other limits.
    pub fn with_limits(mut self, limits: Limits) -> ScryerEngine {
        self.limits = limits;
        self
    }

    /// When the running query is given up: the backstop, or the limits' deadline if earlier.
    fn until(&self) -> Instant {
        let backstop = Instant::now() + self.backstop;
        match self.limits.deadline {
            Some(d) if d < backstop => d,
            _ => backstop,
        }
    }

    /// The first `cap` answers (`usize::MAX`: all), and whether the search stopped at `cap`.
    pub fn query_upto(
        &mut self,
        view: &View,
        query: &Term,
        cap: usize,
    ) -> KrResult<(Vec<Subst>, bool)> {
        let mut all = self.ask(view, query, if cap == 1 { 1 } else { 0 })?;
        let cut = all.len() >= cap;
        all.truncate(cap);
        Ok((all, cut))
    }

    fn ask(&mut self, view: &View, query: &Term, cap: u8) -> KrResult<Vec<Subst>> {
        let goal = text::query(query)?;
        let vars: Vec<Sym> = query
            .vars()
            .into_iter()
            .filter(|v| v.name() != "_")
            .collect();
        let template = if vars.is_empty() {
            Term::atom("ans")
        } else {
            Term::compound("ans", vars.iter().map(|v| Term::Var(*v)).collect())
        };
        if self.worker.is_none() {
            // Before the mirrors are synced: they must not record facts no machine got.
            self.wait_for_stuck()?;
            self.worker = Some(Worker::start(self.program.clone())?);
        }
        let world = world_of(view);
        let (retract, assert, rebuild) = self.sync(world, view);
        let Some(worker) = &self.worker else {
            return Err(machine::fault("the scryer thread did not start"));
        };
        let reply = worker.ask(
            Request {
                world,
                rebuild,
                retract,
                assert,
                template,
                goal,
                cap,
                inferences: self.limits.max_inferences,
            },
            self.until(),
        );
        if worker.stuck() {
            // Its thread still runs the query: the next query gets a new thread once this one
            // ends, and every machine of it is given the facts afresh.
            if let Some(mut w) = self.worker.take() {
                w.close();
                self.stuck = Some(w);
            }
            for m in &mut self.mirrors {
                *m = Mirror::default();
            }
        }
        let reply = match reply {
            Ok(r) => r,
            Err(e) => {
                if machine::is_fault(&e) {
                    // The machine may not hold what the mirror says: start it afresh.
                    self.mirrors[world] = Mirror::default();
                    self.mirrors[world].retracted = u64::MAX;
                }
                return Err(e);
            }
        };
        let (answers, output) = reply;
        self.output.push_str(&output);
        Ok(answers.iter().map(|a| answer(&vars, a)).collect())
    }

    /// Fails while an earlier query that outlived its time still runs on its thread.
    fn wait_for_stuck(&mut self) -> KrResult<()> {
        match &self.stuck {
            Some(w) if !w.finished() => Err(machine::fault(
                "an earlier query of this agent outlived its time and still runs (scryer cannot \
                 stop a query); no other query starts until it ends: bound the work of that \
                 query, or use the native engine, which stops every query at its limits",
            )),
            _ => {
                self.stuck = None;
                Ok(())
            }
        }
    }

    /// The facts to retract and to assert so that machine `world` holds the view's facts in
    /// the view's order (per predicate: the order of answers); and whether to rebuild it first
    /// (then everything is asserted anew). Per predicate, the common prefix of what the
    /// machine holds and what the view has stays; the rest is retracted and asserted.
    fn sync(&mut self, world: usize, view: &View) -> (Vec<Term>, Vec<Term>, bool) {
        type Key = (Sym, usize);
        let key = |f: &Term| f.functor().unwrap_or((Sym::intern("[]"), 0));
        let mut want: FxHashMap<Key, Vec<&Term>> = FxHashMap::default();
        let mut keys: Vec<Key> = Vec::new();
        let facts = view
            .bases
            .iter()
            .flat_map(|b| b.iter())
            .chain(view.goal_facts.iter());
        for f in facts {
            let k = key(f);
            if view.knowledge.defines(k.0, k.1) || text::denied(k.0.name()) {
                continue;
            }
            want.entry(k)
                .or_insert_with(|| {
                    keys.push(k);
                    Vec::new()
                })
                .push(f);
        }
        let mirror = &mut self.mirrors[world];
        let rebuild = mirror.retracted >= self.rebuild_after;
        if rebuild {
            *mirror = Mirror::default();
            self.rebuilds += 1;
        }
        let mut have: FxHashMap<Key, Vec<usize>> = FxHashMap::default();
        for (i, f) in mirror.facts.iter().enumerate() {
            let k = key(f);
            have.entry(k)
                .or_insert_with(|| {
                    if !want.contains_key(&k) {
                        keys.push(k);
                    }
                    Vec::new()
                })
                .push(i);
        }
        let mut dropped = vec![false; mirror.facts.len()];
        let (mut retract, mut assert) = (Vec::new(), Vec::new());
        for k in &keys {
            let w = want.get(k).map_or(&[][..], |v| &v[..]);
            let h = have.get(k).map_or(&[][..], |v| &v[..]);
            let p = w
                .iter()
                .zip(h)
                .take_while(|(a, &i)| ***a == mirror.facts[i])
                .count();
            for &i in &h[p..] {
                dropped[i] = true;
                retract.push(mirror.facts[i].clone());
            }
            assert.extend(w[p..].iter().map(|t| (*t).clone()));
        }
        if !retract.is_empty() {
            let mut i = 0;
            mirror.facts.retain(|_| {
                i += 1;
                !dropped[i - 1]
            });
        }
        mirror.facts.extend(assert.iter().cloned());
        mirror.retracted += retract.len() as u64;
        (retract, assert, rebuild)
    }
}

/// Which machine answers a view: beliefs (several bases), one goal, or a single other base.
fn world_of(view: &View) -> usize {
    if !view.goal_facts.is_empty() || view.bases.is_empty() {
        1
    } else if view.bases.len() > 1 {
        0
    } else {
        2
    }
}

/// An answer (an instance of the template) as a substitution of the query's variables:
/// variables left unbound are left out, variables bound to each other are bound to the first
/// query variable, other unbound variables are named `_R0`, `_R1`, ...
fn answer(vars: &[Sym], instance: &Term) -> Subst {
    let values = instance.args();
    let mut names: FxHashMap<Sym, Term> = FxHashMap::default();
    for (v, t) in vars.iter().zip(values) {
        if let Term::Var(s) = t {
            names.entry(*s).or_insert(Term::Var(*v));
        }
    }
    let mut s = Subst::new();
    let mut fresh = Fresh {
        taken: vars,
        count: 0,
    };
    for (v, t) in vars.iter().zip(values) {
        if let Term::Var(x) = t {
            if names.get(x) == Some(&Term::Var(*v)) {
                continue;
            }
        }
        s.bind(*v, rename(t, &mut names, &mut fresh));
    }
    s
}

/// `t` with its variables named as `names` says, new ones `_R0`, `_R1`, ... (skipping the
/// query's own names). Iterative: an answer may be a list of a hundred thousand variables.
fn rename(t: &Term, names: &mut FxHashMap<Sym, Term>, fresh: &mut Fresh) -> Term {
    if t.is_ground() {
        return t.clone();
    }
    enum Step<'a> {
        Visit(&'a Term),
        Build(Sym, usize),
    }
    let mut work = vec![Step::Visit(t)];
    let mut done: Vec<Term> = Vec::new();
    while let Some(step) = work.pop() {
        match step {
            Step::Visit(Term::Var(x)) => {
                done.push(names.entry(*x).or_insert_with(|| fresh.next()).clone())
            }
            Step::Visit(Term::Compound(c)) => {
                work.push(Step::Build(c.name, c.args.len()));
                work.extend(c.args.iter().rev().map(Step::Visit));
            }
            Step::Visit(other) => done.push(other.clone()),
            Step::Build(name, n) => {
                let args = done.split_off(done.len() - n);
                done.push(Term::compound(name, args));
            }
        }
    }
    done.pop().unwrap_or_else(|| t.clone())
}

/// New variable names for an answer: `_R0`, `_R1`, ..., none of them a query variable's name.
struct Fresh<'a> {
    taken: &'a [Sym],
    count: usize,
}

impl Fresh<'_> {
    fn next(&mut self) -> Term {
        loop {
            let name = format!("_R{}", self.count);
            self.count += 1;
            if !self.taken.iter().any(|v| v.name() == name) {
                return Term::var(&name);
            }
        }
    }
}

/// scryer 0.10 keeps only the last group of a discontiguous predicate: the clauses grouped by
/// predicate, in order of first appearance (relative order kept).
fn group_by_predicate(clauses: &[Term]) -> Vec<&Term> {
    let key = |c: &Term| {
        let head = if c.is_functor(Sym::intern(":-"), 2) || c.is_functor(Sym::intern("-->"), 2) {
            let extra = usize::from(c.is_functor(Sym::intern("-->"), 2)) * 2;
            c.args()[0].functor().map(|(n, a)| (n, a + extra))
        } else {
            c.functor()
        };
        head
    };
    let mut groups: Vec<(Option<(Sym, usize)>, Vec<&Term>)> = Vec::new();
    let mut index: FxHashMap<Option<(Sym, usize)>, usize> = FxHashMap::default();
    for c in clauses {
        let k = key(c);
        let i = *index.entry(k).or_insert_with(|| {
            groups.push((k, Vec::new()));
            groups.len() - 1
        });
        groups[i].1.push(c);
    }
    groups.into_iter().flat_map(|(_, v)| v).collect()
}

impl Engine for ScryerEngine {
    fn query(&mut self, view: &View, query: &Term) -> KrResult<Vec<Subst>> {
        self.ask(view, query, 0)
    }

    fn query_first(&mut self, view: &View, query: &Term) -> KrResult<Option<Subst>> {
        Ok(self.ask(view, query, 1)?.into_iter().next())
    }

    fn holds(&mut self, view: &View, query: &Term) -> KrResult<bool> {
        Ok(!self.ask(view, query, 1)?.is_empty())
    }

    fn take_output(&mut self) -> String {
        std::mem::take(&mut self.output)
    }
}

impl Clone for ScryerEngine {
    /// A clone starts its own machines (with the same knowledge and limits).
    fn clone(&self) -> ScryerEngine {
        ScryerEngine {
            limits: self.limits,
            program: self.program.clone(),
            worker: None,
            stuck: None,
            mirrors: (0..machine::WORLDS).map(|_| Mirror::default()).collect(),
            output: String::new(),
            rebuilds: 0,
            rebuild_after: self.rebuild_after,
            backstop: self.backstop,
        }
    }
}

#[cfg(test)]
mod tests;
