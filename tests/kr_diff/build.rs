//! Short constructors for building Prolog programs and queries as `Term`s in Rust.

#![allow(dead_code)]

use goal::term::{Sym, Term};

/// An atom.
pub fn a(name: &str) -> Term {
    Term::atom(name)
}

/// A variable.
pub fn v(name: &str) -> Term {
    Term::var(name)
}

/// An integer.
pub fn i(n: i64) -> Term {
    Term::Int(n)
}

/// A compound term (an atom when `args` is empty).
pub fn c(name: &str, args: Vec<Term>) -> Term {
    Term::compound(Sym::intern(name), args)
}

/// A proper list.
pub fn list(items: Vec<Term>) -> Term {
    Term::list(items)
}

/// A conjunction of goals (`true` when empty).
pub fn and(goals: Vec<Term>) -> Term {
    Term::conjunction(goals)
}

/// `Head :- Body` (a fact when `body` is empty).
pub fn rule(head: Term, body: Vec<Term>) -> Term {
    if body.is_empty() {
        head
    } else {
        c(":-", vec![head, and(body)])
    }
}

/// A binary operator term such as `X is A+B`.
pub fn op(name: &str, l: Term, r: Term) -> Term {
    c(name, vec![l, r])
}

/// `\+ G`.
pub fn naf(g: Term) -> Term {
    c("\\+", vec![g])
}
