//! The solver: iterative SLD resolution over a goal-frame arena and a choicepoint stack, with
//! cut barriers, negation as failure, if-then-else, soft cut and all-solutions collection.
//! Nothing here recurses with the proof depth or the term depth.

use super::builtins::{self, B};
use super::code::{Code, Key, UNSET};
use super::store::{Cell, Store, VarNames};
use crate::kr::error::{KrError, KrResult, Limits};
use crate::kr::factbase::{FactBase, Scan};
use crate::kr::knowledge::{Knowledge, Pred, PredRef};
use crate::term::{well_known as wk, Subst, Sym, Term};
use rand_chacha::ChaCha8Rng;

pub(crate) const NONE: u32 = u32::MAX;

/// A goal waiting to run, with its continuation and cut barrier.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub goal: Goal,
    pub next: u32,
    pub cut: u32,
    pub depth: u32,
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
    Dead,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Choice {
    pub alt: Alt,
    heap: u32,
    trail: u32,
    frames: u32,
    strs: u32,
    next: u32,
    cut: u32,
    depth: u32,
}

/// Answers collected by `findall/3`, kept off the heap so backtracking does not erase them.
#[derive(Default)]
pub(crate) struct Bag {
    code: Code,
    items: Vec<(Cell, u32)>,
}

/// Reusable buffers of the solver (one per thread).
#[derive(Default)]
pub(crate) struct Machine {
    pub st: Store,
    pub frames: Vec<Frame>,
    pub cps: Vec<Choice>,
    bags: Vec<Bag>,
    slots: Vec<Cell>,
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
    pub limits: Limits,
    pub rng: &'a mut ChaCha8Rng,
    pub out: &'a mut String,
}

/// One running query.
pub(crate) struct Solver<'a, 'm> {
    pub m: &'m mut Machine,
    pub cx: Ctx<'a>,
    pub cont: u32,
    pub inferences: u64,
    pub query_vars: Vec<(Sym, Cell)>,
}

impl<'a, 'm> Solver<'a, 'm> {
    /// Prepares `goal` for solving.
    pub fn new(m: &'m mut Machine, cx: Ctx<'a>, goal: &Term, occurs_check: bool) -> Self {
        m.reset();
        m.st.occurs_check = occurs_check;
        let mut vars = Vec::new();
        let g = m.st.from_term(goal, &mut vars);
        m.frames.push(Frame {
            goal: Goal::Call(g),
            next: NONE,
            cut: 0,
            depth: 0,
        });
        Solver {
            m,
            cx,
            cont: 0,
            inferences: 0,
            query_vars: vars,
        }
    }

    /// The next answer (`Ok(false)` when there are no more).
    pub fn next(&mut self, first: bool) -> KrResult<bool> {
        if !first && !self.backtrack()? {
            return Ok(false);
        }
        self.run()
    }

    /// The current answer as a substitution over the query's variables.
    pub fn answer(&self) -> Subst {
        let mut names = VarNames::new(&self.query_vars);
        let mut s = Subst::new();
        for (v, c) in &self.query_vars {
            let d = self.m.st.deref(*c);
            if let (Cell::Ref(a), Cell::Ref(b)) = (d, *c) {
                if a == b {
                    continue;
                }
            }
            let t = self.m.st.to_term(d, &mut names);
            if t != Term::Var(*v) {
                s.bind(*v, t);
            }
        }
        s
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
    fn depth_of(&self, next: u32) -> u32 {
        if next == NONE {
            0
        } else {
            self.m.frames[next as usize].depth
        }
    }

    fn push_frame(&mut self, goal: Goal, next: u32, cut: u32, _depth: u32) -> u32 {
        let depth = self.depth_of(next) + 1;
        self.m.frames.push(Frame {
            goal,
            next,
            cut,
            depth,
        });
        self.m.frames.len() as u32 - 1
    }

    fn push_choice(&mut self, alt: Alt, next: u32, cut: u32, depth: u32) {
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

    fn restore(&mut self, ch: &Choice) {
        self.m.st.undo(ch.trail as usize);
        self.m.st.heap.truncate(ch.heap as usize);
        self.m.st.strs.truncate(ch.strs as usize);
        self.m.frames.truncate(ch.frames as usize);
    }

    fn pred(&self, r: PredRef) -> &'a Pred {
        match r {
            PredRef::User(i) => &self.cx.kn.preds[i as usize],
            _ => {
                let PredRef::Lib(i) = r else { unreachable!() };
                &self.cx.lib.preds[i as usize]
            }
        }
    }

    // ---- the main loop ----

    fn run(&mut self) -> KrResult<bool> {
        loop {
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
                Goal::Call(g) => self.call(g, f.next, f.cut, f.depth)?,
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
            };
            if !ok && !self.backtrack()? {
                return Ok(false);
            }
        }
    }

    /// Resumes the newest choicepoint; false when none is left.
    fn backtrack(&mut self) -> KrResult<bool> {
        loop {
            let Some(ch) = self.m.cps.last().copied() else {
                return Ok(false);
            };
            self.restore(&ch);
            let b = self.m.cps.len() as u32 - 1;
            match ch.alt {
                Alt::Dead => {
                    self.m.cps.pop();
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
                    if self.try_clauses(goal, pred, key, pos, b, true, ch.next, ch.depth)? {
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
    fn bag_list(&mut self, bag: u32, tail: Cell) -> Cell {
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
    fn member_step(&mut self, x: Cell, list: Cell) -> bool {
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

    /// Calls goal `g`.
    fn call(&mut self, g: Cell, next: u32, cut: u32, depth: u32) -> KrResult<bool> {
        let g = self.m.st.deref(g);
        let (name, arity, p) = match g {
            Cell::Atom(s) => (s, 0, 0),
            Cell::Ptr(p) => match self.m.st.heap[p as usize] {
                Cell::Fun(s, n) => (s, n, p),
                _ => return Ok(false),
            },
            Cell::Ref(_) => {
                return Err(KrError::iso(Term::atom("instantiation_error"), None));
            }
            other => {
                let t = self.m.st.to_term(other, &mut VarNames::new(&[]));
                return Err(KrError::iso(
                    Term::compound("type_error", vec![Term::atom("callable"), t]),
                    None,
                ));
            }
        };
        self.inferences += 1;
        if self.inferences > self.cx.limits.max_inferences {
            return Err(KrError::Budget {
                predicate: format!("{}/{}", Term::Atom(name), arity),
                limit: self.cx.limits.max_inferences,
            });
        }
        match self.cx.kn.table.get(&(name, arity)).copied() {
            Some(PredRef::Builtin(b)) => self.builtin(b, g, p, next, cut, depth),
            Some(r) => {
                let key = if arity > 0 {
                    Key::of_cell(&self.m.st, self.a(p, 0))
                } else {
                    None
                };
                let b = self.m.cps.len() as u32;
                if depth > self.cx.limits.max_depth {
                    return Err(KrError::Depth {
                        predicate: format!("{}/{}", Term::Atom(name), arity),
                        limit: self.cx.limits.max_depth,
                    });
                }
                self.try_clauses(g, r, key, 0, b, false, next, depth)
            }
            None => {
                let b = self.m.cps.len() as u32;
                let scan = self.start_scan(0, g, name, arity, p);
                self.try_facts(g, 0, scan, b, false, next)
            }
        }
    }

    /// The first clause index at or after `i` whose first-argument key can match `key`.
    #[inline]
    fn skip(pred: &Pred, list: &[u32], mut i: usize, key: Option<Key>) -> usize {
        if let Some(k) = key {
            while i < list.len() {
                match pred.clauses[list[i] as usize].key {
                    Some(ck) if ck != k => i += 1,
                    _ => break,
                }
            }
        }
        i
    }

    /// Tries the clauses of `r` from candidate position `pos`; the choicepoint for this goal is
    /// (or will be) at index `b`.
    #[allow(clippy::too_many_arguments)]
    fn try_clauses(
        &mut self,
        goal: Cell,
        r: PredRef,
        key: Option<Key>,
        pos: u32,
        b: u32,
        mut has_choice: bool,
        next: u32,
        depth: u32,
    ) -> KrResult<bool> {
        let pred = self.pred(r);
        let list = pred.candidates(key);
        let mut i = Self::skip(pred, list, pos as usize, key);
        loop {
            if i >= list.len() {
                if has_choice {
                    self.m.cps.truncate(b as usize);
                }
                return Ok(false);
            }
            let j = Self::skip(pred, list, i + 1, key);
            if j < list.len() {
                let alt = Alt::Clauses {
                    goal,
                    pred: r,
                    key,
                    pos: j as u32,
                };
                if has_choice {
                    self.m.cps[b as usize].alt = alt;
                } else {
                    self.push_choice(alt, next, 0, depth);
                    has_choice = true;
                }
            } else if has_choice {
                self.m.cps.truncate(b as usize);
                has_choice = false;
            }
            let (hm, tm, fm, sm) = (
                self.m.st.heap.len(),
                self.m.st.trail.len(),
                self.m.frames.len(),
                self.m.st.strs.len(),
            );
            if self.try_clause(pred, list[i], goal, next, depth, b) {
                return Ok(true);
            }
            self.m.st.undo(tm);
            self.m.st.heap.truncate(hm);
            self.m.st.strs.truncate(sm);
            self.m.frames.truncate(fm);
            i = j;
        }
    }

    fn try_clause(
        &mut self,
        pred: &'a Pred,
        ci: u32,
        goal: Cell,
        next: u32,
        depth: u32,
        cut: u32,
    ) -> bool {
        let cl = &pred.clauses[ci as usize];
        let m = &mut *self.m;
        m.slots.clear();
        m.slots.resize(cl.nslots as usize, UNSET);
        if let (Cell::Ptr(off), Cell::Ptr(gp)) = (cl.head, goal) {
            for i in 0..pred.arity {
                let c = cl.code.cells[(off + 1 + i) as usize];
                let h = m.st.heap[(gp + 1 + i) as usize];
                if !cl.code.unify_arg(&mut m.st, c, h, &mut m.slots) {
                    return false;
                }
            }
        }
        let mut nx = next;
        let mut d = if next == NONE {
            0
        } else {
            m.frames[next as usize].depth
        };
        let _ = depth;
        for g in cl.body.iter().rev() {
            let c = cl.code.build(&mut m.st, *g, &mut m.slots);
            d += 1;
            m.frames.push(Frame {
                goal: Goal::Call(c),
                next: nx,
                cut,
                depth: d,
            });
            nx = m.frames.len() as u32 - 1;
        }
        self.cont = nx;
        true
    }

    /// Starts scanning fact source `stage` (a fact base, or the goal facts after the last base).
    fn start_scan(&self, stage: u32, _g: Cell, name: Sym, arity: u32, p: u32) -> Scan {
        if (stage as usize) < self.cx.bases.len() {
            let (k1, k2) = if arity == 0 {
                (None, None)
            } else {
                (
                    Key::of_cell(&self.m.st, self.a(p, 0)),
                    if arity > 1 {
                        Key::of_cell(&self.m.st, self.a(p, 1))
                    } else {
                        None
                    },
                )
            };
            self.cx.bases[stage as usize].scan(name, arity, k1, k2)
        } else {
            Scan { links: 0, next: 0 }
        }
    }

    /// The next fact that may match `g`, advancing through the sources.
    fn next_fact(&self, g: Cell, stage: &mut u32, scan: &mut Scan) -> Option<&'a Term> {
        let (name, arity, p) = match g {
            Cell::Atom(s) => (s, 0, 0),
            Cell::Ptr(p) => match self.m.st.heap[p as usize] {
                Cell::Fun(s, n) => (s, n, p),
                _ => return None,
            },
            _ => return None,
        };
        let nb = self.cx.bases.len() as u32;
        loop {
            if *stage < nb {
                if let Some(t) = self.cx.bases[*stage as usize].advance(scan) {
                    return Some(t);
                }
                *stage += 1;
                *scan = self.start_scan(*stage, g, name, arity, p);
            } else {
                let facts = self.cx.goal_facts;
                while (scan.next as usize) < facts.len() {
                    let t = &facts[scan.next as usize];
                    scan.next += 1;
                    if t.functor() == Some((name, arity as usize)) {
                        return Some(t);
                    }
                }
                return None;
            }
        }
    }

    fn try_facts(
        &mut self,
        goal: Cell,
        mut stage: u32,
        mut scan: Scan,
        b: u32,
        mut has_choice: bool,
        next: u32,
    ) -> KrResult<bool> {
        let mut cand = self.next_fact(goal, &mut stage, &mut scan);
        loop {
            let Some(t) = cand else {
                if has_choice {
                    self.m.cps.truncate(b as usize);
                }
                return Ok(false);
            };
            let (s0, sc0) = (stage, scan);
            let after = self.next_fact(goal, &mut stage, &mut scan);
            if after.is_some() {
                let alt = Alt::Facts {
                    goal,
                    stage: s0,
                    scan: sc0,
                };
                if has_choice {
                    self.m.cps[b as usize].alt = alt;
                } else {
                    self.push_choice(alt, next, 0, 0);
                    has_choice = true;
                }
            } else if has_choice {
                self.m.cps.truncate(b as usize);
                has_choice = false;
            }
            let (hm, tm, sm) = (
                self.m.st.heap.len(),
                self.m.st.trail.len(),
                self.m.st.strs.len(),
            );
            if self.unify_fact(goal, t) {
                self.cont = next;
                return Ok(true);
            }
            self.m.st.undo(tm);
            self.m.st.heap.truncate(hm);
            self.m.st.strs.truncate(sm);
            cand = after;
        }
    }

    /// Unifies a heap term with a stored fact without copying the fact (only the parts bound
    /// to variables are copied).
    pub fn unify_fact(&mut self, c: Cell, t: &Term) -> bool {
        // Fast path: the arguments of a fact are usually atomic.
        if let (Cell::Ptr(p), Term::Compound(k)) = (self.m.st.deref(c), t) {
            if self.m.st.heap[p as usize].fun() != Some((k.name, k.args.len() as u32)) {
                return false;
            }
            for (i, a) in k.args.iter().enumerate() {
                if !self.unify_fact_arg(self.a(p, i as u32), a) {
                    return false;
                }
            }
            return true;
        }
        self.unify_fact_arg(c, t)
    }

    fn unify_fact_arg(&mut self, c: Cell, t: &Term) -> bool {
        match (self.m.st.deref(c), t) {
            (Cell::Atom(x), Term::Atom(y)) => return x == *y,
            (Cell::Int(x), Term::Int(y)) => return x == *y,
            (Cell::Ref(a), Term::Atom(y)) => {
                self.m.st.bind(a, Cell::Atom(*y));
                return true;
            }
            (Cell::Ref(a), Term::Int(y)) => {
                self.m.st.bind(a, Cell::Int(*y));
                return true;
            }
            _ => {}
        }
        let mut work: Vec<(Cell, &Term)> = vec![(c, t)];
        while let Some((c, t)) = work.pop() {
            let c = self.m.st.deref(c);
            match (c, t) {
                (_, Term::Var(_)) => {}
                (Cell::Ref(a), _) => {
                    let v = match t {
                        Term::Atom(s) => Cell::Atom(*s),
                        Term::Int(i) => Cell::Int(*i),
                        Term::Float(f) => Cell::Flt(f.0),
                        _ => self.m.st.from_term(t, &mut Vec::new()),
                    };
                    self.m.st.bind(a, v);
                }
                (Cell::Atom(x), Term::Atom(y)) => {
                    if x != *y {
                        return false;
                    }
                }
                (Cell::Int(x), Term::Int(y)) => {
                    if x != *y {
                        return false;
                    }
                }
                (Cell::Flt(x), Term::Float(y)) => {
                    if crate::term::Float(x) != *y {
                        return false;
                    }
                }
                (Cell::Str(i), Term::Str(s)) => {
                    if *self.m.st.strs[i as usize] != **s {
                        return false;
                    }
                }
                (Cell::Ptr(p), Term::Compound(k)) => {
                    if self.m.st.heap[p as usize].fun() != Some((k.name, k.args.len() as u32)) {
                        return false;
                    }
                    for (i, a) in k.args.iter().enumerate() {
                        work.push((self.a(p, i as u32), a));
                    }
                }
                _ => return false,
            }
        }
        true
    }

    // ---- control constructs and built-ins ----

    #[allow(clippy::too_many_arguments)]
    fn builtin(
        &mut self,
        b: B,
        g: Cell,
        p: u32,
        next: u32,
        cut: u32,
        depth: u32,
    ) -> KrResult<bool> {
        let cps = self.m.cps.len() as u32;
        match b {
            B::True => {
                self.cont = next;
                Ok(true)
            }
            B::Fail => Ok(false),
            B::Cut => {
                self.m.cps.truncate(cut as usize);
                self.cont = next;
                Ok(true)
            }
            B::Comma => {
                let f2 = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), f2, cut, depth);
                Ok(true)
            }
            B::Or => {
                let lhs = self.ad(p, 0);
                let else_ = self.a(p, 1);
                match self.m.st.functor(lhs) {
                    Some((s, 2)) if s == wk::ARROW || s == wk::SOFT_ARROW => {
                        let Cell::Ptr(q) = lhs else { return Ok(false) };
                        self.push_choice(Alt::Goal(else_), next, cut, depth);
                        let then = self.push_frame(Goal::Call(self.a(q, 1)), next, cut, depth);
                        let gate = if s == wk::ARROW {
                            Goal::CutTo(cps)
                        } else {
                            Goal::SoftCut(cps)
                        };
                        let gate = self.push_frame(gate, then, cut, depth);
                        self.cont = self.push_frame(Goal::Call(self.a(q, 0)), gate, cps + 1, depth);
                    }
                    _ => {
                        self.push_choice(Alt::Goal(else_), next, cut, depth);
                        self.cont = self.push_frame(Goal::Call(lhs), next, cut, depth);
                    }
                }
                Ok(true)
            }
            B::IfThen => {
                let then = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                let gate = self.push_frame(Goal::CutTo(cps), then, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), gate, cps, depth);
                Ok(true)
            }
            B::SoftIfThen => {
                let then = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), then, cps, depth);
                Ok(true)
            }
            B::Not => {
                self.push_choice(Alt::NafSucceed, next, cut, depth);
                let f = self.push_frame(Goal::NafFail(cps), NONE, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), f, cps + 1, depth);
                Ok(true)
            }
            B::Call => {
                let arity = self.m.st.heap[p as usize].fun().map_or(1, |f| f.1);
                let goal = self.a(p, 0);
                let goal = if arity > 1 {
                    let extra: Vec<Cell> = (1..arity).map(|i| self.a(p, i)).collect();
                    self.add_args(goal, &extra)?
                } else {
                    goal
                };
                self.cont = self.push_frame(Goal::Call(goal), next, cps, depth);
                Ok(true)
            }
            B::Findall | B::Findall4 => {
                let bag = self.m.bags.len() as u32;
                self.m.bags.push(Bag::default());
                let tail = if b == B::Findall4 {
                    self.a(p, 3)
                } else {
                    Cell::Atom(wk::NIL)
                };
                self.push_choice(
                    Alt::FindallEnd {
                        bag,
                        result: self.a(p, 2),
                        tail,
                    },
                    next,
                    cut,
                    depth,
                );
                let f = self.push_frame(
                    Goal::Collect {
                        bag,
                        tmpl: self.a(p, 0),
                    },
                    NONE,
                    cut,
                    depth,
                );
                self.cont = self.push_frame(Goal::Call(self.a(p, 1)), f, cps + 1, depth);
                Ok(true)
            }
            B::Between => {
                let lo = builtins::int_arg(self, p, 0, "between", 3)?;
                let hi = match self.ad(p, 1) {
                    Cell::Atom(s) if matches!(s.name(), "inf" | "infinite") => i64::MAX,
                    _ => builtins::int_arg(self, p, 1, "between", 3)?,
                };
                match self.ad(p, 2) {
                    Cell::Int(x) => {
                        if lo <= x && x <= hi {
                            self.cont = next;
                            return Ok(true);
                        }
                        Ok(false)
                    }
                    x @ Cell::Ref(_) => {
                        if lo > hi {
                            return Ok(false);
                        }
                        if lo < hi {
                            self.push_choice(Alt::Between { x, cur: lo + 1, hi }, next, cut, depth);
                        }
                        let ok = self.unify(x, Cell::Int(lo));
                        self.cont = next;
                        Ok(ok)
                    }
                    other => Err(builtins::type_error(self, "integer", other, "between", 3)),
                }
            }
            B::Member => {
                let x = self.a(p, 0);
                let list = self.a(p, 1);
                self.push_choice(Alt::Member { x, list }, next, cut, depth);
                if self.member_step(x, list) {
                    self.cont = next;
                    Ok(true)
                } else {
                    Ok(false)
                }
            }
            B::Repeat => {
                self.push_choice(Alt::Repeat, next, cut, depth);
                self.cont = next;
                Ok(true)
            }
            _ => match builtins::det(self, b, g, p)? {
                builtins::Flow::Fail => Ok(false),
                builtins::Flow::True => {
                    self.cont = next;
                    Ok(true)
                }
                builtins::Flow::Call(goal) => {
                    self.cont = self.push_frame(Goal::Call(goal), next, cps, depth);
                    Ok(true)
                }
            },
        }
    }

    /// `goal` with `extra` arguments appended (for `call/N`, `maplist`, ...).
    pub fn add_args(&mut self, goal: Cell, extra: &[Cell]) -> KrResult<Cell> {
        let goal = self.m.st.deref(goal);
        let (name, args): (Sym, Vec<Cell>) = match goal {
            Cell::Atom(s) => (s, Vec::new()),
            Cell::Ptr(q) => match self.m.st.heap[q as usize] {
                Cell::Fun(s, n) => (s, (0..n).map(|i| self.a(q, i)).collect()),
                _ => return Ok(goal),
            },
            Cell::Ref(_) => return Err(KrError::iso(Term::atom("instantiation_error"), None)),
            other => {
                return Err(builtins::type_error(
                    self,
                    "callable",
                    other,
                    "call",
                    1 + extra.len(),
                ))
            }
        };
        let mut all = args;
        all.extend_from_slice(extra);
        Ok(self.m.st.new_struct(name, &all))
    }
}
