//! List built-ins implemented natively (the hot and the deterministic ones); the rest are in
//! the prelude.

use super::arith::compare_cells;
use super::budget;
use super::builtins::{goal, inst, int_arg, type_error, Flow, B};
use super::machine::Solver;
use super::store::Cell;
use crate::kr::error::KrResult;
use crate::term::{well_known as wk, Sym};
use std::cmp::Ordering;

const NIL: Cell = Cell::Atom(wk::NIL);

/// The items of a proper list argument (instantiation error for a partial list, type error
/// otherwise).
fn proper(s: &Solver, c: Cell, name: &str, arity: usize) -> KrResult<Vec<Cell>> {
    let (items, end) = s.m.st.list_items(c);
    if s.m.st.cyclic.get() {
        return Err(budget::cyclic_in(name, arity));
    }
    match end {
        Cell::Atom(n) if n == wk::NIL => Ok(items),
        Cell::Ref(_) => Err(inst(name, arity)),
        _ => Err(type_error(s, "list", c, name, arity)),
    }
}

fn unify_list(s: &mut Solver, items: &[Cell], target: Cell) -> Flow {
    let l = s.m.st.new_list(items, NIL);
    if s.unify(l, target) {
        Flow::True
    } else {
        Flow::Fail
    }
}

fn sort_cells(s: &Solver, items: &mut [Cell]) {
    items.sort_by(|a, b| s.m.st.compare(*a, *b));
}

fn dedup(s: &Solver, items: &mut Vec<Cell>) {
    items.dedup_by(|a, b| s.m.st.compare(*a, *b) == Ordering::Equal);
}

fn ord_merge(s: &Solver, a: &[Cell], b: &[Cell], keep: (bool, bool, bool)) -> Vec<Cell> {
    // keep = (only in a, in both, only in b)
    let (mut i, mut j) = (0, 0);
    let mut out = Vec::new();
    while i < a.len() || j < b.len() {
        let o = if i == a.len() {
            Ordering::Greater
        } else if j == b.len() {
            Ordering::Less
        } else {
            s.m.st.compare(a[i], b[j])
        };
        match o {
            Ordering::Less => {
                if keep.0 {
                    out.push(a[i]);
                }
                i += 1;
            }
            Ordering::Equal => {
                if keep.1 {
                    out.push(a[i]);
                }
                i += 1;
                j += 1;
            }
            Ordering::Greater => {
                if keep.2 {
                    out.push(b[j]);
                }
                j += 1;
            }
        }
    }
    out
}

/// `nth0/3` and `nth1/3` past the end of a partial list ending in `end`: the list is extended
/// with `k` fresh items, then `elem`, then a fresh tail (as SWI's library does).
fn nth_extend(s: &mut Solver, end: Cell, k: i64, elem: Cell) -> Flow {
    let end = s.m.st.deref(end);
    if !matches!(end, Cell::Ref(_)) || k > 100_000_000 {
        return Flow::Fail;
    }
    let mut items: Vec<Cell> = (0..k).map(|_| s.m.st.new_var()).collect();
    items.push(elem);
    let tail = s.m.st.new_var();
    let l = s.m.st.new_list(&items, tail);
    if s.unify(end, l) {
        Flow::True
    } else {
        Flow::Fail
    }
}

/// List built-ins; `None` when `b` is not one of them.
pub(crate) fn det(s: &mut Solver, b: B, p: u32) -> KrResult<Option<Flow>> {
    Ok(Some(match b {
        B::Length => {
            let (items, end) = s.m.st.list_items(s.a(p, 0));
            let n = s.ad(p, 1);
            match end {
                Cell::Atom(x) if x == wk::NIL => {
                    if !matches!(n, Cell::Ref(_) | Cell::Int(_)) {
                        return Err(type_error(s, "integer", n, "length", 2));
                    }
                    let y = s.a(p, 1);
                    if s.unify(y, Cell::Int(items.len() as i64)) {
                        Flow::True
                    } else {
                        Flow::Fail
                    }
                }
                Cell::Ref(_) => match n {
                    Cell::Int(k) if k < 0 => {
                        return Err(super::builtins::domain_error(
                            s,
                            "not_less_than_zero",
                            n,
                            "length",
                            2,
                        ))
                    }
                    Cell::Int(k) => {
                        if k < items.len() as i64 {
                            return Ok(Some(Flow::Fail));
                        }
                        if k > 100_000_000 {
                            return Err(super::builtins::domain_error(
                                s,
                                "list_length",
                                n,
                                "length",
                                2,
                            ));
                        }
                        budget::reserve(s, 4 * (k - items.len() as i64) as u64, "length", 2)?;
                        let vars: Vec<Cell> =
                            (items.len() as i64..k).map(|_| s.m.st.new_var()).collect();
                        let rest = s.m.st.new_list(&vars, NIL);
                        if s.unify(end, rest) {
                            Flow::True
                        } else {
                            Flow::Fail
                        }
                    }
                    Cell::Ref(_) => {
                        let y = s.a(p, 1);
                        Flow::Call(goal(
                            s,
                            "$length_enum",
                            &[end, Cell::Int(items.len() as i64), y],
                        ))
                    }
                    other => return Err(type_error(s, "integer", other, "length", 2)),
                },
                _ => return Err(type_error(s, "list", s.a(p, 0), "length", 2)),
            }
        }
        B::Memberchk => {
            budget::list_walk(s, s.a(p, 1), "memberchk", 2)?;
            let x = s.a(p, 0);
            let mut l = s.a(p, 1);
            loop {
                match s.m.st.cons(l) {
                    Some((h, t)) => {
                        let mark = s.m.st.trail.len();
                        if s.unify(x, h) {
                            return Ok(Some(Flow::True));
                        }
                        s.m.st.undo(mark);
                        l = t;
                    }
                    None => {
                        // A partial list: memberchk adds the element, like the library.
                        let end = s.m.st.deref(l);
                        if let Cell::Ref(_) = end {
                            let v = s.m.st.new_var();
                            let cell = s.m.st.new_struct(wk::DOT, &[x, v]);
                            return Ok(Some(if s.unify(end, cell) {
                                Flow::True
                            } else {
                                Flow::Fail
                            }));
                        }
                        return Ok(Some(Flow::Fail));
                    }
                }
            }
        }
        B::Reverse => {
            let (mut items, end) = s.m.st.list_items(s.a(p, 0));
            if let Cell::Ref(_) = end {
                // A partial list: SWI's definition, bounded by the length of the second list
                // (with neither list proper, SWI's answers never end: an error here).
                proper(s, s.a(p, 1), "reverse", 2)?;
                let (x, y) = (s.a(p, 0), s.a(p, 1));
                return Ok(Some(Flow::Call(goal(s, "$reverse", &[x, NIL, y, y]))));
            }
            if !matches!(end, Cell::Atom(n) if n == wk::NIL) {
                return Err(type_error(s, "list", s.a(p, 0), "reverse", 2));
            }
            items.reverse();
            let y = s.a(p, 1);
            unify_list(s, &items, y)
        }
        B::Delete => {
            // SWI: drop every item that unifies with the element (without binding either).
            let items = proper(s, s.a(p, 0), "delete", 3)?;
            let x = s.a(p, 1);
            let mut keep = Vec::with_capacity(items.len());
            for it in items {
                let mark = s.m.st.trail.len();
                let unifies = s.unify(it, x);
                s.m.st.undo(mark);
                if !unifies {
                    keep.push(it);
                }
            }
            let y = s.a(p, 2);
            unify_list(s, &keep, y)
        }
        B::Msort | B::Sort | B::ListToOrdSet => {
            let mut items = proper(s, s.a(p, 0), "sort", 2)?;
            sort_cells(s, &mut items);
            if b != B::Msort {
                dedup(s, &mut items);
            }
            let y = s.a(p, 1);
            unify_list(s, &items, y)
        }
        B::Sort4 => {
            let key = int_arg(s, p, 0, "sort", 4)?;
            if key < 0 {
                return Err(super::builtins::domain_error(
                    s,
                    "not_less_than_zero",
                    Cell::Int(key),
                    "sort",
                    4,
                ));
            }
            let order = match s.ad(p, 1) {
                Cell::Atom(o) => o.name(),
                Cell::Ref(_) => return Err(inst("sort", 4)),
                other => return Err(type_error(s, "atom", other, "sort", 4)),
            };
            let items = proper(s, s.a(p, 2), "sort", 4)?;
            let mut keyed = Vec::with_capacity(items.len());
            for it in items {
                let k = if key == 0 {
                    it
                } else {
                    match s.m.st.deref(it) {
                        Cell::Ptr(q)
                            if s.m.st.heap[q as usize]
                                .fun()
                                .is_some_and(|f| f.1 as i64 >= key) =>
                        {
                            s.a(q, key as u32 - 1)
                        }
                        other => return Err(type_error(s, "compound", other, "sort", 4)),
                    }
                };
                keyed.push((k, it));
            }
            let desc = matches!(order, "@>" | "@>=");
            keyed.sort_by(|a, b| {
                let o = s.m.st.compare(a.0, b.0);
                if desc {
                    o.reverse()
                } else {
                    o
                }
            });
            if matches!(order, "@<" | "@>") {
                keyed.dedup_by(|a, b| s.m.st.compare(a.0, b.0) == Ordering::Equal);
            } else if !matches!(order, "@=<" | "@>=") {
                return Err(super::builtins::domain_error(
                    s,
                    "order",
                    Cell::Atom(Sym::intern(order)),
                    "sort",
                    4,
                ));
            }
            let items: Vec<Cell> = keyed.into_iter().map(|(_, v)| v).collect();
            let y = s.a(p, 3);
            unify_list(s, &items, y)
        }
        B::Keysort => {
            let items = proper(s, s.a(p, 0), "keysort", 2)?;
            let mut keyed = Vec::with_capacity(items.len());
            for it in items {
                match s.m.st.deref(it) {
                    Cell::Ptr(q) if s.m.st.heap[q as usize].fun() == Some((wk::MINUS, 2)) => {
                        keyed.push((s.a(q, 0), it))
                    }
                    Cell::Ref(_) => return Err(inst("keysort", 2)),
                    other => {
                        return Err(type_error(s, "pair", other, "keysort", 2));
                    }
                }
            }
            keyed.sort_by(|a, b| s.m.st.compare(a.0, b.0));
            let items: Vec<Cell> = keyed.into_iter().map(|(_, v)| v).collect();
            let y = s.a(p, 1);
            unify_list(s, &items, y)
        }
        B::Nth0 | B::Nth1 => {
            let base = if b == B::Nth0 { 0 } else { 1 };
            match s.ad(p, 0) {
                Cell::Int(i) => {
                    budget::list_walk(s, s.a(p, 1), "nth0", 3)?;
                    let mut l = s.a(p, 1);
                    let mut k = i - base;
                    if k < 0 {
                        return Ok(Some(Flow::Fail));
                    }
                    loop {
                        match s.m.st.cons(l) {
                            Some((h, t)) => {
                                if k == 0 {
                                    let y = s.a(p, 2);
                                    return Ok(Some(if s.unify(h, y) {
                                        Flow::True
                                    } else {
                                        Flow::Fail
                                    }));
                                }
                                k -= 1;
                                l = t;
                            }
                            None => return Ok(Some(nth_extend(s, l, k, s.a(p, 2)))),
                        }
                    }
                }
                Cell::Ref(_) => {
                    let args = [s.a(p, 1), Cell::Int(base), s.a(p, 0), s.a(p, 2)];
                    Flow::Call(goal(s, "$nth_enum", &args))
                }
                other => return Err(type_error(s, "integer", other, "nth0", 3)),
            }
        }
        B::SumList | B::SumList2 => {
            let items = proper(s, s.a(p, 0), "sum_list", 2)?;
            let l = s.m.st.new_list(&items, NIL);
            let y = s.a(p, 1);
            Flow::Call(goal(s, "$sum_eval", &[l, y]))
        }
        B::MaxList | B::MinList => {
            let name = if b == B::MaxList {
                "max_list"
            } else {
                "min_list"
            };
            let items = proper(s, s.a(p, 0), name, 2)?;
            let Some(&first) = items.first() else {
                return Ok(Some(Flow::Fail));
            };
            let mut best = first;
            for &it in &items[1..] {
                let o = compare_cells(s, it, best, name)?;
                if (b == B::MaxList && o == Ordering::Greater)
                    || (b == B::MinList && o == Ordering::Less)
                {
                    best = it;
                }
            }
            // Evaluate to check the elements are numbers.
            let y = s.a(p, 1);
            if s.unify(y, best) {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        B::MaxMember | B::MinMember => {
            let items = proper(s, s.a(p, 1), "max_member", 2)?;
            let Some(&first) = items.first() else {
                return Ok(Some(Flow::Fail));
            };
            let mut best = first;
            for &it in &items[1..] {
                let o = s.m.st.compare(it, best);
                if (b == B::MaxMember && o == Ordering::Greater)
                    || (b == B::MinMember && o == Ordering::Less)
                {
                    best = it;
                }
            }
            let x = s.a(p, 0);
            if s.unify(x, best) {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        B::Numlist => {
            let lo = int_arg(s, p, 0, "numlist", 3)?;
            let hi = int_arg(s, p, 1, "numlist", 3)?;
            if lo > hi {
                return Ok(Some(Flow::Fail));
            }
            if hi - lo > 100_000_000 {
                return Err(super::builtins::domain_error(
                    s,
                    "list_length",
                    Cell::Int(hi - lo),
                    "numlist",
                    3,
                ));
            }
            budget::reserve(s, 3 * (hi - lo + 1) as u64, "numlist", 3)?;
            let items: Vec<Cell> = (lo..=hi).map(Cell::Int).collect();
            let y = s.a(p, 2);
            unify_list(s, &items, y)
        }
        B::ListToSet => {
            let items = proper(s, s.a(p, 0), "list_to_set", 2)?;
            let mut idx: Vec<usize> = (0..items.len()).collect();
            idx.sort_by(|a, b| s.m.st.compare(items[*a], items[*b]).then(a.cmp(b)));
            let mut keep = vec![true; items.len()];
            for w in idx.windows(2) {
                if s.m.st.compare(items[w[0]], items[w[1]]) == Ordering::Equal {
                    keep[w[1]] = false;
                }
            }
            let out: Vec<Cell> = items
                .iter()
                .zip(keep)
                .filter(|(_, k)| *k)
                .map(|(c, _)| *c)
                .collect();
            let y = s.a(p, 1);
            unify_list(s, &out, y)
        }
        B::Flatten => {
            let mut out = Vec::new();
            let mut stack = vec![s.a(p, 0)];
            while let Some(c) = stack.pop() {
                let c = s.m.st.deref(c);
                match c {
                    Cell::Atom(n) if n == wk::NIL => {}
                    _ => match s.m.st.cons(c) {
                        Some((h, t)) => {
                            stack.push(t);
                            stack.push(h);
                        }
                        None => out.push(c),
                    },
                }
            }
            let y = s.a(p, 1);
            unify_list(s, &out, y)
        }
        B::PairsKeysValues | B::PairsKeys | B::PairsValues => {
            let (pi, ki, vi) = match b {
                B::PairsKeysValues => (0, Some(1), Some(2)),
                B::PairsKeys => (0, Some(1), None),
                _ => (0, None, Some(1)),
            };
            let (pairs, end) = s.m.st.list_items(s.a(p, pi));
            if matches!(end, Cell::Atom(n) if n == wk::NIL) {
                let mut ks = Vec::new();
                let mut vs = Vec::new();
                for it in pairs {
                    let k = s.m.st.new_var();
                    let v = s.m.st.new_var();
                    let pair = s.m.st.new_struct(wk::MINUS, &[k, v]);
                    if !s.unify(it, pair) {
                        return Ok(Some(Flow::Fail));
                    }
                    ks.push(k);
                    vs.push(v);
                }
                if let Some(i) = ki {
                    let y = s.a(p, i);
                    if let Flow::Fail = unify_list(s, &ks, y) {
                        return Ok(Some(Flow::Fail));
                    }
                }
                if let Some(i) = vi {
                    let y = s.a(p, i);
                    return Ok(Some(unify_list(s, &vs, y)));
                }
                Flow::True
            } else if b == B::PairsKeysValues {
                let ks = proper(s, s.a(p, 1), "pairs_keys_values", 3)?;
                let (vs, _) = s.m.st.list_items(s.a(p, 2));
                let vs: Vec<Cell> = if vs.len() == ks.len() {
                    vs
                } else {
                    ks.iter().map(|_| s.m.st.new_var()).collect()
                };
                let pairs: Vec<Cell> = ks
                    .iter()
                    .zip(&vs)
                    .map(|(k, v)| s.m.st.new_struct(wk::MINUS, &[*k, *v]))
                    .collect();
                let vl = s.m.st.new_list(&vs, NIL);
                let y = s.a(p, 2);
                if !s.unify(vl, y) {
                    return Ok(Some(Flow::Fail));
                }
                let x = s.a(p, 0);
                unify_list(s, &pairs, x)
            } else {
                return Err(inst("pairs_keys", 2));
            }
        }
        B::OrdSubtract | B::OrdUnion | B::OrdIntersection => {
            let a = proper(s, s.a(p, 0), "ord_union", 3)?;
            let c = proper(s, s.a(p, 1), "ord_union", 3)?;
            let keep = match b {
                B::OrdSubtract => (true, false, false),
                B::OrdUnion => (true, true, true),
                _ => (false, true, false),
            };
            let out = ord_merge(s, &a, &c, keep);
            let y = s.a(p, 2);
            unify_list(s, &out, y)
        }
        B::OrdUnion2 => {
            let sets = proper(s, s.a(p, 0), "ord_union", 2)?;
            let mut acc = Vec::new();
            for set in sets {
                let items = proper(s, set, "ord_union", 2)?;
                acc = ord_merge(s, &acc, &items, (true, true, true));
            }
            let y = s.a(p, 1);
            unify_list(s, &acc, y)
        }
        B::OrdMemberchk => {
            let items = proper(s, s.a(p, 1), "ord_memberchk", 2)?;
            let x = s.a(p, 0);
            let found = items
                .iter()
                .any(|it| s.m.st.compare(x, *it) == Ordering::Equal);
            if found {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        B::OrdInsert | B::OrdAddElement | B::OrdDelElement => {
            let items = proper(s, s.a(p, 0), "ord_add_element", 3)?;
            let e = [s.a(p, 1)];
            let keep = if b == B::OrdDelElement {
                (true, false, false)
            } else {
                (true, true, true)
            };
            let out = ord_merge(s, &items, &e, keep);
            let y = s.a(p, 2);
            unify_list(s, &out, y)
        }
        B::OrdSubset => {
            let a = proper(s, s.a(p, 0), "ord_subset", 2)?;
            let c = proper(s, s.a(p, 1), "ord_subset", 2)?;
            if ord_merge(s, &a, &c, (true, false, false)).is_empty() {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        B::OrdEmpty => {
            let x = s.a(p, 0);
            if s.unify(x, NIL) {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        _ => return Ok(None),
    }))
}
