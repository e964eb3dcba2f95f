//! The solver: iterative SLD resolution over a goal-frame arena and a choicepoint stack, with
//! cut barriers, negation as failure, if-then-else, soft cut and all-solutions collection.
//! Nothing here recurses with the proof depth or the term depth.

use super::budget::CHECK_EVERY;
use super::clauses::{Args, Direct, Regs};
use super::code::{Code, Key, UNSET};
use super::draws::Draws;
use super::store::{Cell, Store, VarNames};
use crate::kr::error::{KrError, KrResult, Limits};
use crate::kr::factbase::{FactBase, Scan};
use crate::kr::knowledge::{Knowledge, Pred, PredRef};
use crate::term::{Subst, Sym, Term};
use std::collections::HashSet;

pub(crate) const NONE: u32 = u32::MAX;

/// The error for a cyclic term where a finite one is needed (answers, output).
pub(crate) fn cyclic() -> KrError {
    KrError::iso(
        Term::compound("representation_error", vec![Term::atom("cyclic_term")]),
        None,
    )
}

/// A goal waiting to run, with its continuation and cut barrier.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub goal: Goal,
    pub next: u32,
    pub cut: u32,
    pub depth: u32,
    /// What the goal's predicate resolves to, when known at compile time (saves a lookup).
    pub pred: Option<PredRef>,
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum Goal {
    Call(Cell),
    /// Remove all choicepoints above the given height (end of an if-then-else condition).
    CutTo(u32),
    /// Disable the else branch of a soft cut.
    SoftCut(u32),
    /// The goal under `\+` succeeded: remove its choicepoints and fail.
    NafFail(u32),
    /// Record a `findall/3` answer and fail.
    Collect {
        bag: u32,
        tmpl: Cell,
    },
    /// The goal of the `catch/3` whose choicepoint is at this index has exited.
    CatchExit(u32),
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum Alt {
    Clauses {
        goal: Cell,
        pred: PredRef,
        key: Option<Key>,
        pos: u32,
    },
    Facts {
        goal: Cell,
        stage: u32,
        scan: Scan,
    },
    Goal(Cell),
    NafSucceed,
    FindallEnd {
        bag: u32,
        result: Cell,
        tail: Cell,
    },
    Between {
        x: Cell,
        cur: i64,
        hi: i64,
    },
    Member {
        x: Cell,
        list: Cell,
    },
    Repeat,
    /// An active `catch/3`: an error thrown while this choicepoint is on the stack (and
    /// `active`) is unified with `catcher` and handled by calling `recovery`.
    Catch {
        catcher: Cell,
        recovery: Cell,
        active: bool,
    },
    /// Backtracking into a `catch/3` goal that exited with choicepoints: reactivate the catch.
    CatchReactivate(u32),
    Dead,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Choice {
    pub alt: Alt,
    heap: u32,
    trail: u32,
    frames: u32,
    strs: u32,
    pub(crate) next: u32,
    pub(crate) cut: u32,
    pub(crate) depth: u32,
}

/// Answers collected by `findall/3`, kept off the heap so backtracking does not erase them.
#[derive(Default)]
pub(crate) struct Bag {
    pub code: Code,
    pub items: Vec<(Cell, u32)>,
}

/// Reusable buffers of the solver (one per thread).
#[derive(Default)]
pub(crate) struct Machine {
    pub st: Store,
    pub frames: Vec<Frame>,
    pub cps: Vec<Choice>,
    pub bags: Vec<Bag>,
    pub slots: Vec<Cell>,
    /// The argument registers of the next [`Direct`] call.
    pub regs: Regs,
    pub arith: super::arith::ArithStacks,
}

impl Machine {
    fn reset(&mut self) {
        self.st.reset();
        self.frames.clear();
        self.cps.clear();
        self.bags.clear();
        // Give back memory after an unusually big query so idle threads stay small.
        if self.st.heap.capacity() > 1 << 20 {
            self.st.heap = Vec::new();
            self.st.trail = Vec::new();
            self.frames = Vec::new();
            self.cps = Vec::new();
            self.st.strs = Vec::new();
        }
    }
}

/// Everything a query reads: knowledge, fact bases, goal facts; plus the agent's RNG and output.
pub(crate) struct Ctx<'a> {
    pub kn: &'a Knowledge,
    pub lib: &'static Knowledge,
    pub bases: &'a [&'a FactBase],
    pub goal_facts: &'a [Term],
    pub limits: &'a Limits,
    pub rng: &'a mut Draws,
    pub out: &'a mut String,
    pub clock: &'a mut super::Clock,
    /// The atoms the engine's queries have made at run time so far (see `budget::new_atom`).
    pub made_atoms: &'a mut HashSet<Sym>,
}

/// One running query.
pub(crate) struct Solver<'a, 'm> {
    pub m: &'m mut Machine,
    pub cx: Ctx<'a>,
    pub cont: u32,
    pub inferences: u64,
    /// The inference count at which budgets are checked next (see `budget.rs`).
    pub next_check: u64,
    pub query_vars: Vec<(Sym, Cell)>,
    /// How many of `query_vars` (the first ones) were bound before the query ran.
    bound: usize,
    /// The call the run loop makes next, before reading any frame (see [`Direct`]).
    pub(crate) direct: Direct,
    /// Set when matching a stored fact met a variable of the fact (an open message): the
    /// match is then redone on a copy of the whole fact (see `Solver::try_facts`).
    pub(crate) fact_vars: bool,
}

impl<'a, 'm> Solver<'a, 'm> {
    /// Prepares the goal that `place` puts on the emptied store; `place` returns the goal's
    /// cell, the query's variables and how many of them (the first ones) were bound before the
    /// query ran (answers leave those out).
    pub fn start(
        m: &'m mut Machine,
        cx: Ctx<'a>,
        occurs_check: bool,
        place: impl FnOnce(&mut Store) -> (Cell, Vec<(Sym, Cell)>, usize),
    ) -> Self {
        m.reset();
        m.st.occurs_check = occurs_check;
        m.st.max_walk = cx.limits.max_heap_cells as usize;
        let next_check = CHECK_EVERY.min(cx.limits.max_inferences + 1);
        let (g, vars, bound) = place(&mut m.st);
        m.frames.push(Frame {
            goal: Goal::Call(g),
            next: NONE,
            cut: 0,
            depth: 0,
            pred: None,
        });
        Solver {
            m,
            cx,
            cont: 0,
            inferences: 0,
            next_check,
            query_vars: vars,
            bound,
            direct: Direct::NONE,
            fact_vars: false,
        }
    }

    /// The next answer (`Ok(false)` when there are no more).
    pub fn next(&mut self, first: bool) -> KrResult<bool> {
        let found = if !first && !self.backtrack()? {
            false
        } else {
            self.run()?
        };
        if self.m.st.cyclic.get() {
            return Err(self.walk_fault());
        }
        Ok(found)
    }

    /// The current answer as a substitution over the query's variables.
    pub fn answer(&self) -> KrResult<Subst> {
        // Names are only needed for unbound variables inside answers: built on first use.
        let mut names: Option<VarNames> = None;
        let mut s = Subst::new();
        for (v, c) in &self.query_vars[self.bound..] {
            let d = self.m.st.deref(*c);
            if let (Cell::Ref(a), Cell::Ref(b)) = (d, *c) {
                if a == b {
                    continue;
                }
            }
            // Atomic answers (the common case) need no traversal.
            let atomic = match d {
                Cell::Atom(x) => Some(Term::Atom(x)),
                Cell::Int(i) => Some(Term::Int(i)),
                _ => None,
            };
            if let Some(t) = atomic {
                s.bind(*v, t);
                continue;
            }
            let names = names.get_or_insert_with(|| VarNames::new(&self.query_vars));
            let t = self.m.st.to_term(d, names);
            // `to_term` stops on a cyclic term and raises the flag.
            if self.m.st.cyclic.get() {
                return Err(self.walk_fault());
            }
            if t != Term::Var(*v) {
                s.bind(*v, t);
            }
        }
        Ok(s)
    }

    /// The error for a traversal that gave up (cyclic term, or a walk over the step limit).
    pub(crate) fn walk_fault(&self) -> KrError {
        if self.m.st.oversize.get() {
            let max = self.cx.limits.max_heap_cells;
            return super::budget::resource("memory", "term traversal".into(), max);
        }
        cyclic()
    }

    // ---- helpers used by built-ins ----

    /// Argument `i` of the goal whose header is at `p`.
    #[inline]
    pub fn a(&self, p: u32, i: u32) -> Cell {
        self.m.st.heap[(p + 1 + i) as usize]
    }

    /// Dereferenced argument.
    #[inline]
    pub fn ad(&self, p: u32, i: u32) -> Cell {
        self.m.st.deref(self.a(p, i))
    }

    pub fn unify(&mut self, a: Cell, b: Cell) -> bool {
        self.m.st.unify(a, b)
    }

    /// The depth of a frame: the length of its continuation (so tail calls do not deepen).
    #[inline]
    pub(crate) fn depth_of(&self, next: u32) -> u32 {
        if next == NONE {
            0
        } else {
            self.m.frames[next as usize].depth
        }
    }

    pub(crate) fn push_frame(&mut self, goal: Goal, next: u32, cut: u32, _depth: u32) -> u32 {
        let depth = self.depth_of(next) + 1;
        self.m.frames.push(Frame {
            goal,
            next,
            cut,
            depth,
            pred: None,
        });
        self.m.frames.len() as u32 - 1
    }

    pub(crate) fn push_choice(&mut self, alt: Alt, next: u32, cut: u32, depth: u32) {
        let st = &self.m.st;
        self.m.cps.push(Choice {
            alt,
            heap: st.heap.len() as u32,
            trail: st.trail.len() as u32,
            frames: self.m.frames.len() as u32,
            strs: st.strs.len() as u32,
            next,
            cut,
            depth,
        });
    }

    pub(crate) fn restore(&mut self, ch: &Choice) {
        self.m.st.undo(ch.trail as usize);
        self.m.st.heap.truncate(ch.heap as usize);
        self.m.st.strs.truncate(ch.strs as usize);
        self.m.frames.truncate(ch.frames as usize);
    }

    pub(crate) fn pred(&self, r: PredRef) -> &'a Pred {
        match r {
            PredRef::User(i) => &self.cx.kn.preds[i as usize],
            _ => {
                let PredRef::Lib(i) = r else { unreachable!() };
                &self.cx.lib.preds[i as usize]
            }
        }
    }

    // ---- the main loop ----

    pub(crate) fn run(&mut self) -> KrResult<bool> {
        loop {
            if self.m.st.cyclic.get() {
                let e = self.walk_fault();
                if self.recover(e)? {
                    continue;
                }
            }
            let d = self.direct;
            if d.pending() {
                self.direct = Direct::NONE;
                let ok = match self.call_direct(d) {
                    Ok(ok) => ok,
                    Err(e) => self.recover(e)?,
                };
                if !ok && !self.backtrack_or_recover()? {
                    return Ok(false);
                }
                continue;
            }
            if self.cont == NONE {
                return Ok(true);
            }
            let f = self.m.frames[self.cont as usize];
            // The newest frame, not protected by a choicepoint, is garbage once read: reuse
            // its slot (this keeps deterministic tail recursion in constant frame space).
            if self.cont as usize + 1 == self.m.frames.len()
                && self.m.cps.last().is_none_or(|c| c.frames <= self.cont)
            {
                self.m.frames.pop();
            }
            let ok = match f.goal {
                Goal::Call(g) => match self.call(g, f.next, f.cut, f.depth, f.pred) {
                    Ok(ok) => ok,
                    Err(e) => self.recover(e)?,
                },
                Goal::CutTo(b) => {
                    self.m.cps.truncate(b as usize);
                    self.cont = f.next;
                    true
                }
                Goal::SoftCut(b) => {
                    if let Some(c) = self.m.cps.get_mut(b as usize) {
                        c.alt = Alt::Dead;
                    }
                    self.cont = f.next;
                    true
                }
                Goal::NafFail(b) => {
                    self.m.cps.truncate(b as usize);
                    false
                }
                Goal::Collect { bag, tmpl } => {
                    let st = &self.m.st;
                    let b = &mut self.m.bags[bag as usize];
                    let mut vars = Vec::new();
                    let root = b.code.add_cell(st, tmpl, &mut vars);
                    b.items.push((root, vars.len() as u32));
                    false
                }
                Goal::CatchExit(b) => {
                    self.catch_exit(b);
                    self.cont = f.next;
                    true
                }
            };
            if !ok && !self.backtrack_or_recover()? {
                return Ok(false);
            }
        }
    }

    /// [`Solver::backtrack`], handing an error to the innermost active `catch/3`.
    fn backtrack_or_recover(&mut self) -> KrResult<bool> {
        match self.backtrack() {
            Ok(ok) => Ok(ok),
            Err(e) => self.recover(e),
        }
    }

    /// Resumes the newest choicepoint; false when none is left.
    pub(crate) fn backtrack(&mut self) -> KrResult<bool> {
        loop {
            if self.m.st.cyclic.get() {
                return Err(self.walk_fault());
            }
            let Some(ch) = self.m.cps.last().copied() else {
                return Ok(false);
            };
            // Resuming an alternative is an inference too: a loop of pure backtracking
            // (`repeat`, `member/2` on a cyclic list) must meet the budgets.
            self.inferences += 1;
            if self.inferences >= self.next_check {
                self.checkpoint(&|| alt_name(&ch.alt))?;
            }
            self.restore(&ch);
            let b = self.m.cps.len() as u32 - 1;
            match ch.alt {
                Alt::Dead | Alt::Catch { .. } => {
                    self.m.cps.pop();
                }
                Alt::CatchReactivate(c) => {
                    self.m.cps.pop();
                    if let Some(Choice {
                        alt: Alt::Catch { active, .. },
                        ..
                    }) = self.m.cps.get_mut(c as usize)
                    {
                        *active = true;
                    }
                }
                Alt::Goal(g) => {
                    self.m.cps.pop();
                    self.cont = self.push_frame(Goal::Call(g), ch.next, ch.cut, ch.depth);
                    return Ok(true);
                }
                Alt::NafSucceed => {
                    self.m.cps.pop();
                    self.cont = ch.next;
                    return Ok(true);
                }
                Alt::Repeat => {
                    self.cont = ch.next;
                    return Ok(true);
                }
                Alt::FindallEnd { bag, result, tail } => {
                    self.m.cps.pop();
                    let list = self.bag_list(bag, tail);
                    if self.unify(result, list) {
                        self.cont = ch.next;
                        return Ok(true);
                    }
                }
                Alt::Between { x, cur, hi } => {
                    if cur >= hi {
                        self.m.cps.pop();
                    } else if let Some(c) = self.m.cps.last_mut() {
                        c.alt = Alt::Between {
                            x,
                            cur: cur + 1,
                            hi,
                        };
                    }
                    if self.unify(x, Cell::Int(cur)) {
                        self.cont = ch.next;
                        return Ok(true);
                    }
                }
                Alt::Member { x, list } => {
                    if self.member_step(x, list) {
                        self.cont = ch.next;
                        return Ok(true);
                    }
                }
                Alt::Clauses {
                    goal,
                    pred,
                    key,
                    pos,
                } => {
                    let args = Args::Heap(Self::args_of(goal));
                    if self.try_clauses(
                        Some(goal),
                        args,
                        pred,
                        key,
                        pos,
                        b,
                        true,
                        ch.next,
                        ch.depth,
                    )? {
                        return Ok(true);
                    }
                }
                Alt::Facts { goal, stage, scan } => {
                    if self.try_facts(goal, stage, scan, b, true, ch.next)? {
                        return Ok(true);
                    }
                }
            }
        }
    }

    /// Takes bag `bag` (and every newer one) and builds its answers as a list ending in `tail`.
    pub(crate) fn bag_list(&mut self, bag: u32, tail: Cell) -> Cell {
        let b = self.m.bags.drain(bag as usize..).next().unwrap_or_default();
        let mut cells = Vec::with_capacity(b.items.len());
        for (root, n) in &b.items {
            self.m.slots.clear();
            self.m.slots.resize(*n as usize, UNSET);
            let c = b.code.build(&mut self.m.st, *root, &mut self.m.slots);
            cells.push(c);
        }
        self.m.st.new_list(&cells, tail)
    }

    /// One step of `member/2`: unify with the head, leave the tail as the alternative.
    /// The choicepoint for this call must be on top.
    pub(crate) fn member_step(&mut self, x: Cell, list: Cell) -> bool {
        match self.m.st.cons(list) {
            Some((h, t)) => {
                if self.m.st.cons(t).is_some() {
                    if let Some(c) = self.m.cps.last_mut() {
                        c.alt = Alt::Member { x, list: t };
                    }
                } else {
                    self.m.cps.pop();
                }
                self.unify(x, h)
            }
            None => {
                self.m.cps.pop();
                false
            }
        }
    }
}

/// The predicate behind a choicepoint, for budget messages.
fn alt_name(alt: &Alt) -> String {
    match alt {
        Alt::Between { .. } => "between/3".into(),
        Alt::Member { .. } => "member/2".into(),
        Alt::Repeat => "repeat/0".into(),
        Alt::Clauses { .. } | Alt::Facts { .. } => "backtracking into a predicate".into(),
        _ => "backtracking".into(),
    }
}
