//! Walking located terms without recursion: subterms with their spans, variable occurrences,
//! the predicate calls of a query, and the literals of an update.

use crate::diag::Span;
use crate::syntax::prolog::{Located, TermSpans};
use crate::term::{Sym, Term};
use std::collections::BTreeSet;

/// A set of variables (membership only: never iterated into output, since `Sym` ids depend on
/// interning order).
pub type VarSet = BTreeSet<Sym>;

/// The variables of `t`.
pub fn var_set(t: &Term) -> VarSet {
    let mut out = VarSet::new();
    t.for_each_var(&mut |v| {
        out.insert(v);
    });
    out
}

/// A subterm with the span it was read from (the parent's span when spans are missing).
pub type At<'a> = (&'a Term, Span);

/// The span of argument `i` of the term at `spans` (falls back to the term's own span).
fn arg_span<'a>(
    spans: Option<&'a TermSpans>,
    parent: &Span,
    i: usize,
) -> (Option<&'a TermSpans>, Span) {
    match spans.and_then(|s| s.args.get(i)) {
        Some(s) => (Some(s), s.span.clone()),
        None => (None, parent.clone()),
    }
}

/// Every subterm of `loc` in pre-order, with spans.
pub fn subterms(loc: &Located) -> Vec<At<'_>> {
    let mut out = Vec::new();
    let mut stack: Vec<(&Term, Option<&TermSpans>, Span)> =
        vec![(&loc.term, Some(&loc.spans), loc.spans.span.clone())];
    while let Some((t, spans, span)) = stack.pop() {
        if let Term::Compound(c) = t {
            for (i, a) in c.args.iter().enumerate().rev() {
                let (s, sp) = arg_span(spans, &span, i);
                stack.push((a, s, sp));
            }
        }
        out.push((t, span));
    }
    out
}

/// The occurrences of variables in `loc`, in textual order.
pub fn var_occurrences(loc: &Located) -> Vec<(Sym, Span)> {
    subterms(loc)
        .into_iter()
        .filter_map(|(t, s)| match t {
            Term::Var(v) => Some((*v, s)),
            _ => None,
        })
        .collect()
}

/// True for the names the reader gives anonymous variables (`_` becomes `_G<n>`).
pub fn is_anonymous(v: Sym) -> bool {
    let n = v.name();
    n == "_"
        || n.strip_prefix("_G")
            .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
}

/// The name of a variable as the user wrote it (`_` for anonymous ones).
pub fn var_name(v: Sym) -> &'static str {
    if is_anonymous(v) {
        "_"
    } else {
        v.name()
    }
}

/// A located subterm: a term with its spans, borrowed from a [`Located`].
#[derive(Clone, Copy)]
pub struct Sub<'a> {
    pub term: &'a Term,
    pub spans: Option<&'a TermSpans>,
    pub span: &'a Span,
}

impl<'a> Sub<'a> {
    /// The whole of `loc`.
    pub fn of(loc: &'a Located) -> Sub<'a> {
        Sub {
            term: &loc.term,
            spans: Some(&loc.spans),
            span: &loc.spans.span,
        }
    }

    /// Argument `i` (with the parent's span when spans are missing).
    pub fn arg(&self, i: usize) -> Option<Sub<'a>> {
        let t = self.term.args().get(i)?;
        let s = self.spans.and_then(|s| s.args.get(i));
        Some(Sub {
            term: t,
            spans: s,
            span: s.map_or(self.span, |s| &s.span),
        })
    }

    /// An owned copy as a [`Located`].
    pub fn located(&self) -> Located {
        Located {
            term: self.term.clone(),
            spans: self.spans.cloned().unwrap_or_else(|| TermSpans {
                span: self.span.clone(),
                args: Vec::new(),
            }),
        }
    }
}

/// The top-level conjuncts of `s` (`a, (b, c)` gives `a`, `b`, `c`).
pub fn conjuncts(s: Sub<'_>) -> Vec<Sub<'_>> {
    let mut out = Vec::new();
    let mut stack = vec![s];
    while let Some(s) = stack.pop() {
        if s.term.is_functor(Sym::intern(","), 2) {
            if let (Some(a), Some(b)) = (s.arg(0), s.arg(1)) {
                stack.push(b);
                stack.push(a);
                continue;
            }
        }
        out.push(s);
    }
    out
}

/// How a goal position inside a query is used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Polarity {
    Positive,
    /// Under `not/1` or `\+/1`: binds nothing.
    Negated,
}

/// The predicate calls made by query `s`, looking through control constructs (`,` `;` `->`
/// `\+` `not` `call/N` `findall` `forall` `once` ...), with their polarity. Variables as goals
/// are skipped.
pub fn calls(s: Sub<'_>) -> Vec<(Sub<'_>, Polarity)> {
    let mut out = Vec::new();
    let mut stack = vec![(s, Polarity::Positive)];
    while let Some((s, pol)) = stack.pop() {
        let Some((name, arity)) = s.term.functor() else {
            continue; // variables, numbers, strings
        };
        let n = name.name();
        // (argument positions that are goals, polarity change)
        let goal_args: &[usize] = match (n, arity) {
            (",", 2) | (";", 2) | ("->", 2) | ("*->", 2) => &[0, 1],
            ("\\+", 1) | ("not", 1) => {
                if let Some(a) = s.arg(0) {
                    stack.push((a, Polarity::Negated));
                }
                continue;
            }
            ("once", 1) | ("ignore", 1) => &[0],
            ("call", _) => &[0],
            ("forall", 2) => &[0, 1],
            ("findall", 3) | ("findall", 4) | ("bagof", 3) | ("setof", 3) => &[1],
            ("aggregate_all", 3) | ("aggregate", 3) => &[1],
            ("aggregate_all", 4) | ("aggregate", 4) => &[2],
            ("^", 2) => &[1],
            _ => {
                out.push((s, pol));
                continue;
            }
        };
        if n == "call" && arity > 1 {
            // call(G, A1, ...) calls G with extra arguments: its predicate is not known here.
            out.push((s, pol));
            continue;
        }
        if !matches!(n, "," | ";" | "->" | "*->") {
            out.push((s, pol)); // the control construct itself (a built-in)
        }
        for &i in goal_args.iter().rev() {
            if let Some(a) = s.arg(i) {
                stack.push((a, pol));
            }
        }
    }
    out
}

/// The variables a query binds: those not only under negation.
pub fn binding_vars(loc: &Located) -> VarSet {
    let mut out = VarSet::new();
    for (c, pol) in calls(Sub::of(loc)) {
        if pol == Polarity::Positive {
            c.term.for_each_var(&mut |v| {
                out.insert(v);
            });
        }
    }
    out
}

/// The first span at which variable `v` occurs in `loc`.
pub fn first_occurrence(loc: &Located, v: Sym) -> Span {
    var_occurrences(loc)
        .into_iter()
        .find(|(w, _)| *w == v)
        .map_or(loc.spans.span.clone(), |(_, s)| s)
}
