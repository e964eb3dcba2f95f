//! Answering goals from facts: the agent's fact bases (indexed scans on the first two
//! arguments) and the facts of one goal (a scanned slice), unified without copying the facts.

use super::code::Key;
use super::machine::{Alt, Solver};
use super::store::Cell;
use crate::kr::error::KrResult;
use crate::kr::factbase::Scan;
use crate::term::{Sym, Term};

/// Nesting handled by plain recursion in [`Solver::unify_fact_arg`] (bounded, so it is safe).
const SHALLOW_DEPTH: u32 = 4;

impl<'a> Solver<'a, '_> {
    /// Starts scanning fact source `stage` (a fact base, or the goal facts after the last base).
    #[inline]
    pub(crate) fn start_scan(&self, stage: u32, _g: Cell, name: Sym, arity: u32, p: u32) -> Scan {
        if (stage as usize) < self.cx.bases.len() {
            let base = self.cx.bases[stage as usize];
            // Most queries look at several bases that lack the predicate: one hash says so,
            // before the argument keys are read.
            if !base.has_pred(name, arity as usize) {
                return Scan {
                    links: 0,
                    next: u32::MAX,
                };
            }
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
            base.scan(name, arity, k1, k2)
        } else {
            Scan { links: 0, next: 0 }
        }
    }

    /// The next fact that may match `g`, advancing through the sources; with it, the position
    /// (stage and scan) that yields it again at once.
    pub(crate) fn next_fact(
        &self,
        g: Cell,
        stage: &mut u32,
        scan: &mut Scan,
    ) -> Option<(&'a Term, u32, Scan)> {
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
                let at = *scan;
                if let Some(t) = self.cx.bases[*stage as usize].advance(scan) {
                    return Some((t, *stage, at));
                }
                *stage += 1;
                *scan = self.start_scan(*stage, g, name, arity, p);
            } else {
                let facts = self.cx.goal_facts;
                while (scan.next as usize) < facts.len() {
                    let at = *scan;
                    let t = &facts[scan.next as usize];
                    scan.next += 1;
                    if t.functor() == Some((name, arity as usize)) {
                        return Some((t, *stage, at));
                    }
                }
                return None;
            }
        }
    }

    pub(crate) fn try_facts(
        &mut self,
        goal: Cell,
        mut stage: u32,
        mut scan: Scan,
        b: u32,
        mut has_choice: bool,
        next: u32,
    ) -> KrResult<bool> {
        let mut cand = self.next_fact(goal, &mut stage, &mut scan).map(|f| f.0);
        loop {
            let Some(t) = cand else {
                if has_choice {
                    self.m.cps.truncate(b as usize);
                }
                return Ok(false);
            };
            // Looking ahead decides on a choicepoint; the choicepoint resumes at the fact
            // found, so backtracking does not walk the sources passed over again.
            let after = self.next_fact(goal, &mut stage, &mut scan);
            if let Some((_, s_at, sc_at)) = after {
                let alt = Alt::Facts {
                    goal,
                    stage: s_at,
                    scan: sc_at,
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
            let mark = self.m.st.mark();
            let mut ok = self.unify_fact(goal, t);
            if std::mem::take(&mut self.fact_vars) {
                // A fact with variables: matched part by part, each part's variables would be
                // fresh apart (`q(Z, Z)` would not share Z). Matched whole on a copy instead.
                self.m.st.rewind(mark);
                let copy = self.m.st.put_term(t, &mut Vec::new());
                ok = self.m.st.unify(goal, copy);
            }
            if ok {
                self.cont = next;
                return Ok(true);
            }
            self.m.st.rewind(mark);
            cand = after.map(|f| f.0);
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

    pub(crate) fn unify_fact_arg(&mut self, c: Cell, t: &Term) -> bool {
        self.unify_fact_shallow(c, t, SHALLOW_DEPTH)
    }

    /// Unifies without allocating while the term is shallow (atomic arguments, compounds
    /// nested up to `depth` levels, as in `percept(seen(1, 2))`); deeper parts go to the
    /// iterative unifier, so user-controlled nesting cannot overflow the stack.
    fn unify_fact_shallow(&mut self, c: Cell, t: &Term, depth: u32) -> bool {
        match (self.m.st.deref(c), t) {
            (Cell::Atom(x), Term::Atom(y)) => x == *y,
            (Cell::Int(x), Term::Int(y)) => x == *y,
            (Cell::Ref(a), Term::Atom(y)) => {
                self.m.st.bind(a, Cell::Atom(*y));
                true
            }
            (Cell::Ref(a), Term::Int(y)) => {
                self.m.st.bind(a, Cell::Int(*y));
                true
            }
            (Cell::Ptr(p), Term::Compound(k)) if depth > 0 => {
                if self.m.st.heap[p as usize].fun() != Some((k.name, k.args.len() as u32)) {
                    return false;
                }
                for (i, a) in k.args.iter().enumerate() {
                    if !self.unify_fact_shallow(self.a(p, i as u32), a, depth - 1) {
                        return false;
                    }
                }
                true
            }
            _ => self.unify_fact_deep(c, t),
        }
    }

    fn unify_fact_deep(&mut self, c: Cell, t: &Term) -> bool {
        let mut work: Vec<(Cell, &Term)> = vec![(c, t)];
        while let Some((c, t)) = work.pop() {
            let c = self.m.st.deref(c);
            match (c, t) {
                (_, Term::Var(_)) => {
                    // The caller matches the whole fact again (see `Solver::fact_vars`).
                    self.fact_vars = true;
                    return false;
                }
                (Cell::Ref(a), _) => {
                    let v = match t {
                        Term::Atom(s) => Cell::Atom(*s),
                        Term::Int(i) => Cell::Int(*i),
                        Term::Float(f) => Cell::Flt(f.0),
                        _ => {
                            let mut vars = Vec::new();
                            let v = self.m.st.put_term(t, &mut vars);
                            if !vars.is_empty() {
                                self.fact_vars = true;
                                return false;
                            }
                            v
                        }
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
                (Cell::Big(i), Term::BigInt(b)) => {
                    if *self.m.st.strs[i as usize] != *b.to_string() {
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
}
