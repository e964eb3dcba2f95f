//! The fixed knowledge programs (family tree, blocks world, path finding), each with fact sets
//! generated from a seed and queries over every argument mode.

use crate::build::*;
use goal::term::Term;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A knowledge program: clauses to load and queries to compare answers on.
pub struct Program {
    /// Name, shown in failure messages.
    pub name: String,
    /// Facts and rules.
    pub clauses: Vec<Term>,
    /// Queries.
    pub queries: Vec<Term>,
}

fn person(k: usize) -> Term {
    a(&format!("p{k}"))
}

/// A family tree of `n` people: each person after the first two has up to two parents among the
/// earlier people (so `ancestor/2` terminates), with rules over it.
pub fn family(rng: &mut ChaCha8Rng, n: usize) -> Program {
    let mut clauses = Vec::new();
    for k in 0..n {
        let g = if rng.gen_bool(0.5) { "male" } else { "female" };
        clauses.push(c(g, vec![person(k)]));
    }
    for k in 2..n {
        let mut parents: Vec<usize> = (0..k).collect();
        parents.shuffle(rng);
        for &p in parents.iter().take(rng.gen_range(1..=2)) {
            clauses.push(c("parent", vec![person(p), person(k)]));
        }
    }
    let (x, y, z, p) = (v("X"), v("Y"), v("Z"), v("P"));
    clauses.extend([
        rule(
            c("ancestor", vec![x.clone(), y.clone()]),
            vec![c("parent", vec![x.clone(), y.clone()])],
        ),
        rule(
            c("ancestor", vec![x.clone(), y.clone()]),
            vec![
                c("parent", vec![x.clone(), z.clone()]),
                c("ancestor", vec![z.clone(), y.clone()]),
            ],
        ),
        rule(
            c("sibling", vec![x.clone(), y.clone()]),
            vec![
                c("parent", vec![p.clone(), x.clone()]),
                c("parent", vec![p.clone(), y.clone()]),
                op("\\==", x.clone(), y.clone()),
            ],
        ),
        rule(
            c("grandparent", vec![x.clone(), z.clone()]),
            vec![
                c("parent", vec![x.clone(), y.clone()]),
                c("parent", vec![y.clone(), z.clone()]),
            ],
        ),
        rule(
            c("mother", vec![x.clone(), y.clone()]),
            vec![
                c("parent", vec![x.clone(), y.clone()]),
                c("female", vec![x.clone()]),
            ],
        ),
        rule(
            c("orphan", vec![x.clone()]),
            vec![
                c("person", vec![x.clone()]),
                naf(c("parent", vec![v("_"), x.clone()])),
            ],
        ),
        rule(
            c("person", vec![x.clone()]),
            vec![c("male", vec![x.clone()])],
        ),
        rule(
            c("person", vec![x.clone()]),
            vec![c("female", vec![x.clone()])],
        ),
        rule(
            c("descendants", vec![x.clone(), v("N")]),
            vec![c(
                "aggregate_all",
                vec![a("count"), c("ancestor", vec![x.clone(), v("_D")]), v("N")],
            )],
        ),
    ]);
    let mut queries = Vec::new();
    for rel in ["parent", "ancestor", "sibling", "grandparent", "mother"] {
        queries.push(c(rel, vec![v("A"), v("B")]));
        for _ in 0..6 {
            let k = rng.gen_range(0..n);
            queries.push(c(rel, vec![person(k), v("B")]));
            queries.push(c(rel, vec![v("A"), person(k)]));
            queries.push(c(rel, vec![person(k), person(rng.gen_range(0..n))]));
        }
    }
    queries.push(c("orphan", vec![v("X")]));
    queries.push(c("descendants", vec![v("X"), v("N")]));
    queries.push(c(
        "setof",
        vec![
            v("X"),
            c("^", vec![v("Y"), c("ancestor", vec![v("X"), v("Y")])]),
            v("L"),
        ],
    ));
    queries.push(c(
        "bagof",
        vec![v("Y"), c("parent", vec![v("X"), v("Y")]), v("L")],
    ));
    queries.push(c(
        "findall",
        vec![
            op("-", v("X"), v("Y")),
            c("sibling", vec![v("X"), v("Y")]),
            v("L"),
        ],
    ));
    queries.push(and(vec![
        c("person", vec![v("X")]),
        c("not", vec![c("ancestor", vec![v("X"), v("_")])]),
    ]));
    Program {
        name: format!("family({n})"),
        clauses,
        queries,
    }
}

fn block(k: usize) -> Term {
    a(&format!("b{k}"))
}

/// A blocks world of `n` blocks in random stacks on the table, with `clear/1`, `above/2` and the
/// recursive `tower/1`.
pub fn blocks(rng: &mut ChaCha8Rng, n: usize) -> Program {
    let mut order: Vec<usize> = (0..n).collect();
    order.shuffle(rng);
    let mut clauses = Vec::new();
    let mut below: Option<usize> = None;
    for &b in &order {
        clauses.push(c("block", vec![block(b)]));
        let on = match below {
            Some(x) if rng.gen_bool(0.6) => block(x),
            _ => a("table"),
        };
        clauses.push(c("on", vec![block(b), on]));
        below = Some(b);
    }
    let (x, y, z, t) = (v("X"), v("Y"), v("Z"), v("T"));
    clauses.extend([
        rule(
            c("clear", vec![x.clone()]),
            vec![
                c("block", vec![x.clone()]),
                naf(c("on", vec![v("_"), x.clone()])),
            ],
        ),
        rule(
            c("above", vec![x.clone(), y.clone()]),
            vec![c("on", vec![x.clone(), y.clone()])],
        ),
        rule(
            c("above", vec![x.clone(), y.clone()]),
            vec![
                c("on", vec![x.clone(), z.clone()]),
                c("above", vec![z.clone(), y.clone()]),
            ],
        ),
        rule(
            c("tower", vec![list(vec![x.clone()])]),
            vec![c("on", vec![x.clone(), a("table")])],
        ),
        rule(
            c(
                "tower",
                vec![Term::list_with_tail(vec![x.clone(), y.clone()], t.clone())],
            ),
            vec![
                c("on", vec![x.clone(), y.clone()]),
                c("tower", vec![Term::cons(y.clone(), t.clone())]),
            ],
        ),
        rule(
            c("height", vec![x.clone(), v("H")]),
            vec![c("on", vec![x.clone(), a("table")]), op("=", v("H"), i(1))],
        ),
        rule(
            c("height", vec![x.clone(), v("H")]),
            vec![
                c("on", vec![x.clone(), y.clone()]),
                c("block", vec![y.clone()]),
                c("height", vec![y.clone(), v("H0")]),
                op("is", v("H"), op("+", v("H0"), i(1))),
            ],
        ),
    ]);
    let mut queries = vec![
        c("clear", vec![v("X")]),
        c("above", vec![v("X"), v("Y")]),
        c("height", vec![v("X"), v("H")]),
        and(vec![
            c("clear", vec![v("X")]),
            c("tower", vec![v("T")]),
            c("last", vec![v("T"), v("X")]),
        ]),
        c("findall", vec![v("X"), c("clear", vec![v("X")]), v("L")]),
        c(
            "aggregate_all",
            vec![
                c("max", vec![v("H")]),
                c("height", vec![v("_"), v("H")]),
                v("M"),
            ],
        ),
        and(vec![
            c("tower", vec![v("T")]),
            c("length", vec![v("T"), v("N")]),
            op(">", v("N"), i(1)),
        ]),
    ];
    for _ in 0..5 {
        let k = rng.gen_range(0..n);
        queries.push(c("clear", vec![block(k)]));
        queries.push(c("above", vec![block(k), v("Y")]));
        queries.push(c("above", vec![v("X"), block(k)]));
        queries.push(c(
            "tower",
            vec![Term::list_with_tail(vec![block(k)], v("T"))],
        ));
    }
    Program {
        name: format!("blocks({n})"),
        clauses,
        queries,
    }
}

fn node(k: usize) -> Term {
    a(&format!("n{k}"))
}

/// A random directed graph of `n` nodes (possibly cyclic) and path finding with a visited list.
pub fn paths(rng: &mut ChaCha8Rng, n: usize) -> Program {
    let mut clauses = Vec::new();
    for x in 0..n {
        for y in 0..n {
            if x != y && rng.gen_bool(0.3) {
                clauses.push(c("edge", vec![node(x), node(y)]));
            }
        }
    }
    let (x, y, z, vis, p, q) = (v("X"), v("Y"), v("Z"), v("V"), v("P"), v("Q"));
    clauses.extend([
        rule(
            c("path", vec![x.clone(), y.clone(), p.clone()]),
            vec![
                c(
                    "path",
                    vec![x.clone(), y.clone(), list(vec![x.clone()]), q.clone()],
                ),
                c("reverse", vec![q.clone(), p.clone()]),
            ],
        ),
        rule(
            c("path", vec![x.clone(), x.clone(), vis.clone(), vis.clone()]),
            vec![],
        ),
        rule(
            c("path", vec![x.clone(), y.clone(), vis.clone(), p.clone()]),
            vec![
                c("edge", vec![x.clone(), z.clone()]),
                naf(c("memberchk", vec![z.clone(), vis.clone()])),
                c(
                    "path",
                    vec![
                        z.clone(),
                        y.clone(),
                        Term::cons(z.clone(), vis.clone()),
                        p.clone(),
                    ],
                ),
            ],
        ),
        rule(
            c("reachable", vec![x.clone(), y.clone()]),
            vec![c(
                "once",
                vec![c("path", vec![x.clone(), y.clone(), v("_")])],
            )],
        ),
    ]);
    // The shortest path: the first of the paths sorted by length (`msort` keeps ties in order).
    clauses.push(rule(
        c("shortest", vec![x.clone(), y.clone(), p.clone()]),
        vec![
            c(
                "findall",
                vec![
                    op("-", v("N"), v("P0")),
                    and(vec![
                        c("path", vec![x.clone(), y.clone(), v("P0")]),
                        c("length", vec![v("P0"), v("N")]),
                    ]),
                    v("L"),
                ],
            ),
            c(
                "msort",
                vec![
                    v("L"),
                    Term::list_with_tail(vec![op("-", v("_"), p.clone())], v("_")),
                ],
            ),
        ],
    ));
    let mut queries = vec![c("edge", vec![v("X"), v("Y")])];
    for _ in 0..8 {
        let (s, t) = (rng.gen_range(0..n), rng.gen_range(0..n));
        queries.push(c("path", vec![node(s), node(t), v("P")]));
        queries.push(c("reachable", vec![node(s), v("Y")]));
        queries.push(c("shortest", vec![node(s), node(t), v("P")]));
        queries.push(c(
            "aggregate_all",
            vec![a("count"), c("path", vec![node(s), v("_"), v("_")]), v("N")],
        ));
    }
    Program {
        name: format!("paths({n})"),
        clauses,
        queries,
    }
}
