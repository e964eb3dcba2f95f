//! Reusing the memory of an agent's last message content: a send writes its content over the
//! one the agent sent before, in place, when no one holds that one any more (its receiver
//! deleted the message, the agent its `sent/2` fact) and it has the same shape, instead of
//! allocating the compounds anew (and the receiver then frees nothing).
//!
//! Why this is exact: a compound is written only through `Arc::get_mut`, which succeeds only
//! for the one holder, so no one else can see the change; and the written term is the one
//! `message::atomic_instance` builds (the same walk over the pattern, the same values), wrapped
//! in the same mood, so the message, its `sent/2` fact and every trace are the same. Where the
//! shape differs, a part is held elsewhere or content validation may reject it, the send builds
//! its content the usual way.

use super::message::{atomic_instance, atomic_value, CONTENT_DEPTH};
use crate::syntax::ast::Mood;
use crate::term::{well_known as wk, Compound, Subst, Term};
use std::sync::Arc;

/// `content` under `s`, wrapped in `mood`, written over `spare` (see the module doc); `None`
/// when it cannot be (the caller builds the content the usual way).
pub fn refilled(mood: Mood, content: &Term, s: &Subst, mut spare: Term) -> Option<Term> {
    let Term::Compound(c) = content else {
        return None;
    };
    let mut suspect = false;
    let wrapper = match mood {
        Mood::Declarative => None,
        Mood::Imperative => Some(wk::IMP),
        Mood::Interrogative => Some(wk::INT),
    };
    match wrapper {
        None => refill(s, c, &mut spare, CONTENT_DEPTH, &mut suspect)?,
        Some(name) => {
            let w = unique(&mut spare)?;
            if w.name != name || w.args.len() != 1 {
                return None;
            }
            if refill(s, c, &mut w.args[0], CONTENT_DEPTH, &mut suspect).is_none() {
                w.args[0] = atomic_instance(s, content, CONTENT_DEPTH, &mut suspect)?.0;
            }
        }
    }
    // Content validation may reject it: the usual way checks (and reports) it.
    (!suspect).then_some(spare)
}

/// The compound `t` is, when `t` is its one holder.
fn unique(t: &mut Term) -> Option<&mut Compound> {
    match t {
        Term::Compound(c) => Arc::get_mut(c),
        _ => None,
    }
}

/// Writes the instance of pattern `c` under `s` over `spare` (a compound of `c`'s arity that
/// no one else holds), as [`atomic_instance`] builds it: each variable's atomic value, each
/// compound argument written over the spare's argument or else built, each other argument
/// copied. `None` (and `spare` half-written) where `atomic_instance` has no instance or the
/// spare's shape differs; sets `suspect` as `atomic_instance` does.
fn refill(s: &Subst, c: &Compound, spare: &mut Term, depth: u32, suspect: &mut bool) -> Option<()> {
    if depth == 0 {
        return None;
    }
    let into = unique(spare)?;
    if into.args.len() != c.args.len() {
        return None;
    }
    *suspect |= crate::clamr::content::may_reject(c.name);
    into.name = c.name;
    for (a, slot) in c.args.iter().zip(into.args.iter_mut()) {
        match a {
            Term::Var(_) => *slot = atomic_value(s, a)?,
            Term::Compound(ac) => {
                if refill(s, ac, slot, depth - 1, suspect).is_none() {
                    *slot = atomic_instance(s, a, depth - 1, suspect)?.0;
                }
            }
            other => *slot = other.clone(),
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agent::mailbox::tests::term;
    use crate::agent::message::message_content;
    use crate::agent::message::tests::subst;

    /// A spare no one else holds: `text` built anew.
    fn fresh(text: &str) -> Term {
        term(text)
    }

    #[test]
    fn a_refilled_content_is_the_content_built_anew() {
        let s = subst(&[
            ("T", "1"),
            ("R", "4"),
            ("A", "foo"),
            ("U", "T"),
            ("G", "g(a)"),
        ]);
        let moods = [Mood::Declarative, Mood::Imperative, Mood::Interrogative];
        let wrap = |m: Mood, x: &str| match m {
            Mood::Declarative => x.to_string(),
            Mood::Imperative => format!("imp({x})"),
            Mood::Interrogative => format!("int({x})"),
        };
        // The spare: another message of the same shape (other names, other values).
        let cases = [
            ("token(T, R)", "tok(7, 8)"),
            ("token(U, f(R, [A]))", "x(0, h(0, [0]))"),
            ("f(g(a), T, h(b))", "f(g(z), 0, h(z))"),
            ("f(a, T)", "f(k(1, 2), 3)"),
        ];
        for (pattern, spare) in cases {
            for m in moods {
                let want = message_content(m, &term(pattern), &s).expect("valid");
                let got = refilled(m, &term(pattern), &s, fresh(&wrap(m, spare)));
                assert_eq!(got, Some(want), "{pattern} as {m:?} over {spare}");
            }
        }
    }

    #[test]
    fn a_spare_of_another_shape_or_held_elsewhere_is_not_written() {
        let s = subst(&[("T", "1"), ("R", "4"), ("A", "foo"), ("G", "g(a)")]);
        let token = term("token(T, R)");
        // Another arity, another mood's wrapper, an atom.
        for spare in ["token(1, 2, 3)", "int(token(1, 2))", "token"] {
            assert_eq!(refilled(Mood::Imperative, &token, &s, fresh(spare)), None);
        }
        assert_eq!(
            refilled(Mood::Declarative, &token, &s, fresh("token(1, 2, 3)")),
            None
        );
        // The wrapper fits but its content has another arity: built anew inside it.
        let got = refilled(Mood::Imperative, &token, &s, fresh("imp(token(1, 2, 3))"));
        assert_eq!(got, Some(term("imp(token(1, 4))")));
        // Held by someone else (a message not yet read): left as it is.
        let spare = fresh("imp(token(7, 8))");
        let other = spare.clone();
        assert_eq!(refilled(Mood::Imperative, &token, &s, spare), None);
        assert_eq!(other, term("imp(token(7, 8))"));
        // Only an inner part held elsewhere: that part is built anew, the holder's unchanged.
        let spare = fresh("imp(token(7, 8))");
        let inner = spare.args()[0].clone();
        let got = refilled(Mood::Imperative, &token, &s, spare);
        assert_eq!(got, Some(term("imp(token(1, 4))")));
        assert_eq!(inner, term("token(7, 8)"));
        // A value that is no atomic term, or content validation may reject: the usual way.
        let open = term("f(G)");
        assert_eq!(refilled(Mood::Declarative, &open, &s, fresh("f(0)")), None);
        let greater = term("greater(A)");
        assert_eq!(
            refilled(Mood::Declarative, &greater, &s, fresh("x(0)")),
            None
        );
    }
}
