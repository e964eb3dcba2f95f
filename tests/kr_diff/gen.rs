//! Seeded generators: random fact sets with random queries over them, and random queries over the
//! list, sorting, all-solutions and arithmetic built-ins.

use crate::build::*;
use crate::programs::Program;
use goal::term::Term;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Atoms of generated data. No one-character atoms: scryer 0.10 reads a list that starts with one
/// (`[d,2]`) as a partial string and then rejects it as a list (`sort/2` raises `type_error`).
const ATOMS: &[&str] = &["al", "bo", "cy", "di", "ed"];
const VARS: &[&str] = &["X", "Y", "Z", "W"];
/// Predicates of generated fact sets (name, arity). `u/1` never has facts: in GOAL an undefined
/// predicate fails, so scryer runs with the `unknown` flag set to `fail` (see `scryer::PRELUDE`).
const PREDS: &[(&str, usize)] = &[("p", 1), ("q", 2), ("r", 2), ("s", 3), ("u", 1)];

fn constant(rng: &mut ChaCha8Rng) -> Term {
    if rng.gen_bool(0.7) {
        a(ATOMS.choose(rng).copied().unwrap_or("al"))
    } else {
        i(rng.gen_range(0..4))
    }
}

fn arg(rng: &mut ChaCha8Rng) -> Term {
    if rng.gen_bool(0.65) {
        v(VARS.choose(rng).copied().unwrap_or("X"))
    } else {
        constant(rng)
    }
}

/// A random fact set over `p/1`, `q/2`, `r/2`, `s/3` (duplicates allowed: beliefs are a set in
/// GOAL, but knowledge may repeat facts), with rules `t/2` and `w/1` over them and `n` queries.
pub fn fact_set(rng: &mut ChaCha8Rng, n: usize) -> Program {
    let mut clauses = Vec::new();
    for &(name, arity) in PREDS {
        if name == "u" {
            continue;
        }
        for _ in 0..rng.gen_range(2..14) {
            let args = (0..arity).map(|_| constant(rng)).collect();
            clauses.push(c(name, args));
        }
    }
    clauses.push(rule(
        c("t", vec![v("X"), v("Y")]),
        vec![c("q", vec![v("X"), v("Z")]), c("r", vec![v("Z"), v("Y")])],
    ));
    clauses.push(rule(
        c("t", vec![v("X"), v("Y")]),
        vec![c("s", vec![v("X"), v("Y"), v("_")])],
    ));
    clauses.push(rule(
        c("w", vec![v("X")]),
        vec![
            c("p", vec![v("X")]),
            naf(c("q", vec![v("X"), v("_")])),
            a("!"),
        ],
    ));
    clauses.push(rule(
        c("w", vec![v("X")]),
        vec![c("r", vec![v("X"), v("X")])],
    ));
    // Random rules with cuts, negation, if-then-else and all-solutions calls in their bodies.
    for (name, head) in [("g", vec![v("X")]), ("h", vec![v("X"), v("Y")])] {
        for _ in 0..rng.gen_range(1..=3) {
            let mut body: Vec<Term> = (0..rng.gen_range(1..=3))
                .map(|_| goal(rng, 1, false))
                .collect();
            if rng.gen_bool(0.4) {
                let at = rng.gen_range(0..=body.len());
                body.insert(at, a("!"));
            }
            clauses.push(rule(c(name, head.clone()), body));
        }
    }
    let queries = (0..n).map(|_| query(rng)).collect();
    Program {
        name: "facts".into(),
        clauses,
        queries,
    }
}

/// A literal over the fact predicates and the fixed rules; with `top`, also over the generated
/// rules `g/1` and `h/2` (their own bodies never call them, so every program terminates).
fn literal(rng: &mut ChaCha8Rng, top: bool) -> Term {
    let preds: &[(&str, usize)] = &[
        ("p", 1),
        ("q", 2),
        ("r", 2),
        ("s", 3),
        ("u", 1),
        ("t", 2),
        ("w", 1),
        ("g", 1),
        ("h", 2),
    ];
    let n = if top { preds.len() } else { preds.len() - 2 };
    let (name, arity) = preds[rng.gen_range(0..n)];
    c(name, (0..arity).map(|_| arg(rng)).collect())
}

fn goal(rng: &mut ChaCha8Rng, depth: u32, top: bool) -> Term {
    let k = rng.gen_range(0..100);
    match k {
        0..=49 => literal(rng, top),
        50..=57 => naf(literal(rng, top)),
        58..=61 => c("not", vec![literal(rng, top)]),
        62..=65 => op(
            ["\\==", "==", "\\=", "="]
                .choose(rng)
                .copied()
                .unwrap_or("=="),
            arg(rng),
            arg(rng),
        ),
        // The standard order of two distinct unbound variables is implementation-defined (ISO
        // 7.2.1): compare with a constant only.
        66 => op("@<", arg(rng), constant(rng)),
        67..=74 if depth > 0 => and(vec![goal(rng, depth - 1, top), goal(rng, depth - 1, top)]),
        75..=79 if depth > 0 => op(";", goal(rng, depth - 1, top), goal(rng, depth - 1, top)),
        80..=83 if depth > 0 => op(
            ";",
            op("->", goal(rng, depth - 1, top), goal(rng, depth - 1, top)),
            goal(rng, depth - 1, top),
        ),
        84..=86 if depth > 0 => c(
            "findall",
            vec![
                v(VARS.choose(rng).copied().unwrap_or("X")),
                goal(rng, depth - 1, top),
                result_var(rng, "L"),
            ],
        ),
        87..=89 => {
            let what = ["count", "bag", "set"]
                .choose(rng)
                .copied()
                .unwrap_or("count");
            let tmpl = if what == "count" {
                a("count")
            } else {
                c(what, vec![v(VARS.choose(rng).copied().unwrap_or("X"))])
            };
            c(
                "aggregate_all",
                vec![tmpl, literal(rng, top), result_var(rng, "N")],
            )
        }
        90..=92 => c("forall", vec![literal(rng, top), literal(rng, top)]),
        93..=95 => c("once", vec![literal(rng, top)]),
        96..=97 => {
            // setof/bagof with and without `^`.
            let name = if rng.gen_bool(0.5) { "setof" } else { "bagof" };
            let g = c("q", vec![v("X"), v("Y")]);
            let g = if rng.gen_bool(0.5) {
                c("^", vec![v("Y"), g])
            } else {
                g
            };
            c(name, vec![v("X"), g, result_var(rng, "L")])
        }
        _ => and(vec![literal(rng, top), a("!"), literal(rng, top)]),
    }
}

/// A result variable: half the time shared between goals (`L`, `N`: a later all-solutions call
/// may find it bound, even to a non-list), else fresh (`L17`, `N3`, ...).
fn result_var(rng: &mut ChaCha8Rng, prefix: &str) -> Term {
    if rng.gen_bool(0.5) {
        v(prefix)
    } else {
        v(&format!("{prefix}{}", rng.gen_range(0..1000)))
    }
}

/// A random query over the fact set predicates.
pub fn query(rng: &mut ChaCha8Rng) -> Term {
    let n = rng.gen_range(1..=3);
    and((0..n).map(|_| goal(rng, 2, true)).collect())
}

fn small_list(rng: &mut ChaCha8Rng, max: usize) -> Term {
    let n = rng.gen_range(0..=max);
    list((0..n).map(|_| constant(rng)).collect())
}

fn int_list(rng: &mut ChaCha8Rng, max: usize) -> Term {
    let n = rng.gen_range(0..=max);
    list((0..n).map(|_| i(rng.gen_range(-5..10))).collect())
}

fn pair_list(rng: &mut ChaCha8Rng, max: usize) -> Term {
    let n = rng.gen_range(0..=max);
    list(
        (0..n)
            .map(|_| c("f", vec![constant(rng), i(rng.gen_range(0..4))]))
            .collect(),
    )
}

fn expr(rng: &mut ChaCha8Rng, depth: u32) -> Term {
    if depth == 0 || rng.gen_bool(0.3) {
        return if rng.gen_bool(0.07) {
            Term::Float(goal::term::Float(rng.gen_range(-8..8) as f64 / 4.0))
        } else {
            i(rng.gen_range(-20..20))
        };
    }
    let ops = ["+", "-", "*", "//", "mod", "min", "max", "/"];
    let name = ops.choose(rng).copied().unwrap_or("+");
    let l = expr(rng, depth - 1);
    let r = expr(rng, depth - 1);
    match rng.gen_range(0..10) {
        0 => c("abs", vec![l]),
        1 => c("-", vec![l]),
        _ => op(name, l, r),
    }
}

/// A random query over the list, sorting and arithmetic built-ins.
pub fn list_query(rng: &mut ChaCha8Rng) -> Term {
    let (x, y, z) = (v("X"), v("Y"), v("Z"));
    match rng.gen_range(0..22) {
        0 => c("append", vec![x, y, small_list(rng, 4)]),
        1 => c("append", vec![small_list(rng, 3), small_list(rng, 3), x]),
        2 => c("reverse", vec![small_list(rng, 5), x]),
        3 => c("member", vec![x, small_list(rng, 5)]),
        4 => c("length", vec![small_list(rng, 5), x]),
        5 => c("nth0", vec![x, small_list(rng, 5), y]),
        6 => c("nth0", vec![i(rng.gen_range(0..5)), small_list(rng, 5), y]),
        7 => c("msort", vec![small_list(rng, 6), x]),
        8 => c("sort", vec![small_list(rng, 6), x]),
        9 => {
            let order = ["@<", "@>", "@=<", "@>="]
                .choose(rng)
                .copied()
                .unwrap_or("@<");
            c(
                "sort",
                vec![i(rng.gen_range(0..=2)), a(order), pair_list(rng, 6), x],
            )
        }
        10 => c(
            "findall",
            vec![
                op("-", x.clone(), y.clone()),
                and(vec![
                    c("member", vec![x.clone(), small_list(rng, 4)]),
                    c("member", vec![y, small_list(rng, 3)]),
                    op("@<", x, v("_Z")),
                ]),
                z,
            ],
        ),
        11 => c(
            "setof",
            vec![x.clone(), c("member", vec![x, small_list(rng, 6)]), y],
        ),
        12 => c(
            "bagof",
            vec![
                x.clone(),
                c("member", vec![c("f", vec![x, y]), pair_list(rng, 5)]),
                z,
            ],
        ),
        13 => {
            let what = ["count", "sum", "max", "min", "bag", "set"]
                .choose(rng)
                .copied()
                .unwrap_or("count");
            let tmpl = if what == "count" {
                a("count")
            } else {
                c(what, vec![x.clone()])
            };
            c(
                "aggregate_all",
                vec![tmpl, c("member", vec![x, int_list(rng, 5)]), y],
            )
        }
        14 => {
            let lo = rng.gen_range(-3..5);
            c("between", vec![i(lo), i(lo + rng.gen_range(-1..5)), x])
        }
        15 => op("is", x, expr(rng, 3)),
        16 => op(
            ["<", ">", "=<", ">=", "=:=", "=\\="]
                .choose(rng)
                .copied()
                .unwrap_or("<"),
            expr(rng, 2),
            expr(rng, 2),
        ),
        17 => c("sum_list", vec![int_list(rng, 5), x]),
        18 => c("max_list", vec![int_list(rng, 5), x]),
        19 => c("last", vec![small_list(rng, 4), x]),
        20 => c("subtract", vec![small_list(rng, 5), small_list(rng, 3), x]),
        _ => c("delete", vec![small_list(rng, 5), constant(rng), x]),
    }
}

/// Queries that raise errors on both engines: the error terms (their formal part) must agree.
/// Left out on purpose: `atom_length(123, L)` (SWI, and so GOAL, accepts numbers; ISO and
/// scryer raise `type_error`), syntax errors of `number_codes/2` (the formal term is
/// implementation-specific) and `length(L, -1)` (SWI and ISO differ).
pub fn error_queries() -> Vec<Term> {
    vec![
        op("is", v("X"), op("+", v("Y"), i(1))),
        op("is", v("X"), op("+", a("foo"), i(1))),
        op("is", v("X"), op("//", i(1), i(0))),
        op("<", v("X"), i(1)),
        c("atom_length", vec![v("X"), v("Y")]),
        c("functor", vec![v("F"), v("N"), v("A")]),
        c("arg", vec![a("x"), c("f", vec![a("a")]), v("A")]),
        op("=..", v("X"), v("Y")),
        c("call", vec![v("G")]),
        c("call", vec![i(1)]),
        c("atom_codes", vec![v("X"), v("Y")]),
        c("atom_chars", vec![v("X"), list(vec![a("ab")])]),
        c(
            "findall",
            vec![v("X"), c("member", vec![v("X"), list(vec![i(1)])]), i(9)],
        ),
        c(
            "aggregate_all",
            vec![c("bag", vec![v("X")]), a("fail"), i(9)],
        ),
        c("atom_length", vec![a("abc"), a("x")]),
        op("is", v("X"), c("foo", vec![i(1)])),
        c("sub_atom", vec![v("A"), v("B"), v("L"), v("C"), a("x")]),
        c("succ", vec![v("X"), i(0)]),
        c("between", vec![i(1), a("x"), v("X")]),
        c("nth0", vec![a("x"), list(vec![a("ab")]), v("E")]),
    ]
}
