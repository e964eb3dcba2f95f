//! Calling a goal: built-ins through their table, user predicates by their clauses (first
//! argument indexing, head matching, the first body goal called at once without a frame).

use super::code::{Code, Key, UNSET};
use super::machine::{Alt, Frame, Goal, Machine, Solver, NONE};
use super::store::{Cell, VarNames};
use crate::kr::error::{KrError, KrResult};
use crate::kr::knowledge::{Pred, PredRef};
use crate::term::{Sym, Term};

/// A clause's first body goal, called right after the clause's head matched, with its
/// arguments in the argument registers (or built on the heap) without a goal term around
/// them and without a frame. Packed in two words, written and read whole: a struct written
/// field by field and read back in wider loads stalls store-to-load forwarding.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Direct {
    /// The predicate (low half, see [`Direct::new`]) and where the arguments lie (high half,
    /// [`REGS`] for the argument registers); `u64::MAX` when no call is pending.
    call: u64,
    /// The continuation (low half) and the depth (high half).
    cont: u64,
}

/// The `Args` word of a [`Direct`] call whose arguments are in the registers.
const REGS: u32 = u32::MAX;
/// The predicate word's flag for a library predicate.
const LIB: u32 = 1 << 31;

impl Direct {
    /// No call pending.
    pub(crate) const NONE: Direct = Direct {
        call: u64::MAX,
        cont: 0,
    };

    /// Packs a call. Predicate indices are below 2^31 - 1 (a predicate table that size
    /// would take hundreds of gigabytes), so no call packs to [`Direct::NONE`].
    fn new(pred: PredRef, args: Args, next: u32, depth: u32) -> Direct {
        let p = match pred {
            PredRef::User(i) => i,
            PredRef::Lib(i) => i | LIB,
            PredRef::Builtin(_) => unreachable!("built-ins are not called directly"),
        };
        let a = match args {
            Args::Heap(a) => a,
            Args::Regs => REGS,
        };
        Direct {
            call: u64::from(p) | u64::from(a) << 32,
            cont: u64::from(next) | u64::from(depth) << 32,
        }
    }

    /// True when a call is pending.
    #[inline]
    pub(crate) fn pending(self) -> bool {
        self.call != u64::MAX
    }

    fn pred(self) -> PredRef {
        let p = self.call as u32;
        if p & LIB != 0 {
            PredRef::Lib(p & !LIB)
        } else {
            PredRef::User(p)
        }
    }

    fn args(self) -> Args {
        match (self.call >> 32) as u32 {
            REGS => Args::Regs,
            a => Args::Heap(a),
        }
    }
}

/// Most arguments a call passes in the argument registers.
pub(crate) const MAX_REGS: usize = 8;

/// Where the arguments of a call lie.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Args {
    /// On the heap from this address on (a goal term's arguments, or a built block).
    Heap(u32),
    /// In the machine's argument registers: a first body goal whose arguments are variables
    /// and constants, read from the clause's slots without copying a block to the heap.
    Regs,
}

/// The argument registers (see [`Args::Regs`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Regs(pub [Cell; MAX_REGS]);

impl Default for Regs {
    fn default() -> Self {
        Regs([UNSET; MAX_REGS])
    }
}

impl<'a, 'm> Solver<'a, 'm> {
    /// Calls goal `g`.
    pub(crate) fn call(
        &mut self,
        g: Cell,
        next: u32,
        cut: u32,
        depth: u32,
        pred: Option<PredRef>,
    ) -> KrResult<bool> {
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
        if self.inferences >= self.next_check {
            self.checkpoint(&|| format!("{}/{}", Term::Atom(name), arity))?;
        }
        let pred = match pred {
            Some(r) => Some(r),
            None => self.cx.kn.table.get(&(name, arity)).copied(),
        };
        match pred {
            Some(PredRef::Builtin(b)) => self.builtin(b, g, p, next, cut, depth),
            Some(r) => self.call_clauses(r, Some(g), Args::Heap(Self::args_of(g)), next, depth),
            None => {
                let b = self.m.cps.len() as u32;
                let scan = self.start_scan(0, g, name, arity, p);
                self.try_facts(g, 0, scan, b, false, next)
            }
        }
    }

    /// The heap address of the first argument of goal `g` (a structure or an atom).
    #[inline]
    pub(crate) fn args_of(g: Cell) -> u32 {
        match g {
            Cell::Ptr(p) => p + 1,
            _ => 0,
        }
    }

    /// The goal `name(args...)` of `arity` arguments, built as a term (for a choicepoint or a
    /// fact scan, which keep the goal).
    fn goal_at(&mut self, name: Sym, arity: u32, args: Args) -> Cell {
        if arity == 0 {
            return Cell::Atom(name);
        }
        let m = &mut *self.m;
        let p = m.st.heap.len() as u32;
        m.st.heap.push(Cell::Fun(name, arity));
        match args {
            Args::Heap(a) => {
                m.st.heap
                    .extend_from_within(a as usize..(a + arity) as usize)
            }
            Args::Regs => m.st.heap.extend_from_slice(&m.regs.0[..arity as usize]),
        }
        Cell::Ptr(p)
    }

    /// Argument `i` of a call whose arguments lie at `args`.
    #[inline]
    fn arg(m: &super::machine::Machine, args: Args, i: usize) -> Cell {
        match args {
            Args::Heap(a) => m.st.heap[a as usize + i],
            Args::Regs => m.regs.0[i],
        }
    }

    /// Calls the clauses of a clause's first body goal (see [`Direct`]).
    pub(crate) fn call_direct(&mut self, d: Direct) -> KrResult<bool> {
        let pred = d.pred();
        self.inferences += 1;
        if self.inferences >= self.next_check {
            let p = self.pred(pred);
            let (name, arity) = (p.name, p.arity);
            self.checkpoint(&|| format!("{}/{}", Term::Atom(name), arity))?;
        }
        let (next, depth) = (d.cont as u32, (d.cont >> 32) as u32);
        self.call_clauses(pred, None, d.args(), next, depth)
    }

    /// Calls the clauses (and goal facts) of predicate `r` on the arguments at `args`; `goal`
    /// is the goal term when there is one already.
    fn call_clauses(
        &mut self,
        r: PredRef,
        mut goal: Option<Cell>,
        mut args: Args,
        next: u32,
        depth: u32,
    ) -> KrResult<bool> {
        let pred = self.pred(r);
        let (name, arity) = (pred.name, pred.arity);
        let key = if arity > 0 {
            Key::of_cell(&self.m.st, Self::arg(self.m, args, 0))
        } else {
            None
        };
        if depth > self.cx.limits.max_depth {
            return Err(KrError::Depth {
                predicate: format!("{}/{}", Term::Atom(name), arity),
                limit: self.cx.limits.max_depth,
            });
        }
        // A goal's facts join the knowledge clauses of their predicate (GOAL's goal
        // module holds both): `goals { done. }` with `done :- ...` in knowledge. The
        // facts are tried after the clauses, as facts asserted after them would be.
        let arity_usize = arity as usize;
        if self
            .cx
            .goal_facts
            .iter()
            .any(|f| f.functor() == Some((name, arity_usize)))
        {
            let g = match goal {
                Some(g) => g,
                None => self.goal_at(name, arity, args),
            };
            goal = Some(g);
            let p = match g {
                Cell::Ptr(p) => p,
                _ => 0,
            };
            args = Args::Heap(p + 1);
            let stage = self.cx.bases.len() as u32;
            let scan = self.start_scan(stage, g, name, arity, p);
            self.push_choice(
                Alt::Facts {
                    goal: g,
                    stage,
                    scan,
                },
                next,
                0,
                depth,
            );
        }
        let b = self.m.cps.len() as u32;
        let list = self.candidates(pred, key, args);
        let i = Self::skip(pred, list, 0, key);
        if i < list.len() && Self::skip(pred, list, i + 1, key) == list.len() {
            // One candidate: what `try_clauses` does for it (no choicepoint, and a failed head
            // leaves its bindings to the backtracking that follows), without its loop.
            return Ok(self.try_clause(pred, list[i], args, next, b));
        }
        self.try_clauses(goal, args, r, key, i as u32, b, false, next, depth)
    }

    /// The candidate clauses of `pred` for a call with first-argument key `key` on the
    /// arguments at `args`. The second-argument key is read from the goal on every entry:
    /// backtracking restores the bindings of the call, so the list is the same each time.
    #[inline(always)]
    fn candidates(&self, pred: &'a Pred, key: Option<Key>, args: Args) -> &'a [u32] {
        let key2 = if key.is_none() && pred.arity >= 2 && pred.has_second_index() {
            Key::of_cell(&self.m.st, Self::arg(self.m, args, 1))
        } else {
            None
        };
        pred.candidates(key, key2)
    }

    /// The first clause index at or after `i` whose first-argument key can match `key`.
    #[inline]
    pub(crate) fn skip(pred: &Pred, list: &[u32], mut i: usize, key: Option<Key>) -> usize {
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
    pub(crate) fn try_clauses(
        &mut self,
        mut goal: Option<Cell>,
        mut args: Args,
        r: PredRef,
        key: Option<Key>,
        pos: u32,
        b: u32,
        mut has_choice: bool,
        next: u32,
        depth: u32,
    ) -> KrResult<bool> {
        let pred = self.pred(r);
        let list = self.candidates(pred, key, args);
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
                let goal = match goal {
                    Some(g) => g,
                    None => {
                        let g = self.goal_at(pred.name, pred.arity, args);
                        args = Args::Heap(Self::args_of(g));
                        *goal.insert(g)
                    }
                };
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
            // After the last candidate, a failed head leaves its bindings to the backtracking
            // that follows (it restores an older choicepoint): no mark to rewind to.
            let saved = has_choice.then(|| (self.m.st.mark(), self.m.frames.len()));
            let ok = self.try_clause(pred, list[i], args, next, b);
            let Some((mark, fm)) = saved.filter(|_| !ok) else {
                return Ok(ok);
            };
            self.m.st.rewind(mark);
            self.m.frames.truncate(fm);
            i = j;
        }
    }

    /// Matches clause `ci`'s head against the arguments at `args` and schedules
    /// its body: the first goal as the next [`Direct`] call when it calls clauses, the others
    /// as frames.
    #[inline(always)]
    pub(crate) fn try_clause(
        &mut self,
        pred: &'a Pred,
        ci: u32,
        args: Args,
        next: u32,
        cut: u32,
    ) -> bool {
        let cl = &pred.clauses[ci as usize];
        let m = &mut *self.m;
        m.slots.clear();
        m.slots.resize(cl.nslots as usize, UNSET);
        if let Cell::Ptr(off) = cl.head {
            if !match_head(m, &cl.code, off, pred.arity, args) {
                return false;
            }
        }
        let direct = match cl.preds.first() {
            Some(Some(r @ (PredRef::User(_) | PredRef::Lib(_)))) => Some(*r),
            _ => None,
        };
        let mut nx = next;
        // Depth is the continuation length: the last body goal is one deeper than `next`.
        let mut d = if next == NONE {
            0
        } else {
            m.frames[next as usize].depth
        };
        let framed = usize::from(direct.is_some());
        if cl.body.len() > framed {
            m.frames.reserve(cl.body.len());
        }
        for (g, pred) in cl.body.iter().zip(&cl.preds).skip(framed).rev() {
            let c = cl.code.build(&mut m.st, *g, &mut m.slots);
            d += 1;
            m.frames.push(Frame {
                goal: Goal::Call(c),
                next: nx,
                cut,
                depth: d,
                pred: *pred,
            });
            nx = m.frames.len() as u32 - 1;
        }
        if let Some(pred) = direct {
            let args = place_args(m, &cl.code, cl.body[0], cl.flat_first);
            self.direct = Direct::new(pred, args, nx, d + 1);
        }
        self.cont = nx;
        true
    }
}

/// Unifies the arguments of the compiled head at `off` (a structure of `arity` arguments)
/// with the call's arguments at `args`, binding the clause's slots. One loop per place the
/// arguments lie in, over the machine's parts borrowed apart: no per-argument test of where
/// they lie, and the registers are read without a bounds check (they are not written here).
#[inline(always)]
fn match_head(m: &mut Machine, code: &Code, off: u32, arity: u32, args: Args) -> bool {
    let (off, n) = (off as usize + 1, arity as usize);
    let head = &code.cells[off..off + n];
    let Machine {
        st, slots, regs, ..
    } = m;
    match args {
        Args::Regs => {
            debug_assert!(
                n <= MAX_REGS,
                "register calls have at most MAX_REGS arguments"
            );
            for (&c, &h) in head.iter().zip(&regs.0) {
                if !code.unify_arg(st, c, h, slots) {
                    return false;
                }
            }
        }
        Args::Heap(a) => {
            for (&c, i) in head.iter().zip(a as usize..) {
                let h = st.heap[i];
                if !code.unify_arg(st, c, h, slots) {
                    return false;
                }
            }
        }
    }
    true
}

/// Places the arguments of the compiled goal `goal` for a call: in the argument registers
/// when `flat` gives their cells (none is a structure and they fit; fresh variables are made
/// in the order a block copy would make them), else built as a block on the heap.
#[inline(always)]
fn place_args(m: &mut Machine, code: &Code, goal: Cell, flat: Option<(u32, u32)>) -> Args {
    let Some((from, end)) = flat else {
        return Args::Heap(code.build_args(&mut m.st, goal, &mut m.slots));
    };
    let cells = &code.cells[from as usize..end as usize];
    debug_assert!(
        cells.len() <= MAX_REGS,
        "checked when the clause was loaded"
    );
    let Machine {
        st, slots, regs, ..
    } = m;
    for (r, &c) in regs.0.iter_mut().zip(cells) {
        *r = match c {
            Cell::Ref(k) if (k as usize) < slots.len() => {
                // By value: a copy made field by field and read back whole stalls the
                // store-to-load forwarding.
                let v = slots[k as usize];
                if let Cell::Ref(u32::MAX) = v {
                    let v = st.new_var();
                    slots[k as usize] = v;
                    v
                } else {
                    v
                }
            }
            Cell::Atom(_) | Cell::Int(_) | Cell::Flt(_) => c,
            _ => code.build(st, c, slots),
        };
    }
    Args::Regs
}

#[cfg(test)]
mod tests {
    use super::{Args, Direct};
    use crate::kr::knowledge::PredRef;

    #[test]
    fn a_packed_direct_call_reads_back_what_was_packed() {
        let cases = [
            (PredRef::User(0), Args::Regs, super::NONE, 0),
            (PredRef::User(7), Args::Heap(0), 3, 1),
            (PredRef::Lib(5), Args::Heap(u32::MAX - 1), 0, u32::MAX),
            (PredRef::Lib((1 << 31) - 2), Args::Regs, u32::MAX - 1, 42),
        ];
        for (pred, args, next, depth) in cases {
            let d = Direct::new(pred, args, next, depth);
            assert!(d.pending());
            assert_eq!(d.pred(), pred);
            let same_args = match (d.args(), args) {
                (Args::Regs, Args::Regs) => true,
                (Args::Heap(a), Args::Heap(b)) => a == b,
                _ => false,
            };
            assert!(same_args, "{args:?} read back as {:?}", d.args());
            assert_eq!((d.cont as u32, (d.cont >> 32) as u32), (next, depth));
        }
        assert!(!Direct::NONE.pending());
    }
}
