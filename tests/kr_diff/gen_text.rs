//! Seeded queries over the atom built-ins, ordered sets, pairs and the remaining list built-ins.

use crate::build::*;
use goal::term::Term;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Words the atom queries work on (no one-character atoms as inputs, see `gen::ATOMS`).
const WORDS: &[&str] = &[
    "hello", "abc", "ab", "prolog", "goal", "x1", "aaa", "12", "-7", "3.5",
];

fn word(rng: &mut ChaCha8Rng) -> Term {
    a(WORDS.choose(rng).copied().unwrap_or("abc"))
}

fn ints(rng: &mut ChaCha8Rng, max: usize, lo: i64, hi: i64) -> Term {
    let n = rng.gen_range(0..=max);
    list((0..n).map(|_| i(rng.gen_range(lo..hi))).collect())
}

fn keys(rng: &mut ChaCha8Rng, max: usize) -> Term {
    let n = rng.gen_range(0..=max);
    let names = ["kx", "ky", "kz"];
    list(
        (0..n)
            .map(|_| {
                op(
                    "-",
                    a(names.choose(rng).copied().unwrap_or("kx")),
                    i(rng.gen_range(0..5)),
                )
            })
            .collect(),
    )
}

/// A random query over atoms, ordered sets, pairs and more list built-ins.
pub fn text_query(rng: &mut ChaCha8Rng) -> Term {
    let (x, y, z) = (v("X"), v("Y"), v("Z"));
    match rng.gen_range(0..24) {
        0 => c("atom_concat", vec![x, y, word(rng)]),
        1 => c("atom_concat", vec![word(rng), word(rng), x]),
        2 => {
            let w = word(rng);
            let mut args = [v("B"), v("L"), v("A")]
                .into_iter()
                .map(|t| {
                    if rng.gen_bool(0.25) {
                        i(rng.gen_range(0..3))
                    } else {
                        t
                    }
                })
                .collect::<Vec<_>>();
            args.push(v("S"));
            c("sub_atom", [vec![w], args].concat())
        }
        3 => c("sub_atom", vec![word(rng), v("B"), i(2), v("A"), v("S")]),
        4 => c("atom_length", vec![word(rng), x]),
        5 => c("atom_chars", vec![word(rng), x]),
        6 => and(vec![
            c("atom_codes", vec![word(rng), x.clone()]),
            c("atom_codes", vec![y, x]),
        ]),
        7 => c("char_code", vec![a("a"), x]),
        8 => c("atom_number", vec![word(rng), x]),
        9 => c("atom_number", vec![x, i(rng.gen_range(-20..20))]),
        10 => c("list_to_ord_set", vec![ints(rng, 6, 0, 5), x]),
        11 => and(vec![
            c("list_to_ord_set", vec![ints(rng, 5, 0, 6), x.clone()]),
            c("list_to_ord_set", vec![ints(rng, 5, 0, 6), y.clone()]),
            c(
                ["ord_union", "ord_subtract", "ord_intersection"]
                    .choose(rng)
                    .copied()
                    .unwrap_or("ord_union"),
                vec![x, y, z],
            ),
        ]),
        12 => and(vec![
            c("list_to_ord_set", vec![ints(rng, 5, 0, 6), x.clone()]),
            c("ord_memberchk", vec![i(rng.gen_range(0..6)), x]),
        ]),
        13 => c("pairs_keys_values", vec![keys(rng, 4), x, y]),
        14 => c(
            "pairs_keys_values",
            vec![x, list(vec![a("kx"), a("ky")]), list(vec![i(1), i(2)])],
        ),
        15 => c("keysort", vec![keys(rng, 6), x]),
        16 => c("nth1", vec![x, ints(rng, 5, 0, 4), y]),
        17 => c(
            "numlist",
            vec![i(rng.gen_range(-2..3)), i(rng.gen_range(-1..6)), x],
        ),
        18 => c("select", vec![x, ints(rng, 4, 0, 3), y]),
        19 => c(
            "selectchk",
            vec![i(rng.gen_range(0..3)), ints(rng, 4, 0, 3), y],
        ),
        20 => c("permutation", vec![ints(rng, 3, 0, 9), x]),
        21 => c(
            ["include", "exclude"]
                .choose(rng)
                .copied()
                .unwrap_or("include"),
            vec![
                a("integer"),
                list(vec![i(1), a("ab"), i(2), c("f", vec![i(3)])]),
                x,
            ],
        ),
        22 => c("foldl", vec![a("plus"), ints(rng, 5, 0, 9), i(0), x]),
        _ => c("nextto", vec![x, y, ints(rng, 5, 0, 4)]),
    }
}
