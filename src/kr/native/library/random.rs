//! `library(random)` predicates beyond `random/1`, `random_between/3`, `random_member/2` and
//! `random_permutation/2`: drawing from the query's seeded generator (the agent's ChaCha RNG,
//! or `goal prolog --seed`), so runs repeat exactly.

use crate::kr::error::KrResult;
use crate::kr::native::builtins::{domain_error, inst, int_arg, type_error, Flow};
use crate::kr::native::machine::Solver;
use crate::kr::native::store::Cell;
use crate::term::well_known as wk;
use rand::Rng;

const NIL: Cell = Cell::Atom(wk::NIL);

/// Largest `K` or `N` of `randseq/3` and `randset/3`.
const MAX_DRAW: i64 = 10_000_000;

fn unify_flow(s: &mut Solver, a: Cell, b: Cell) -> Flow {
    if s.unify(a, b) {
        Flow::True
    } else {
        Flow::Fail
    }
}

/// `random_select(?X, +List, -Rest)`: a random item of `List` and the list without it; with
/// `List` unbound and `Rest` a list, inserts `X` at a random place.
pub(crate) fn random_select(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let (items, end) = s.m.st.list_items(s.a(p, 1));
    if matches!(end, Cell::Atom(n) if n == wk::NIL) {
        if items.is_empty() {
            return Ok(Flow::Fail);
        }
        let i = s.cx.rng.gen_range(0..items.len());
        let mut rest = items.clone();
        let x = rest.remove(i);
        let r = s.m.st.new_list(&rest, NIL);
        let (xa, ra) = (s.a(p, 0), s.a(p, 2));
        return Ok(if s.unify(xa, x) && s.unify(ra, r) {
            Flow::True
        } else {
            Flow::Fail
        });
    }
    let (rest, rend) = s.m.st.list_items(s.a(p, 2));
    if !matches!(rend, Cell::Atom(n) if n == wk::NIL) {
        return Err(inst("random_select", 3));
    }
    let i = s.cx.rng.gen_range(0..=rest.len());
    let mut all = rest;
    all.insert(i, s.a(p, 0));
    let l = s.m.st.new_list(&all, NIL);
    let y = s.a(p, 1);
    Ok(unify_flow(s, y, l))
}

/// The `K` and `N` of `randseq(K, N, L)` / `randset(K, N, L)`, checked (`0 =< K =< N`).
fn draw_counts(s: &Solver, p: u32, name: &str) -> KrResult<(i64, i64)> {
    let k = int_arg(s, p, 0, name, 3)?;
    let n = int_arg(s, p, 1, name, 3)?;
    if k < 0 {
        return Err(domain_error(s, "not_less_than_zero", Cell::Int(k), name, 3));
    }
    if n > MAX_DRAW {
        return Err(domain_error(s, "draw_range", Cell::Int(n), name, 3));
    }
    if k > n {
        return Err(type_error(s, "sample_size", Cell::Int(k), name, 3));
    }
    Ok((k, n))
}

/// `K` distinct integers from `1..=N` in random order.
fn sample(s: &mut Solver, k: i64, n: i64) -> Vec<i64> {
    // A partial Fisher-Yates shuffle over a sparse map, so large N costs only O(K).
    let mut swapped: std::collections::BTreeMap<i64, i64> = Default::default();
    let mut out = Vec::with_capacity(k as usize);
    for i in 0..k {
        let j = s.cx.rng.gen_range(i..n);
        let vj = *swapped.get(&j).unwrap_or(&j);
        let vi = *swapped.get(&i).unwrap_or(&i);
        swapped.insert(j, vi);
        out.push(vj + 1);
    }
    out
}

/// `randseq(+K, +N, -List)`: `K` distinct random integers in `1..N`, in random order.
pub(crate) fn randseq(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let (k, n) = draw_counts(s, p, "randseq")?;
    let items: Vec<Cell> = sample(s, k, n).into_iter().map(Cell::Int).collect();
    let l = s.m.st.new_list(&items, NIL);
    let y = s.a(p, 2);
    Ok(unify_flow(s, y, l))
}

/// `randset(+K, +N, -Set)`: `K` distinct random integers in `1..N`, sorted.
pub(crate) fn randset(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let (k, n) = draw_counts(s, p, "randset")?;
    let mut drawn = sample(s, k, n);
    drawn.sort_unstable();
    let items: Vec<Cell> = drawn.into_iter().map(Cell::Int).collect();
    let l = s.m.st.new_list(&items, NIL);
    let y = s.a(p, 2);
    Ok(unify_flow(s, y, l))
}
