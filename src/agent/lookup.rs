//! Belief queries answered without starting the engine: a single fact pattern matched against
//! the fact bases directly, and a comparison of two integers. Each gives exactly the answers,
//! in the order, that the native engine would give; anything that could differ (a predicate
//! knowledge or a built-in answers, a non-ground fact, a float, many candidate facts, tight
//! resource limits) is left to the engine.

use super::kr_bridge::{FactBase, Limits};
use crate::kr::native::code::Key;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};

/// Most candidate facts a direct match looks at; past this the engine answers (its inference,
/// answer and deadline checks then apply as always).
pub(super) const MAX_CANDIDATES: usize = 256;
/// Most cells of bound values a direct match hands back (the engine's memory budget counts them).
pub(super) const MAX_CELLS: usize = 10_000;

/// True when the limits leave a direct match's work far inside every budget, so that the engine
/// could not have stopped the same query with a resource error.
pub fn roomy(l: &Limits) -> bool {
    l.max_inferences >= 4 * MAX_CANDIDATES as u64
        && l.max_answers >= MAX_CANDIDATES as u64
        && l.max_heap_cells >= 16 * MAX_CELLS as u64
}

/// The answers of the fact pattern `q` under `theta` (which the answers do not repeat) over
/// `bases`, at most `cap`, and whether `cap` stopped them: `q`'s predicate must be one only
/// facts answer. `None`: leave the query to the engine.
pub fn fact_answers(
    bases: &[&FactBase],
    q: &Term,
    theta: &Subst,
    cap: usize,
) -> Option<(Vec<Subst>, bool)> {
    let (name, arity) = q.functor()?;
    let (k1, k2) = (arg_key(q, 0, theta)?, arg_key(q, 1, theta)?);
    let mut out = Vec::new();
    let mut candidates = 0;
    let mut cells = 0;
    for base in bases.iter().filter(|b| b.has_pred(name, arity)) {
        let mut scan = base.scan(name, arity as u32, k1, k2);
        while let Some(fact) = base.advance(&mut scan) {
            candidates += 1;
            if candidates > MAX_CANDIDATES {
                return None;
            }
            let mut a = Subst::new();
            if match_in(q, theta, fact, &mut a, &mut cells)? {
                out.push(a);
                if out.len() >= cap {
                    return Some((out, true));
                }
            }
        }
    }
    Some((out, false))
}

/// The index key of argument `i` of `q` under `theta` (`Some(None)`: unbound or absent);
/// `None` when a float makes the key unreliable for an exact match.
fn arg_key(q: &Term, i: usize, theta: &Subst) -> Option<Option<Key>> {
    let Some(a) = q.args().get(i) else {
        return Some(None);
    };
    let a = match a {
        Term::Var(v) => match theta.get(*v) {
            Some(t) => t,
            None => return Some(None),
        },
        t => t,
    };
    match a {
        Term::Float(_) => None,
        t => Some(Key::of_term(t)),
    }
}

/// A term whose equality is its unifiability with another ground term: an atom, an integer or
/// a string (floats unify by value, `0.0` with `-0.0`).
fn plain_atomic(t: &Term) -> bool {
    matches!(
        t,
        Term::Atom(_) | Term::Int(_) | Term::BigInt(_) | Term::Str(_)
    )
}

/// Matches `pattern` under `theta` against `fact`, binding the pattern's free variables in
/// reading order (as the engine's answers do); `None` when the match cannot be decided by
/// plain comparison (a variable in the fact or in a bound value, a float, a compound bound
/// value compared, or too many cells bound).
fn match_in(
    pattern: &Term,
    theta: &Subst,
    fact: &Term,
    s: &mut Subst,
    cells: &mut usize,
) -> Option<bool> {
    let mut work: SmallVec<[(&Term, &Term); 8]> = smallvec![(pattern, fact)];
    while let Some((p, f)) = work.pop() {
        if matches!(f, Term::Var(_)) {
            return None;
        }
        match p {
            Term::Var(v) if *v == wk::UNDERSCORE => {
                if !f.is_ground() {
                    return None;
                }
            }
            Term::Var(v) => {
                if let Some(bound) = theta.get(*v).or_else(|| s.get(*v)) {
                    if !plain_atomic(bound) || !plain_atomic(f) {
                        return None;
                    }
                    if bound != f {
                        return Some(false);
                    }
                    continue;
                }
                *cells += size_if_ground(f)?;
                if *cells > MAX_CELLS {
                    return None;
                }
                s.bind(*v, f.clone());
            }
            Term::Compound(pc) => {
                let Term::Compound(fc) = f else {
                    return Some(false);
                };
                if pc.name != fc.name || pc.args.len() != fc.args.len() {
                    return Some(false);
                }
                // Reversed, so that the leftmost argument is matched first.
                work.extend(pc.args.iter().zip(fc.args.iter()).rev());
            }
            Term::Float(_) => return None,
            _ => {
                if matches!(f, Term::Float(_)) {
                    return None;
                }
                if p != f {
                    return Some(false);
                }
            }
        }
    }
    Some(true)
}

/// The number of cells of a ground term (`None` when it has a variable or is too large).
#[inline]
pub(super) fn size_if_ground(t: &Term) -> Option<usize> {
    match t {
        Term::Var(_) => None,
        Term::Compound(_) => compound_size_if_ground(t),
        _ => Some(1),
    }
}

/// [`size_if_ground`] of a compound term (out of line: the atomic case is the common one).
#[inline(never)]
fn compound_size_if_ground(t: &Term) -> Option<usize> {
    let mut n = 0;
    let mut stack: SmallVec<[&Term; 16]> = smallvec![t];
    while let Some(t) = stack.pop() {
        n += 1;
        if n > MAX_CELLS {
            return None;
        }
        match t {
            Term::Var(_) => return None,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    Some(n)
}

/// The truth of an arithmetic comparison `q` (`<`, `>`, `=<`, `>=`, `=:=`, `=\=`) whose sides
/// are integers under `theta`; `None` for anything else (the engine evaluates it).
pub fn int_comparison(q: &Term, theta: &Subst) -> Option<bool> {
    let Term::Compound(c) = q else {
        return None;
    };
    if c.args.len() != 2 {
        return None;
    }
    let int = |t: &Term| match theta.walk(t) {
        Term::Int(i) => Some(*i),
        _ => None,
    };
    let (a, b) = (int(&c.args[0])?, int(&c.args[1])?);
    let name = c.name;
    Some(if name == *LT {
        a < b
    } else if name == *GT {
        a > b
    } else if name == *LE {
        a <= b
    } else if name == *GE {
        a >= b
    } else if name == *EQ {
        a == b
    } else if name == *NE {
        a != b
    } else {
        return None;
    })
}

static LT: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern("<"));
static GT: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern(">"));
static LE: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern("=<"));
static GE: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern(">="));
static EQ: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern("=:="));
static NE: std::sync::LazyLock<Sym> = std::sync::LazyLock::new(|| Sym::intern("=\\="));

#[cfg(test)]
mod tests {
    use super::*;

    fn term(text: &str) -> Term {
        let mut r = crate::syntax::prolog::Reader::new("test");
        r.term(text, 0).expect("term").term
    }

    fn base(facts: &[&str]) -> FactBase {
        let mut b = FactBase::new();
        for f in facts {
            b.insert(term(f));
        }
        b
    }

    fn show(answers: &[Subst]) -> Vec<String> {
        answers
            .iter()
            .map(crate::agent::condition::show_subst)
            .collect()
    }

    #[test]
    fn facts_are_matched_in_base_then_insertion_order_under_theta() {
        let b1 = base(&["p(1, a)", "p(2, b)", "q(x)", "p(1, c)"]);
        let b2 = base(&["p(1, a)", "p(3, d)"]);
        let q = term("p(X, Y)");
        let mut theta = Subst::new();
        let (all, cut) = fact_answers(&[&b1, &b2], &q, &theta, usize::MAX).unwrap();
        assert!(!cut);
        assert_eq!(
            show(&all),
            ["X=1, Y=a", "X=2, Y=b", "X=1, Y=c", "X=1, Y=a", "X=3, Y=d"]
        );
        let x = q.args()[0].clone();
        let Term::Var(xv) = x else { panic!() };
        theta.bind(xv, Term::Int(1));
        let (ones, _) = fact_answers(&[&b1, &b2], &q, &theta, usize::MAX).unwrap();
        assert_eq!(show(&ones), ["Y=a", "Y=c", "Y=a"]);
        let (first, cut) = fact_answers(&[&b1, &b2], &q, &theta, 2).unwrap();
        assert!(cut);
        assert_eq!(show(&first), ["Y=a", "Y=c"]);
    }

    #[test]
    fn what_plain_comparison_cannot_decide_is_left_to_the_engine() {
        let floats = base(&["p(1.0)"]);
        assert!(fact_answers(&[&floats], &term("p(X)"), &Subst::new(), 9).is_some());
        assert!(fact_answers(&[&floats], &term("p(1.0)"), &Subst::new(), 9).is_none());
        let mut open = FactBase::new();
        open.insert(term("p(f(_))"));
        assert!(fact_answers(&[&open], &term("p(X)"), &Subst::new(), 9).is_none());
        let many: Vec<String> = (0..=MAX_CANDIDATES).map(|i| format!("p({i})")).collect();
        let big = base(&many.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(fact_answers(&[&big], &term("p(X)"), &Subst::new(), 9999).is_none());
        assert_eq!(
            fact_answers(&[&big], &term("p(7)"), &Subst::new(), 9).map(|a| a.0.len()),
            Some(1)
        );
    }

    #[test]
    fn integer_comparisons_are_decided_and_others_are_not() {
        let q = term("N < 2");
        let Term::Var(n) = q.args()[0].clone() else {
            panic!()
        };
        let mut theta = Subst::new();
        assert_eq!(int_comparison(&q, &theta), None);
        theta.bind(n, Term::Int(1));
        assert_eq!(int_comparison(&q, &theta), Some(true));
        theta.bind(n, Term::Int(2));
        assert_eq!(int_comparison(&q, &theta), Some(false));
        assert_eq!(int_comparison(&term("3 =\\= 3"), &theta), Some(false));
        assert_eq!(int_comparison(&term("3 >= 3"), &theta), Some(true));
        assert_eq!(int_comparison(&term("1 < 2.0"), &theta), None);
        assert_eq!(int_comparison(&term("1 < 1+1"), &theta), None);
        assert_eq!(int_comparison(&term("1 == 1"), &theta), None);
    }
}
