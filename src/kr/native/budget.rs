//! The budgets of a query besides the inference count: working memory (heap cells, goal
//! stack, choicepoints, collected answers), output size, text size, and interruption by a
//! deadline or cancel flag. The solver checks them every [`CHECK_EVERY`] inferences and after
//! each deterministic built-in; built-ins that allocate or walk in proportion to their input
//! call the entry checks here first ([`reserve`], [`list_walk`], [`text_len`]).

use super::machine::{cyclic, Solver};
use super::store::Cell;
use crate::kr::error::{KrError, KrResult};
use crate::term::sym::MAX_SYMS;
use crate::term::{Sym, Term};

/// How many inferences may pass between two checks of memory, output and interruption.
pub(crate) const CHECK_EVERY: u64 = 1024;

/// Approximate sizes, in heap cells, of a goal frame and a choicepoint (for the memory budget).
const FRAME_CELLS: u64 = 3;
const CHOICE_CELLS: u64 = 5;

/// `name/arity` as text, for budget messages.
pub(crate) fn pi(name: &str, arity: usize) -> String {
    format!("{}/{}", Term::atom(name), arity)
}

impl Solver<'_, '_> {
    /// Working memory of the query in heap cells (terms, trail, frames, choicepoints, bags).
    pub(crate) fn memory_used(&self) -> u64 {
        let m = &self.m;
        let bags: usize = m.bags.iter().map(|b| b.code.size_in_cells()).sum();
        m.st.heap.len() as u64
            + m.st.trail.len() as u64 / 4
            + m.frames.len() as u64 * FRAME_CELLS
            + m.cps.len() as u64 * CHOICE_CELLS
            + bags as u64
    }

    /// The periodic check, run when the inference count reaches `next_check`: the inference
    /// budget, memory, output and interruption. `what` names the predicate being called.
    #[cold]
    pub(crate) fn checkpoint(&mut self, what: &dyn Fn() -> String) -> KrResult<()> {
        let l = self.cx.limits;
        if self.inferences > l.max_inferences {
            return Err(KrError::Budget {
                predicate: what(),
                limit: l.max_inferences,
            });
        }
        self.check_memory(what)?;
        if l.cancel.is_set() || l.deadline.is_some_and(|d| std::time::Instant::now() >= d) {
            return Err(KrError::Interrupted { predicate: what() });
        }
        self.next_check = (self.inferences + CHECK_EVERY).min(l.max_inferences + 1);
        Ok(())
    }

    /// The memory and output budgets (checked after every deterministic built-in too).
    pub(crate) fn check_memory(&self, what: &dyn Fn() -> String) -> KrResult<()> {
        let l = self.cx.limits;
        if self.memory_used() > l.max_heap_cells {
            return Err(resource("memory", what(), l.max_heap_cells));
        }
        if self.cx.out.len() as u64 > l.max_output {
            return Err(resource("output", what(), l.max_output));
        }
        Ok(())
    }

    /// The answer budgets, after answer number `n`: how many answers, and their total size.
    pub(crate) fn check_answers(&self, n: u64) -> KrResult<()> {
        let l = self.cx.limits;
        if n > l.max_answers {
            return Err(resource("answers", "the query".into(), l.max_answers));
        }
        if self.m.st.converted.get() > l.max_heap_cells {
            return Err(resource("memory", "the answers".into(), l.max_heap_cells));
        }
        Ok(())
    }

    /// Counts `steps` units of built-in work against the inference budget.
    pub(crate) fn charge(&mut self, steps: u64, name: &str, arity: usize) -> KrResult<()> {
        self.inferences += steps;
        if self.inferences >= self.next_check {
            self.checkpoint(&|| pi(name, arity))?;
        }
        Ok(())
    }
}

/// A `resource_error` for the budget `resource`.
pub(crate) fn resource(resource: &'static str, predicate: String, limit: u64) -> KrError {
    KrError::Resource {
        resource,
        predicate,
        limit,
    }
}

/// Entry check of a built-in about to build `cells` new heap cells: a resource error when
/// that would exceed the memory budget (so nothing huge is allocated first).
pub(crate) fn reserve(s: &Solver, cells: u64, name: &str, arity: usize) -> KrResult<()> {
    let max = s.cx.limits.max_heap_cells;
    if s.memory_used().saturating_add(cells) > max {
        return Err(resource("memory", pi(name, arity), max));
    }
    Ok(())
}

/// Entry check of a built-in about to build a text of `bytes` bytes.
pub(crate) fn text_len(s: &Solver, bytes: u64, name: &str, arity: usize) -> KrResult<()> {
    let max = s.cx.limits.max_text;
    if bytes > max {
        return Err(resource("text", pi(name, arity), max));
    }
    Ok(())
}

/// The atom named `text`, made at run time by the built-in `name/arity`. Atoms are never
/// freed, so each distinct atom the engine's queries make counts once against its atom
/// budget (making it again costs nothing), and the process-wide table is bounded too.
pub(crate) fn new_atom(s: &mut Solver, text: &str, name: &str, arity: usize) -> KrResult<Cell> {
    let known = Sym::lookup(text);
    if let Some(sym) = known.filter(|sym| s.cx.made_atoms.contains(sym)) {
        return Ok(Cell::Atom(sym));
    }
    let max = s.cx.limits.max_new_atoms;
    if s.cx.made_atoms.len() as u64 >= max {
        return Err(resource("atoms", pi(name, arity), max));
    }
    let sym = match known {
        Some(sym) => sym,
        None => match Sym::try_intern_new(text) {
            Some((sym, _)) => sym,
            None => return Err(resource("atoms", pi(name, arity), MAX_SYMS as u64)),
        },
    };
    s.cx.made_atoms.insert(sym);
    Ok(Cell::Atom(sym))
}

/// Entry check of a built-in that walks the list `c`: counts the walk against the inference
/// budget and gives `representation_error(cyclic_term)` for a cyclic list (which would never
/// end). Returns the number of list cells.
pub(crate) fn list_walk(s: &mut Solver, c: Cell, name: &str, arity: usize) -> KrResult<u64> {
    // An acyclic list has fewer cells than the heap (three heap cells each).
    let bound = s.m.st.heap.len() as u64 / 3 + 1;
    let mut n = 0u64;
    let mut cur = c;
    while let Some((_, t)) = s.m.st.cons(cur) {
        n += 1;
        if n > bound {
            return Err(cyclic_in(name, arity));
        }
        cur = t;
    }
    s.charge(n / 8, name, arity)?;
    Ok(n)
}

/// `error(representation_error(cyclic_term), Name/Arity)`.
pub(crate) fn cyclic_in(name: &str, arity: usize) -> KrError {
    match cyclic() {
        KrError::Iso(t) => {
            let formal = t.args()[0].clone();
            KrError::iso(formal, Some((Sym::intern(name), arity)))
        }
        e => e,
    }
}
