//! The binding store of the native engine: a heap of cells with a trail, unification, standard
//! order, and conversion from and to [`Term`]. Everything is iterative (explicit work stacks), so
//! deeply nested terms cannot overflow the Rust stack.

use crate::kr::fxhash::FxHashMap;
use crate::term::{well_known as wk, Float, Sym, Term};
use std::cmp::Ordering;
use std::sync::Arc;

/// One heap cell. Compound terms are a `Fun` header followed by their arguments; `Ptr` points at
/// the header. An unbound variable is a `Ref` to itself. `repr(u32)` fixes the layout that
/// [`write_ref`](super::code::write_ref) relies on: the tag in the first four bytes, a `Ref`'s
/// address in the next four.
#[derive(Clone, Copy, Debug)]
#[repr(u32)]
pub(crate) enum Cell {
    Ref(u32) = 0,
    Atom(Sym),
    Int(i64),
    Flt(f64),
    /// A string, by index into the store's string table.
    Str(u32),
    /// An integer beyond 64 bits: its decimal digits, by index into the string table.
    Big(u32),
    Ptr(u32),
    Fun(Sym, u32),
}

/// The store's heap, trail and string table lengths at a point of a proof (see [`Store::mark`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    heap: usize,
    trail: usize,
    strs: usize,
}

/// The heap, the trail and the string table of one query.
#[derive(Default)]
pub(crate) struct Store {
    pub heap: Vec<Cell>,
    pub trail: Vec<u32>,
    pub strs: Vec<Arc<str>>,
    pub occurs_check: bool,
    pairs: Vec<(Cell, Cell)>,
    /// Scratch stacks for [`super::code::Code`] (kept to avoid allocating per call).
    pub code_pairs: Vec<(Cell, Cell)>,
    /// Set when a traversal met a cyclic term (or an overlong one) and gave up; the solver
    /// turns it into an error.
    pub cyclic: std::cell::Cell<bool>,
    /// Set with `cyclic` when the traversal gave up because it exceeded `max_walk` steps
    /// (a term with so much sharing that walking it as a tree would never end).
    pub oversize: std::cell::Cell<bool>,
    /// Most steps one traversal may take (0: no limit).
    pub max_walk: usize,
    /// Cells converted to terms by [`Store::to_term`] since the query started (answers count
    /// against the memory budget).
    pub converted: std::cell::Cell<u64>,
}

/// Names given to unbound variables when answers are converted back to terms.
pub(crate) struct VarNames {
    /// Heap address of a variable and the name it gets in the answer.
    named: Vec<(u32, Sym)>,
    /// `named` hashed, once it is long (an answer can hold many unbound variables).
    index: Option<FxHashMap<u32, Sym>>,
    fresh: usize,
}

/// Names searched linearly up to this many; hashed beyond.
const LINEAR_NAMES: usize = 32;

impl VarNames {
    /// Names for a query whose variables live at the given addresses.
    pub fn new(query_vars: &[(Sym, Cell)]) -> VarNames {
        let mut names = VarNames {
            named: Vec::new(),
            index: None,
            fresh: 0,
        };
        for (s, c) in query_vars {
            if let Cell::Ref(a) = c {
                if names.find(*a).is_none() {
                    names.add(*a, *s);
                }
            }
        }
        names
    }

    fn find(&self, addr: u32) -> Option<Sym> {
        match &self.index {
            Some(m) => m.get(&addr).copied(),
            None => self.named.iter().find(|(a, _)| *a == addr).map(|(_, s)| *s),
        }
    }

    fn add(&mut self, addr: u32, s: Sym) {
        self.named.push((addr, s));
        match &mut self.index {
            Some(m) => {
                m.insert(addr, s);
            }
            None if self.named.len() > LINEAR_NAMES => {
                self.index = Some(self.named.iter().copied().collect());
            }
            None => {}
        }
    }

    fn name(&mut self, addr: u32) -> Sym {
        if let Some(s) = self.find(addr) {
            return s;
        }
        let s = Sym::intern(&format!("_R{}", self.fresh));
        self.fresh += 1;
        self.add(addr, s);
        s
    }
}

impl Store {
    /// Forgets everything (keeps the allocations).
    pub fn reset(&mut self) {
        self.cyclic.set(false);
        self.oversize.set(false);
        self.converted.set(0);
        self.heap.clear();
        self.trail.clear();
        self.strs.clear();
    }

    /// Step guard for traversals of `roots`: true (and the `cyclic` flag set) when the walk
    /// ran far longer than any acyclic term allows and a root is indeed cyclic.
    #[inline]
    pub fn runaway(&self, steps: &mut usize, limit: usize, roots: &[Cell]) -> bool {
        *steps += 1;
        if *steps <= limit || !steps.is_multiple_of(4096) {
            return false;
        }
        let cyc = roots.iter().any(|r| self.is_cyclic(*r));
        let over = self.max_walk > 0 && *steps > self.max_walk;
        if cyc || over {
            self.oversize.set(!cyc);
            self.cyclic.set(true);
        }
        cyc || over
    }

    /// A step limit for a traversal starting now.
    #[inline]
    pub fn step_limit(&self) -> usize {
        self.heap.len() * 2 + 4096
    }

    /// Follows bound variables.
    #[inline]
    pub fn deref(&self, mut c: Cell) -> Cell {
        while let Cell::Ref(a) = c {
            let n = self.heap[a as usize];
            if let Cell::Ref(b) = n {
                if b == a {
                    return c;
                }
            }
            c = n;
        }
        c
    }

    /// A fresh unbound variable.
    #[inline]
    pub fn new_var(&mut self) -> Cell {
        let a = self.heap.len() as u32;
        self.heap.push(Cell::Ref(a));
        Cell::Ref(a)
    }

    /// Binds the unbound variable at `a`.
    #[inline]
    pub fn bind(&mut self, a: u32, val: Cell) {
        self.heap[a as usize] = val;
        self.trail.push(a);
    }

    /// Undoes bindings back to trail mark `mark`.
    pub fn undo(&mut self, mark: usize) {
        while self.trail.len() > mark {
            let Some(a) = self.trail.pop() else { break };
            self.heap[a as usize] = Cell::Ref(a);
        }
    }

    /// The point to come back to with [`Store::rewind`].
    #[inline]
    pub fn mark(&self) -> Mark {
        Mark {
            heap: self.heap.len(),
            trail: self.trail.len(),
            strs: self.strs.len(),
        }
    }

    /// Undoes the bindings and drops the cells and strings made since `mark`.
    #[inline]
    pub fn rewind(&mut self, mark: Mark) {
        self.undo(mark.trail);
        self.heap.truncate(mark.heap);
        self.strs.truncate(mark.strs);
    }

    /// A string cell.
    pub fn new_str(&mut self, s: Arc<str>) -> Cell {
        self.strs.push(s);
        Cell::Str(self.strs.len() as u32 - 1)
    }

    /// A big-integer cell (the caller makes sure `n` does not fit in an `Int`).
    pub fn new_big(&mut self, n: &num_bigint::BigInt) -> Cell {
        self.strs.push(Arc::from(n.to_string().as_str()));
        Cell::Big(self.strs.len() as u32 - 1)
    }

    /// The value of a big-integer cell's digits.
    pub fn big(&self, i: u32) -> num_bigint::BigInt {
        self.strs[i as usize].parse().unwrap_or_default()
    }

    /// A compound term with the given arguments.
    pub fn new_struct(&mut self, name: Sym, args: &[Cell]) -> Cell {
        if args.is_empty() {
            return Cell::Atom(name);
        }
        let p = self.heap.len() as u32;
        self.heap.push(Cell::Fun(name, args.len() as u32));
        self.heap.extend_from_slice(args);
        Cell::Ptr(p)
    }

    /// A proper list (or a partial list ending in `tail`).
    pub fn new_list(&mut self, items: &[Cell], tail: Cell) -> Cell {
        let mut acc = tail;
        for &it in items.iter().rev() {
            acc = self.new_struct(wk::DOT, &[it, acc]);
        }
        acc
    }

    /// Name and arity of a callable cell (after deref).
    pub fn functor(&self, c: Cell) -> Option<(Sym, u32)> {
        match self.deref(c) {
            Cell::Atom(s) => Some((s, 0)),
            Cell::Ptr(p) => match self.heap[p as usize] {
                Cell::Fun(s, n) => Some((s, n)),
                _ => None,
            },
            _ => None,
        }
    }

    /// Argument `i` (0-based) of the compound at `p`.
    #[inline]
    pub fn arg(&self, p: u32, i: u32) -> Cell {
        self.heap[(p + 1 + i) as usize]
    }

    /// If `c` is a list cell `[H|T]`, its head and tail.
    #[inline]
    pub fn cons(&self, c: Cell) -> Option<(Cell, Cell)> {
        if let Cell::Ptr(p) = self.deref(c) {
            if let Cell::Fun(s, 2) = self.heap[p as usize] {
                if s == wk::DOT {
                    return Some((self.arg(p, 0), self.arg(p, 1)));
                }
            }
        }
        None
    }

    /// The items of a list and what it ends in (dereferenced): `[]` for a proper list, an unbound
    /// variable for a partial list, anything else for a non-list.
    /// A cyclic list (`L = [a|L]`) sets the `cyclic` flag and ends in `[]` after as many
    /// items as the heap could hold, so the walk always stops.
    pub fn list_items(&self, mut c: Cell) -> (Vec<Cell>, Cell) {
        let mut items = Vec::new();
        // An acyclic list has at most one cell per three heap cells.
        let bound = self.heap.len() / 3 + 1;
        loop {
            match self.cons(c) {
                Some((h, t)) => {
                    if items.len() > bound {
                        self.cyclic.set(true);
                        return (items, Cell::Atom(wk::NIL));
                    }
                    items.push(h);
                    c = t;
                }
                None => return (items, self.deref(c)),
            }
        }
    }

    /// True when the two atomic cells are the same constant.
    fn same_atomic(&self, a: Cell, b: Cell) -> bool {
        match (a, b) {
            (Cell::Atom(x), Cell::Atom(y)) => x == y,
            (Cell::Int(x), Cell::Int(y)) => x == y,
            (Cell::Flt(x), Cell::Flt(y)) => Float(x) == Float(y),
            (Cell::Str(x), Cell::Str(y)) | (Cell::Big(x), Cell::Big(y)) => {
                self.strs[x as usize] == self.strs[y as usize]
            }
            _ => false,
        }
    }

    /// Unifies two cells, recording bindings on the trail. On failure some bindings may remain:
    /// the caller backtracks (undoes the trail) anyway.
    pub fn unify(&mut self, a: Cell, b: Cell) -> bool {
        let mut pairs = std::mem::take(&mut self.pairs);
        pairs.clear();
        pairs.push((a, b));
        let ok = self.unify_pairs(&mut pairs);
        self.pairs = pairs;
        ok
    }

    fn unify_pairs(&mut self, pairs: &mut Vec<(Cell, Cell)>) -> bool {
        let (mut steps, limit) = (0usize, self.step_limit());
        while let Some((a, b)) = pairs.pop() {
            if self.runaway(&mut steps, limit, &[a, b]) {
                return false;
            }
            let a = self.deref(a);
            let b = self.deref(b);
            match (a, b) {
                (Cell::Ref(x), Cell::Ref(y)) => {
                    if x != y {
                        if x < y {
                            self.bind(y, a)
                        } else {
                            self.bind(x, b)
                        }
                    }
                }
                (Cell::Ref(x), other) | (other, Cell::Ref(x)) => {
                    if self.occurs_check && self.occurs(x, other) {
                        return false;
                    }
                    self.bind(x, other)
                }
                (Cell::Ptr(p), Cell::Ptr(q)) => {
                    if p == q {
                        continue;
                    }
                    let (Cell::Fun(f, n), Cell::Fun(g, m)) =
                        (self.heap[p as usize], self.heap[q as usize])
                    else {
                        return false;
                    };
                    if f != g || n != m {
                        return false;
                    }
                    for i in (0..n).rev() {
                        pairs.push((self.arg(p, i), self.arg(q, i)));
                    }
                }
                _ => {
                    if !self.same_atomic(a, b) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// True when the variable at `v` occurs in `t`.
    pub fn occurs(&self, v: u32, t: Cell) -> bool {
        let (mut steps, limit) = (0usize, self.step_limit());
        let mut stack = vec![t];
        while let Some(c) = stack.pop() {
            if self.runaway(&mut steps, limit, &[t]) {
                return true;
            }
            match self.deref(c) {
                Cell::Ref(a) if a == v => return true,
                Cell::Ptr(p) => {
                    if let Cell::Fun(_, n) = self.heap[p as usize] {
                        stack.extend((0..n).map(|i| self.arg(p, i)));
                    }
                }
                _ => {}
            }
        }
        false
    }

    /// Copies a term onto the heap; variables are looked up in (and added to) `vars`.
    pub fn put_term(&mut self, t: &Term, vars: &mut Vec<(Sym, Cell)>) -> Cell {
        let root = self.heap.len() as u32;
        self.heap.push(Cell::Ref(root));
        self.put_shallow(root, t, vars, 4);
        self.heap[root as usize]
    }

    /// Fills `slot` with `t` by bounded recursion (no allocation for the usual small goals);
    /// parts nested deeper than `depth` are copied by the iterative [`Store::put_deep`], in
    /// the same left-to-right order, so variables are numbered alike.
    fn put_shallow(&mut self, slot: u32, t: &Term, vars: &mut Vec<(Sym, Cell)>, depth: u32) {
        let c = match t {
            Term::Compound(c) if depth > 0 => {
                let p = self.heap.len() as u32;
                self.heap.push(Cell::Fun(c.name, c.args.len() as u32));
                for i in 0..c.args.len() {
                    self.heap.push(Cell::Ref(p + 1 + i as u32));
                }
                for (i, a) in c.args.iter().enumerate() {
                    self.put_shallow(p + 1 + i as u32, a, vars, depth - 1);
                }
                Cell::Ptr(p)
            }
            _ => self.leaf_cell(slot, t, vars),
        };
        self.heap[slot as usize] = c;
    }

    /// The cell of an atomic term or variable placed in `slot` (a variable seen before shares
    /// the cell of its first occurrence); a compound term is copied by [`Store::put_deep`].
    #[inline]
    fn leaf_cell(&mut self, slot: u32, t: &Term, vars: &mut Vec<(Sym, Cell)>) -> Cell {
        match t {
            Term::Atom(s) => Cell::Atom(*s),
            Term::Int(i) => Cell::Int(*i),
            Term::Float(f) => Cell::Flt(f.0),
            Term::Str(s) => self.new_str(s.clone()),
            Term::BigInt(b) => self.new_big(b),
            Term::Var(v) => {
                if *v == wk::UNDERSCORE {
                    Cell::Ref(slot)
                } else if let Some((_, c)) = vars.iter().find(|(n, _)| n == v) {
                    *c
                } else {
                    vars.push((*v, Cell::Ref(slot)));
                    Cell::Ref(slot)
                }
            }
            Term::Compound(_) => self.put_deep(t, vars),
        }
    }

    /// The iterative copy behind [`Store::put_term`].
    fn put_deep(&mut self, t: &Term, vars: &mut Vec<(Sym, Cell)>) -> Cell {
        let root = self.heap.len() as u32;
        self.heap.push(Cell::Ref(root));
        let mut work: Vec<(u32, &Term)> = vec![(root, t)];
        while let Some((slot, t)) = work.pop() {
            let c = match t {
                Term::Compound(c) => {
                    let p = self.heap.len() as u32;
                    self.heap.push(Cell::Fun(c.name, c.args.len() as u32));
                    for i in 0..c.args.len() {
                        self.heap.push(Cell::Ref(p + 1 + i as u32));
                    }
                    // Left to right, so that variables are numbered in reading order.
                    for (i, a) in c.args.iter().enumerate().rev() {
                        work.push((p + 1 + i as u32, a));
                    }
                    Cell::Ptr(p)
                }
                _ => self.leaf_cell(slot, t, vars),
            };
            self.heap[slot as usize] = c;
        }
        self.heap[root as usize]
    }

    /// Converts a heap term back to a [`Term`]; unbound variables get names from `names`.
    pub fn to_term(&self, c: Cell, names: &mut VarNames) -> Term {
        enum Work {
            Visit(Cell),
            Build(Sym, u32),
        }
        let mut work = vec![Work::Visit(c)];
        let mut out: Vec<Term> = Vec::new();
        let (mut steps, limit) = (0usize, self.step_limit());
        while let Some(w) = work.pop() {
            if self.runaway(&mut steps, limit, &[c]) {
                return Term::Atom(wk::NIL);
            }
            match w {
                Work::Visit(c) => match self.deref(c) {
                    Cell::Ref(a) => out.push(Term::Var(names.name(a))),
                    Cell::Atom(s) => out.push(Term::Atom(s)),
                    Cell::Int(i) => out.push(Term::Int(i)),
                    Cell::Flt(f) => out.push(Term::Float(Float(f))),
                    Cell::Str(i) => out.push(Term::Str(self.strs[i as usize].clone())),
                    Cell::Big(i) => out.push(Term::integer(self.big(i))),
                    Cell::Ptr(p) => {
                        if let Cell::Fun(s, n) = self.heap[p as usize] {
                            work.push(Work::Build(s, n));
                            for i in (0..n).rev() {
                                work.push(Work::Visit(self.arg(p, i)));
                            }
                        }
                    }
                    Cell::Fun(s, _) => out.push(Term::Atom(s)),
                },
                Work::Build(s, n) => {
                    let args = out.split_off(out.len() - n as usize);
                    out.push(Term::compound(s, args));
                }
            }
        }
        self.converted.set(self.converted.get() + steps as u64);
        out.pop().unwrap_or(Term::Atom(wk::NIL))
    }

    fn order_class(c: Cell) -> u8 {
        match c {
            Cell::Ref(_) => 0,
            Cell::Int(_) | Cell::Flt(_) | Cell::Big(_) => 1,
            Cell::Atom(_) => 3,
            Cell::Str(_) => 4,
            _ => 5,
        }
    }

    /// Standard order of terms (like [`Term::compare`]; variables by age).
    pub fn compare(&self, a: Cell, b: Cell) -> Ordering {
        let (a, b) = (self.deref(a), self.deref(b));
        if !matches!((a, b), (Cell::Ptr(_), Cell::Ptr(_))) {
            return self.compare_shallow(a, b);
        }
        let (mut steps, limit) = (0usize, self.step_limit());
        let mut stack = vec![(a, b)];
        while let Some((a, b)) = stack.pop() {
            if self.runaway(&mut steps, limit, &[a, b]) {
                return Ordering::Equal;
            }
            let a = self.deref(a);
            let b = self.deref(b);
            let o = match (a, b) {
                (Cell::Ptr(p), Cell::Ptr(q)) => {
                    if p == q {
                        continue;
                    }
                    let (Cell::Fun(f, n), Cell::Fun(g, m)) =
                        (self.heap[p as usize], self.heap[q as usize])
                    else {
                        return Ordering::Equal;
                    };
                    let o = n.cmp(&m).then_with(|| {
                        if f == g {
                            Ordering::Equal
                        } else {
                            f.name().cmp(g.name())
                        }
                    });
                    if o == Ordering::Equal {
                        for i in (0..n).rev() {
                            stack.push((self.arg(p, i), self.arg(q, i)));
                        }
                    }
                    o
                }
                _ => self.compare_shallow(a, b),
            };
            if o != Ordering::Equal {
                return o;
            }
        }
        Ordering::Equal
    }

    /// Standard order of two dereferenced cells that are not both compound.
    fn compare_shallow(&self, a: Cell, b: Cell) -> Ordering {
        let o = Self::order_class(a).cmp(&Self::order_class(b));
        if o != Ordering::Equal {
            return o;
        }
        match (a, b) {
            (Cell::Ref(x), Cell::Ref(y)) => x.cmp(&y),
            (Cell::Int(x), Cell::Int(y)) => x.cmp(&y),
            (Cell::Flt(x), Cell::Flt(y)) => x.total_cmp(&y),
            (Cell::Int(x), Cell::Flt(y)) => Term::Int(x).compare(&Term::Float(Float(y))),
            (Cell::Flt(x), Cell::Int(y)) => Term::Float(Float(x)).compare(&Term::Int(y)),
            (Cell::Atom(x), Cell::Atom(y)) => {
                if x == y {
                    Ordering::Equal
                } else {
                    x.name().cmp(y.name())
                }
            }
            (Cell::Str(x), Cell::Str(y)) => self.strs[x as usize].cmp(&self.strs[y as usize]),
            (Cell::Big(_), _) | (_, Cell::Big(_)) => self.number(a).compare(&self.number(b)),
            _ => Ordering::Equal,
        }
    }

    /// A number cell as a term (for comparisons involving big integers).
    fn number(&self, c: Cell) -> Term {
        match c {
            Cell::Int(i) => Term::Int(i),
            Cell::Flt(f) => Term::Float(Float(f)),
            Cell::Big(i) => Term::integer(self.big(i)),
            _ => Term::Atom(wk::NIL),
        }
    }

    /// True when the two terms are variants of each other (equal up to renaming of variables).
    pub fn variant(&self, a: Cell, b: Cell) -> bool {
        let mut map: Vec<(u32, u32)> = Vec::new();
        let (mut steps, limit) = (0usize, self.step_limit());
        let mut stack = vec![(a, b)];
        while let Some((a, b)) = stack.pop() {
            if self.runaway(&mut steps, limit, &[a, b]) {
                return false;
            }
            match (self.deref(a), self.deref(b)) {
                (Cell::Ref(x), Cell::Ref(y)) => {
                    match map.iter().find(|(p, q)| *p == x || *q == y) {
                        Some(&(p, q)) => {
                            if p != x || q != y {
                                return false;
                            }
                        }
                        None => map.push((x, y)),
                    }
                }
                (Cell::Ptr(p), Cell::Ptr(q)) => {
                    let (Cell::Fun(f, n), Cell::Fun(g, m)) =
                        (self.heap[p as usize], self.heap[q as usize])
                    else {
                        return false;
                    };
                    if f != g || n != m {
                        return false;
                    }
                    for i in 0..n {
                        stack.push((self.arg(p, i), self.arg(q, i)));
                    }
                }
                (x, y) => {
                    if !self.same_atomic(x, y) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Copies a term with fresh variables (`copy_term/2`).
    pub fn copy(&mut self, c: Cell) -> Cell {
        let mut map: Vec<(u32, Cell)> = Vec::new();
        let root = self.heap.len() as u32;
        self.heap.push(Cell::Ref(root));
        let mut work = vec![(root, c)];
        let (mut steps, limit) = (0usize, self.step_limit());
        while let Some((slot, c)) = work.pop() {
            if self.runaway(&mut steps, limit, &[c]) {
                return self.heap[root as usize];
            }
            let v = match self.deref(c) {
                Cell::Ref(a) => match map.iter().find(|(x, _)| *x == a) {
                    Some((_, c)) => *c,
                    None => {
                        map.push((a, Cell::Ref(slot)));
                        Cell::Ref(slot)
                    }
                },
                Cell::Ptr(p) => {
                    let Cell::Fun(f, n) = self.heap[p as usize] else {
                        continue;
                    };
                    let q = self.heap.len() as u32;
                    self.heap.push(Cell::Fun(f, n));
                    for i in 0..n {
                        self.heap.push(Cell::Ref(q + 1 + i));
                        work.push((q + 1 + i, self.arg(p, i)));
                    }
                    Cell::Ptr(q)
                }
                other => other,
            };
            self.heap[slot as usize] = v;
        }
        self.heap[root as usize]
    }

    /// The distinct unbound variables of a term, in depth-first left-to-right order.
    pub fn term_vars(&self, c: Cell, out: &mut Vec<u32>) {
        let (mut steps, limit) = (0usize, self.step_limit());
        let mut stack = vec![c];
        while let Some(c) = stack.pop() {
            if self.runaway(&mut steps, limit, &[c]) {
                return;
            }
            match self.deref(c) {
                Cell::Ref(a) if !out.contains(&a) => out.push(a),
                Cell::Ref(_) => {}
                Cell::Ptr(p) => {
                    if let Cell::Fun(_, n) = self.heap[p as usize] {
                        stack.extend((0..n).rev().map(|i| self.arg(p, i)));
                    }
                }
                _ => {}
            }
        }
    }

    /// True when the term is cyclic (possible without the occurs check, e.g. `X = f(X)`).
    /// A depth-first walk that marks the compound cells on its path; shared sub-terms are
    /// visited once, so the time is linear in the number of distinct cells.
    pub fn is_cyclic(&self, c: Cell) -> bool {
        if !matches!(self.deref(c), Cell::Ptr(_)) {
            return false;
        }
        // false: on the current path; true: finished (known acyclic).
        let mut state: FxHashMap<u32, bool> = FxHashMap::default();
        // (compound address, next argument to visit)
        let mut path: Vec<(u32, u32)> = Vec::new();
        let Cell::Ptr(root) = self.deref(c) else {
            return false;
        };
        state.insert(root, false);
        path.push((root, 0));
        while let Some(&mut (p, ref mut i)) = path.last_mut() {
            let n = self.heap[p as usize].fun().map_or(0, |f| f.1);
            if *i >= n {
                state.insert(p, true);
                path.pop();
                continue;
            }
            let arg = self.arg(p, *i);
            *i += 1;
            if let Cell::Ptr(q) = self.deref(arg) {
                match state.get(&q) {
                    Some(false) => return true,
                    Some(true) => {}
                    None => {
                        state.insert(q, false);
                        path.push((q, 0));
                    }
                }
            }
        }
        false
    }

    /// True when the term has no unbound variables.
    pub fn is_ground(&self, c: Cell) -> bool {
        let (mut steps, limit) = (0usize, self.step_limit());
        let mut stack = vec![c];
        while let Some(c) = stack.pop() {
            if self.runaway(&mut steps, limit, &[c]) {
                return false;
            }
            match self.deref(c) {
                Cell::Ref(_) => return false,
                Cell::Ptr(p) => {
                    if let Cell::Fun(_, n) = self.heap[p as usize] {
                        stack.extend((0..n).map(|i| self.arg(p, i)));
                    }
                }
                _ => {}
            }
        }
        true
    }
}
