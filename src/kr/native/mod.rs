//! The native Prolog engine: a binding store (`store`), compiled clauses (`code`), the iterative
//! solver (`machine`) with its control constructs (`control`) and fact lookup (`facts`), and the
//! built-ins (`builtins`, `arith`, `text`, `lists`, `output`, `prelude`, `library`).

pub(crate) mod arith;
pub(crate) mod bigint;
pub(crate) mod budget;
pub(crate) mod builtins;
pub(crate) mod catch;
pub(crate) mod clauses;
pub(crate) mod code;
pub(crate) mod control;
pub(crate) mod draws;
pub(crate) mod facts;
pub mod library;
pub(crate) mod lists;
pub(crate) mod machine;
pub(crate) mod output;
pub(crate) mod prelude;
pub(crate) mod prepared;
pub(crate) mod store;
pub(crate) mod text;

use super::error::{KrResult, Limits};
use super::{Engine, View};
use crate::term::{Subst, Sym, Term};
use draws::Draws;
use machine::{Ctx, Machine, Solver};
use std::cell::RefCell;
use std::collections::HashSet;

thread_local! {
    /// The solver buffers, reused by every query on this thread (agents stay small).
    static MACHINE: RefCell<Machine> = RefCell::new(Machine::default());
}

/// The native engine's per-agent state: limits, options, the seeded RNG and the output buffer.
#[derive(Clone, Debug)]
pub struct NativeEngine {
    /// Resource limits applied to every query.
    pub limits: Limits,
    /// Unify with the occurs check (off by default, as in Prolog systems).
    pub occurs_check: bool,
    rng: Draws,
    output: String,
    /// What `get_time/1` answers.
    pub clock: Clock,
    /// The queries of rule conditions, placed once and copied onto the heap afterwards.
    prepared: prepared::Cache,
    /// The distinct atoms this engine's queries made at run time, against
    /// `limits.max_new_atoms` (a set of this engine's own, so that the count never depends on
    /// what other agents or earlier runs in the process made).
    made_atoms: HashSet<Sym>,
}

/// The time `get_time/1` answers: wall-clock time, or simulated time set by the runtime
/// (lock-step runs stay reproducible); reads are counted so the runtime knows a query
/// depended on the time.
#[derive(Clone, Copy, Debug, Default)]
pub struct Clock {
    /// Simulated seconds since the start of the run; `None`: wall-clock time.
    pub now: Option<f64>,
    /// Number of times the time was read.
    pub reads: u64,
}

impl NativeEngine {
    /// An engine whose `random/1` and friends draw from a ChaCha8 RNG seeded with `seed`.
    pub fn new(seed: u64) -> NativeEngine {
        NativeEngine {
            limits: Limits::default(),
            occurs_check: false,
            rng: Draws::seeded(seed),
            output: String::new(),
            clock: Clock::default(),
            prepared: prepared::Cache::default(),
            made_atoms: HashSet::new(),
        }
    }

    /// The same engine with other limits.
    pub fn with_limits(mut self, limits: Limits) -> NativeEngine {
        self.limits = limits;
        self
    }

    /// A value that changes whenever a query drew a random number or read the clock (a
    /// query that did neither gives the same answers when asked again on the same state).
    pub fn chance(&self) -> u128 {
        u128::from(self.rng.count()) + u128::from(self.clock.reads)
    }

    /// True when output built-ins wrote text not yet taken.
    pub fn has_output(&self) -> bool {
        !self.output.is_empty()
    }

    /// Runs `query`, handing each answer to `each` until it returns false or answers run out.
    /// Returns the number of answers produced.
    pub fn solve(
        &mut self,
        view: &View,
        query: &Term,
        each: &mut dyn FnMut(Subst) -> bool,
    ) -> KrResult<usize> {
        self.solve_inner(view, query, &Subst::new(), true, false, each)
    }

    /// [`NativeEngine::solve`] of `env` applied to `query` (`env` binds variables to ground
    /// terms; answers bind the other variables only); with `convert` false, answers are not
    /// converted to terms (the callback gets empty substitutions). With `reuse`, the query is
    /// placed from the engine's cache of prepared queries (for queries asked many times).
    fn solve_inner(
        &mut self,
        view: &View,
        query: &Term,
        env: &Subst,
        convert: bool,
        reuse: bool,
        each: &mut dyn FnMut(Subst) -> bool,
    ) -> KrResult<usize> {
        let lib = builtins::library();
        let cache = &mut self.prepared;
        let mut run = |m: &mut Machine| -> KrResult<usize> {
            let cx = Ctx {
                kn: view.knowledge,
                lib,
                bases: view.bases,
                goal_facts: view.goal_facts,
                limits: &self.limits,
                rng: &mut self.rng,
                out: &mut self.output,
                clock: &mut self.clock,
                made_atoms: &mut self.made_atoms,
            };
            let mut s = Solver::start(m, cx, self.occurs_check, |st| match reuse {
                true => cache.place(st, query, env),
                false => prepared::place_plain(st, query, env),
            });
            let mut n = 0;
            let mut first = true;
            while s.next(first)? {
                first = false;
                n += 1;
                let answer = if convert { s.answer()? } else { Subst::new() };
                s.check_answers(n as u64)?;
                if !each(answer) {
                    break;
                }
            }
            Ok(n)
        };
        MACHINE.with(|cell| match cell.try_borrow_mut() {
            Ok(mut m) => run(&mut m),
            Err(_) => run(&mut Machine::default()),
        })
    }

    /// For a ground query of a predicate that only facts define: how many times the fact is
    /// present (the number of answers), without running the solver.
    fn ground_fact_count(view: &View, query: &Term) -> Option<usize> {
        let (name, arity) = query.functor()?;
        if view.knowledge.table.contains_key(&(name, arity as u32)) || !query.is_ground() {
            return None;
        }
        Some(
            view.bases
                .iter()
                .filter(|b| b.has_pred(name, arity) && b.contains(query))
                .count()
                + view.goal_facts.iter().filter(|f| *f == query).count(),
        )
    }

    /// The first `cap` answers of `query` (`usize::MAX`: all, under the answer budget), and
    /// whether the solver was stopped at `cap` (more answers may exist; they are not sought,
    /// so an infinite generator ends cheaply).
    pub fn query_upto(
        &mut self,
        view: &View,
        query: &Term,
        cap: usize,
    ) -> KrResult<(Vec<Subst>, bool)> {
        if let Some(n) = Self::ground_fact_count(view, query) {
            return Ok((vec![Subst::new(); n.min(cap)], n >= cap));
        }
        let mut out = Vec::new();
        self.solve(view, query, &mut |s| {
            out.push(s);
            out.len() < cap
        })?;
        let cut = out.len() >= cap;
        Ok((out, cut))
    }

    /// [`NativeEngine::query_upto`] of `env` applied to `query`, without building that term:
    /// the answers bind the variables `env` leaves free. `env` must bind its variables to
    /// ground terms (`None` otherwise: apply it and ask [`NativeEngine::query_upto`]). For the
    /// long-lived queries of rule conditions: the query is placed on the heap once per engine
    /// (kept by the address of `query`) and copied from there on later calls.
    pub fn query_upto_in(
        &mut self,
        view: &View,
        query: &Term,
        env: &Subst,
        cap: usize,
    ) -> Option<KrResult<(Vec<Subst>, bool)>> {
        if !env.iter().all(|(_, t)| t.is_ground()) {
            return None;
        }
        let mut out = Vec::new();
        let run = self.solve_inner(view, query, env, true, true, &mut |s| {
            out.push(s);
            out.len() < cap
        });
        Some(run.map(|_| {
            let cut = out.len() >= cap;
            (out, cut)
        }))
    }

    /// True when `query` has at least one answer (stops after the first).
    fn first(&mut self, view: &View, query: &Term) -> KrResult<bool> {
        if let Some(n) = Self::ground_fact_count(view, query) {
            return Ok(n > 0);
        }
        let mut found = false;
        self.solve_inner(view, query, &Subst::new(), false, false, &mut |_| {
            found = true;
            false
        })?;
        Ok(found)
    }
}

impl Default for NativeEngine {
    fn default() -> NativeEngine {
        NativeEngine::new(0)
    }
}

impl Engine for NativeEngine {
    fn query(&mut self, view: &View, query: &Term) -> KrResult<Vec<Subst>> {
        Ok(self.query_upto(view, query, usize::MAX)?.0)
    }

    fn query_first(&mut self, view: &View, query: &Term) -> KrResult<Option<Subst>> {
        let mut out = None;
        self.solve(view, query, &mut |s| {
            out = Some(s);
            false
        })?;
        Ok(out)
    }

    fn holds(&mut self, view: &View, query: &Term) -> KrResult<bool> {
        self.first(view, query)
    }

    fn take_output(&mut self) -> String {
        std::mem::take(&mut self.output)
    }
}
