//! Compiled terms: a term flattened into cells with numbered variable slots, used for knowledge
//! clauses and for the copies `findall/3` keeps. Heads are unified against heap goals without
//! copying them; bodies are built on the heap when a clause is used.

use super::store::{Cell, Store};
use crate::term::{well_known as wk, Sym, Term};
use std::sync::Arc;

/// Marks a variable slot that is not bound yet in a slot array.
pub(crate) const UNSET: Cell = Cell::Ref(u32::MAX);

/// Flattened terms. Inside a `Code`, `Ref(n)` is variable slot `n`, `Ptr(o)` is the offset of a
/// `Fun` header in `cells`, and `Str(i)` indexes `strs`. A compound term is laid out depth
/// first, so a structure and everything inside it occupy one block of cells, `o..ends[o]`,
/// laid out as the heap copy will be: building it is one pass over the block.
#[derive(Clone, Debug, Default)]
pub(crate) struct Code {
    pub cells: Vec<Cell>,
    pub strs: Vec<Arc<str>>,
    /// For the offset of each `Fun` header, the end of its block (0 elsewhere).
    ends: Vec<u32>,
}

/// First-argument key of a clause or goal, for indexing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Key {
    Atom(Sym),
    Int(i64),
    Flt(u64),
    Str,
    Fun(Sym, u32),
}

impl Key {
    /// The key of a term (`None` for a variable).
    pub fn of_term(t: &Term) -> Option<Key> {
        Some(match t {
            Term::Atom(s) => Key::Atom(*s),
            Term::Int(i) => Key::Int(*i),
            Term::Float(f) => Key::Flt(if f.0 == 0.0 { 0 } else { f.0.to_bits() }),
            // Strings and big integers share a key: unification tells them apart.
            Term::Str(_) | Term::BigInt(_) => Key::Str,
            Term::Compound(c) => Key::Fun(c.name, c.args.len() as u32),
            Term::Var(_) => return None,
        })
    }

    /// The key of a dereferenced heap cell (`None` for a variable).
    #[inline]
    pub fn of_cell(store: &Store, c: Cell) -> Option<Key> {
        Some(match store.deref(c) {
            Cell::Atom(s) => Key::Atom(s),
            Cell::Int(i) => Key::Int(i),
            Cell::Flt(f) => Key::Flt(if f == 0.0 { 0 } else { f.to_bits() }),
            Cell::Str(_) | Cell::Big(_) => Key::Str,
            Cell::Ptr(p) => match store.heap[p as usize] {
                Cell::Fun(s, n) => Key::Fun(s, n),
                _ => return None,
            },
            _ => return None,
        })
    }
}

impl Code {
    /// The memory this code takes, in heap cells (a cell is 16 bytes, a block end 4).
    pub fn size_in_cells(&self) -> usize {
        self.cells.len() + self.ends.len() / 4
    }

    /// Appends `t`, numbering its variables through `vars`; returns the root cell.
    pub fn add(&mut self, t: &Term, vars: &mut Vec<Sym>) -> Cell {
        let start = self.cells.len();
        let mut root = UNSET;
        let mut work: Vec<(Option<usize>, &Term)> = vec![(None, t)];
        while let Some((slot, t)) = work.pop() {
            let c = match t {
                Term::Atom(s) => Cell::Atom(*s),
                Term::Int(i) => Cell::Int(*i),
                Term::Float(f) => Cell::Flt(f.0),
                Term::Str(s) => {
                    self.strs.push(s.clone());
                    Cell::Str(self.strs.len() as u32 - 1)
                }
                Term::BigInt(b) => {
                    self.strs.push(std::sync::Arc::from(b.to_string().as_str()));
                    Cell::Big(self.strs.len() as u32 - 1)
                }
                Term::Var(v) => {
                    let n = if *v == wk::UNDERSCORE {
                        vars.push(*v);
                        vars.len() - 1
                    } else {
                        match vars.iter().position(|x| x == v) {
                            Some(n) => n,
                            None => {
                                vars.push(*v);
                                vars.len() - 1
                            }
                        }
                    };
                    Cell::Ref(n as u32)
                }
                Term::Compound(c) => {
                    let p = self.cells.len();
                    self.cells.push(Cell::Fun(c.name, c.args.len() as u32));
                    for (i, a) in c.args.iter().enumerate() {
                        self.cells.push(UNSET);
                        work.push((Some(p + 1 + i), a));
                    }
                    Cell::Ptr(p as u32)
                }
            };
            match slot {
                Some(s) => self.cells[s] = c,
                None => root = c,
            }
        }
        self.mark_blocks(start);
        root
    }

    /// Records the block ends of the structures added from offset `start` on (a run of
    /// headers, each followed by its arguments; inner structures come after outer ones).
    fn mark_blocks(&mut self, start: usize) {
        self.ends.resize(self.cells.len(), 0);
        let mut heads = Vec::new();
        let mut i = start;
        while let Some(f) = self.cells.get(i) {
            heads.push(i);
            i += 1 + f.fun().map_or(0, |f| f.1 as usize);
        }
        for &h in heads.iter().rev() {
            let n = self.cells[h].fun().map_or(0, |f| f.1 as usize);
            let mut end = (h + 1 + n) as u32;
            for c in &self.cells[h + 1..h + 1 + n] {
                if let Cell::Ptr(o) = c {
                    end = end.max(self.ends[*o as usize]);
                }
            }
            self.ends[h] = end;
        }
    }

    /// Copies a heap term into this code (variables numbered through `vars`, by address).
    pub fn add_cell(&mut self, store: &Store, c: Cell, vars: &mut Vec<u32>) -> Cell {
        if let c @ (Cell::Atom(_) | Cell::Int(_) | Cell::Flt(_)) = store.deref(c) {
            return c;
        }
        let start = self.cells.len();
        let mut root = UNSET;
        let mut work: Vec<(Option<usize>, Cell)> = vec![(None, c)];
        let (mut steps, limit) = (0usize, store.step_limit());
        while let Some((slot, c)) = work.pop() {
            if store.runaway(&mut steps, limit, &[c]) {
                // The solver reports the cyclic term; leave a well-formed placeholder.
                self.mark_blocks(start);
                return Cell::Atom(wk::NIL);
            }
            let v = match store.deref(c) {
                Cell::Ref(a) => {
                    let n = match vars.iter().position(|x| *x == a) {
                        Some(n) => n,
                        None => {
                            vars.push(a);
                            vars.len() - 1
                        }
                    };
                    Cell::Ref(n as u32)
                }
                Cell::Str(i) => {
                    self.strs.push(store.strs[i as usize].clone());
                    Cell::Str(self.strs.len() as u32 - 1)
                }
                Cell::Big(i) => {
                    self.strs.push(store.strs[i as usize].clone());
                    Cell::Big(self.strs.len() as u32 - 1)
                }
                Cell::Ptr(p) => {
                    let Cell::Fun(f, n) = store.heap[p as usize] else {
                        continue;
                    };
                    let q = self.cells.len();
                    self.cells.push(Cell::Fun(f, n));
                    for i in 0..n {
                        self.cells.push(UNSET);
                        work.push((Some(q + 1 + i as usize), store.arg(p, i)));
                    }
                    Cell::Ptr(q as u32)
                }
                other => other,
            };
            match slot {
                Some(s) => self.cells[s] = v,
                None => root = v,
            }
        }
        self.mark_blocks(start);
        root
    }

    /// Builds the code term `root` on the heap, binding unset slots to fresh variables.
    #[inline]
    pub fn build(&self, store: &mut Store, root: Cell, slots: &mut [Cell]) -> Cell {
        match root {
            Cell::Ref(n) if (n as usize) < slots.len() => {
                let s = &mut slots[n as usize];
                if let Cell::Ref(u32::MAX) = *s {
                    *s = store.new_var();
                }
                *s
            }
            Cell::Ref(_) => store.new_var(),
            Cell::Str(i) => store.new_str(self.strs[i as usize].clone()),
            Cell::Big(i) => {
                store.new_str(self.strs[i as usize].clone());
                Cell::Big(store.strs.len() as u32 - 1)
            }
            Cell::Ptr(off) => Cell::Ptr(self.build_block(store, off, slots)),
            other => other,
        }
    }

    /// Copies the block of the structure at `off` to the heap (where it keeps its layout);
    /// returns the heap address of the copy.
    #[inline]
    fn build_block(&self, store: &mut Store, off: u32, slots: &mut [Cell]) -> u32 {
        self.copy_cells(store, off, self.ends[off as usize], slots)
    }

    /// Builds the arguments of the compiled goal `root` (a structure or an atom) on the heap,
    /// laid out as the goal's block would be without its header cell (so fresh variables are
    /// made in the same order as when the whole goal is built); returns the address of the
    /// first argument.
    #[inline]
    pub fn build_args(&self, store: &mut Store, root: Cell, slots: &mut [Cell]) -> u32 {
        match root {
            Cell::Ptr(off) => self.copy_cells(store, off + 1, self.ends[off as usize], slots),
            _ => store.heap.len() as u32,
        }
    }

    /// The range of the argument cells of the compiled goal `root` when none of them is a
    /// structure (they are slots and constants, each built alone); `None` otherwise. Computed
    /// once per clause when it is loaded (see `Clause::flat_first`).
    pub fn flat_args(&self, root: Cell) -> Option<(u32, u32)> {
        match root {
            Cell::Ptr(off) => {
                let (from, end) = (off + 1, self.ends[off as usize]);
                let n = self.cells[off as usize].fun().map_or(0, |f| f.1);
                (end - from == n).then_some((from, end))
            }
            _ => Some((0, 0)),
        }
    }

    /// Copies cells `from..end` of this code to the top of the heap, rewriting the cells that
    /// mean something else on the heap (slots, offsets, string indices) as they are written;
    /// returns the heap address of the first copied cell. One pass into the reserved capacity:
    /// a block is a few cells, for which a copy call and a second pass cost more than the work.
    #[inline]
    fn copy_cells(&self, store: &mut Store, from: u32, end: u32, slots: &mut [Cell]) -> u32 {
        self.copy_block(store, from, end, slots)
    }

    /// [`Code::copy_cells`], inlined where it is called.
    #[inline(always)]
    fn copy_block(&self, store: &mut Store, from: u32, end: u32, slots: &mut [Cell]) -> u32 {
        let Store { heap, strs, .. } = store;
        let base = heap.len() as u32;
        let src = &self.cells[from as usize..end as usize];
        heap.reserve(src.len());
        let dst = &mut heap.spare_capacity_mut()[..src.len()];
        for ((d, &s), a) in dst.iter_mut().zip(src).zip(base..) {
            let c = d.write(s);
            match s {
                // A set slot's value is copied whole (see `Solver::try_clause`).
                // A new variable is written whole, as the callee reads it (see `write_ref`).
                Cell::Ref(k) => match slots.get(k as usize) {
                    Some(&v) if !matches!(v, Cell::Ref(u32::MAX)) => *c = v,
                    Some(_) => {
                        write_ref(&mut slots[k as usize], a);
                        write_ref(c, a);
                    }
                    None => write_ref(c, a),
                },
                Cell::Ptr(o) => *c = Cell::Ptr(o - from + base),
                Cell::Str(j) => {
                    strs.push(self.strs[j as usize].clone());
                    *c = Cell::Str(strs.len() as u32 - 1);
                }
                Cell::Big(j) => {
                    strs.push(self.strs[j as usize].clone());
                    *c = Cell::Big(strs.len() as u32 - 1);
                }
                _ => {}
            }
        }
        // SAFETY: the loop initialised every cell of `dst`, the `src.len()` cells after the
        // old length (a zip runs to its shortest side; `dst` and `src` have that length, and
        // `base..` does not end first), within the capacity reserved above.
        unsafe { heap.set_len(base as usize + src.len()) };
        base
    }

    /// Like [`Code::unify`], with the common cases (a new variable, a constant) inline.
    #[inline(always)]
    pub fn unify_arg(&self, store: &mut Store, code: Cell, heap: Cell, slots: &mut [Cell]) -> bool {
        match code {
            Cell::Ref(n) if matches!(slots[n as usize], Cell::Ref(u32::MAX)) => {
                slots[n as usize] = heap;
                true
            }
            Cell::Atom(x) => match store.deref(heap) {
                Cell::Atom(y) => x == y,
                Cell::Ref(a) => {
                    store.bind(a, code);
                    true
                }
                _ => false,
            },
            Cell::Int(x) => match store.deref(heap) {
                Cell::Int(y) => x == y,
                Cell::Ref(a) => {
                    store.bind(a, code);
                    true
                }
                _ => false,
            },
            Cell::Ptr(off) => match store.deref(heap) {
                Cell::Ptr(p) => {
                    let f = self.cells[off as usize];
                    if store.heap[p as usize].fun() != f.fun() {
                        return false;
                    }
                    let n = f.fun().map_or(0, |f| f.1);
                    for i in 0..n {
                        let c = self.cells[(off + 1 + i) as usize];
                        let h = store.heap[(p + 1 + i) as usize];
                        let ok = match c {
                            Cell::Ref(k) if matches!(slots[k as usize], Cell::Ref(u32::MAX)) => {
                                slots[k as usize] = h;
                                true
                            }
                            _ => self.unify(store, c, h, slots),
                        };
                        if !ok {
                            return false;
                        }
                    }
                    true
                }
                Cell::Ref(a) => {
                    // The block is copied inline: here it is a head's structure met by an
                    // unbound argument (an output list cell), a few cells for which the call
                    // costs as much as the copy.
                    let end = self.ends[off as usize];
                    let t = Cell::Ptr(self.copy_block(store, off, end, slots));
                    if store.occurs_check && store.occurs(a, t) {
                        return false;
                    }
                    store.bind(a, t);
                    true
                }
                _ => false,
            },
            _ => self.unify(store, code, heap, slots),
        }
    }

    /// Unifies code term `code` with heap term `heap`, binding slots on first sight.
    pub fn unify(&self, store: &mut Store, code: Cell, heap: Cell, slots: &mut [Cell]) -> bool {
        let mut work = std::mem::take(&mut store.code_pairs);
        work.clear();
        let ok = self.unify_with(store, code, heap, slots, &mut work);
        store.code_pairs = work;
        ok
    }

    fn unify_with(
        &self,
        store: &mut Store,
        code: Cell,
        heap: Cell,
        slots: &mut [Cell],
        work: &mut Vec<(Cell, Cell)>,
    ) -> bool {
        let (mut code, mut heap) = (code, heap);
        loop {
            match code {
                Cell::Ref(n) => {
                    let s = slots[n as usize];
                    if let Cell::Ref(u32::MAX) = s {
                        slots[n as usize] = heap;
                    } else if !store.unify(s, heap) {
                        return false;
                    }
                }
                Cell::Ptr(off) => {
                    let Cell::Fun(f, n) = self.cells[off as usize] else {
                        return false;
                    };
                    match store.deref(heap) {
                        Cell::Ref(a) => {
                            let t = self.build(store, code, slots);
                            if store.occurs_check && store.occurs(a, t) {
                                return false;
                            }
                            store.bind(a, t);
                        }
                        Cell::Ptr(p) => {
                            if store.heap[p as usize].fun() != Some((f, n)) {
                                return false;
                            }
                            for i in (1..n).rev() {
                                work.push((self.cells[(off + 1 + i) as usize], store.arg(p, i)));
                            }
                            code = self.cells[(off + 1) as usize];
                            heap = store.arg(p, 0);
                            continue;
                        }
                        _ => return false,
                    }
                }
                Cell::Str(i) => match store.deref(heap) {
                    Cell::Ref(a) => {
                        let c = store.new_str(self.strs[i as usize].clone());
                        store.bind(a, c);
                    }
                    Cell::Str(j) => {
                        if store.strs[j as usize] != self.strs[i as usize] {
                            return false;
                        }
                    }
                    _ => return false,
                },
                Cell::Big(i) => match store.deref(heap) {
                    Cell::Ref(a) => {
                        store.new_str(self.strs[i as usize].clone());
                        let c = Cell::Big(store.strs.len() as u32 - 1);
                        store.bind(a, c);
                    }
                    Cell::Big(j) => {
                        if store.strs[j as usize] != self.strs[i as usize] {
                            return false;
                        }
                    }
                    _ => return false,
                },
                atomic => match store.deref(heap) {
                    Cell::Ref(a) => store.bind(a, atomic),
                    h => {
                        let same = match (atomic, h) {
                            (Cell::Atom(x), Cell::Atom(y)) => x == y,
                            (Cell::Int(x), Cell::Int(y)) => x == y,
                            (Cell::Flt(x), Cell::Flt(y)) => x == y || x.to_bits() == y.to_bits(),
                            _ => false,
                        };
                        if !same {
                            return false;
                        }
                    }
                },
            }
            match work.pop() {
                Some((c, h)) => {
                    code = c;
                    heap = h;
                }
                None => return true,
            }
        }
    }
}

impl Cell {
    /// The functor of a `Fun` header cell.
    #[inline]
    pub fn fun(self) -> Option<(Sym, u32)> {
        match self {
            Cell::Fun(s, n) => Some((s, n)),
            _ => None,
        }
    }
}

// `write_ref` stores 16 bytes into one cell: a smaller cell would overwrite its neighbour.
const _: () = assert!(std::mem::size_of::<Cell>() == 16 && std::mem::align_of::<Cell>() >= 8);

/// Writes `Cell::Ref(a)` into `cell` in one 16-byte store. The compiler writes a `Ref` field
/// by field (tag, address, padding); a whole-cell load of it soon after (a clause's slot set to
/// a new variable during the head's copy, then passed on as an argument) cannot be forwarded
/// from those narrower stores and stalls until they reach the cache.
#[inline(always)]
pub(crate) fn write_ref(cell: &mut Cell, a: u32) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__m128i, _mm_set_epi32, _mm_storeu_si128};
        // SAFETY: `Cell` is `repr(u32)`: a `Ref` is the tag 0 in bytes 0..4 and the address in
        // bytes 4..8; bytes 8..16 are padding for it, so any value there is valid. SSE2 is part
        // of x86_64, and the store is unaligned, into memory `cell` borrows mutably.
        unsafe {
            _mm_storeu_si128(
                (cell as *mut Cell).cast::<__m128i>(),
                _mm_set_epi32(0, 0, a as i32, 0),
            )
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        *cell = Cell::Ref(a);
    }
}

#[cfg(test)]
mod tests {
    use super::{Code, UNSET};
    use crate::kr::native::store::{Store, VarNames};
    use crate::syntax::prolog::Reader;
    use crate::term::Sym;

    /// Builds `text` from code twice (shared slots, as for a clause's goals) and from a copy
    /// of the heap term (as `findall/3` keeps answers), printing what lands on the heap.
    fn round_trip(text: &str) -> (String, String, String) {
        let t = Reader::new("test").term(text, 0).expect("term").term;
        let mut code = Code::default();
        let mut syms: Vec<Sym> = Vec::new();
        let root = code.add(&t, &mut syms);
        let mut st = Store::default();
        let mut slots = vec![UNSET; syms.len()];
        let a = code.build(&mut st, root, &mut slots);
        let b = code.build(&mut st, root, &mut slots);
        let mut copy = Code::default();
        let root2 = copy.add_cell(&st, a, &mut Vec::new());
        let c = copy.build(&mut st, root2, &mut vec![UNSET; syms.len()]);
        let mut names = VarNames::new(&[]);
        let show = |c, names: &mut VarNames| st.to_term(c, names).to_string();
        (
            show(a, &mut names),
            show(b, &mut names),
            show(c, &mut names),
        )
    }

    #[test]
    fn a_built_term_is_the_compiled_term_with_its_variables_shared() {
        let (a, b, c) =
            round_trip("f(g(X, \"s\", h(Y, k(Z))), [X, 1 | Y], 123456789012345678901234567890, X)");
        assert_eq!(a, b, "built twice from the same slots: the same variables");
        let vars: Vec<&str> = a
            .split(|ch: char| !ch.is_alphanumeric() && ch != '_')
            .filter(|w| w.starts_with('_'))
            .collect();
        assert_eq!(vars.len(), 6, "{a}");
        assert_eq!((vars[0], vars[1]), (vars[3], vars[4]), "{a}");
        assert_eq!(vars[0], vars[5], "{a}");
        assert!(
            vars[0] != vars[1] && vars[1] != vars[2] && vars[0] != vars[2],
            "{a}"
        );
        let shape = |s: &str| {
            s.split(|ch: char| !ch.is_alphanumeric() && ch != '_')
                .map(|w| if w.starts_with('_') { "V" } else { w })
                .collect::<Vec<_>>()
                .join(" ")
        };
        assert_eq!(
            shape(&a),
            shape("f(g(V,\"s\",h(V,k(V))),[V,1|V],123456789012345678901234567890,V)")
        );
        assert_eq!(
            shape(&c),
            shape(&a),
            "a copy of the heap term builds the same term"
        );
    }

    #[test]
    fn a_ref_written_whole_reads_back_as_that_ref_over_any_cell() {
        use super::write_ref;
        use crate::kr::native::store::Cell;
        let olds = [
            UNSET,
            Cell::Int(-1),
            Cell::Flt(f64::NAN),
            Cell::Fun(Sym::from("f"), 9),
        ];
        for old in olds {
            for a in [0, 1, 0x8000_0000, u32::MAX - 1] {
                let mut cell = old;
                write_ref(&mut cell, a);
                assert!(
                    matches!(cell, Cell::Ref(x) if x == a),
                    "{old:?} <- {a}: {cell:?}"
                );
            }
        }
    }
}
