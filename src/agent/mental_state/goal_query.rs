//! Queries about goals: a goal condition prepared once for all the goals it is asked of, and
//! goal facts matched against it without the engine.

use super::{all_vars, plain_ground, Goal, Knowledge};
use crate::kr::native::code::Key;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};

/// A query about goals, prepared once for all the goals it is asked of.
pub struct GoalQuery<'q> {
    /// The query (under `given`).
    pub query: &'q Term,
    /// Ground values of some of the query's variables, read in place instead of building the
    /// query's instance (see [`GoalQuery::under`]).
    given: Option<&'q Subst>,
    /// Its predicate, when knowledge does not define it (then only goal facts or built-ins
    /// answer it).
    key: Option<(crate::term::Sym, usize)>,
    /// True when nothing but goal facts can answer it: neither knowledge nor a built-in or
    /// control construct resolves its predicate (an undefined predicate fails).
    pub only_facts: bool,
}

impl<'q> GoalQuery<'q> {
    /// Prepares `q` against `knowledge`.
    pub fn new(knowledge: &Knowledge, q: &'q Term) -> GoalQuery<'q> {
        let key = q.functor().filter(|k| !knowledge.defines(k.0, k.1));
        GoalQuery {
            query: q,
            given: None,
            key,
            only_facts: key.is_some_and(|k| !knowledge.resolves(k.0, k.1)),
        }
    }

    /// Prepares the instance of `q` under `theta` without building it, when `q` is not a
    /// variable and `theta` binds its variables to ground terms only (then matching a goal fact
    /// against `q` with `theta`'s values read in place is matching it against the instance);
    /// `None` otherwise.
    pub fn under(knowledge: &Knowledge, q: &'q Term, theta: &'q Subst) -> Option<GoalQuery<'q>> {
        let plain = |v: Sym| theta.get(v).is_none_or(plain_ground);
        // A query of atomic arguments (the usual `fib(N)`) is checked without a walk.
        let flat = q.args().iter().all(|a| match a {
            Term::Var(v) => plain(*v),
            Term::Compound(_) => false,
            _ => true,
        });
        if matches!(q, Term::Var(_)) || !(flat || all_vars(q, plain)) {
            return None;
        }
        let mut gq = GoalQuery::new(knowledge, q);
        gq.given = Some(theta);
        Some(gq)
    }

    /// The query's instance (built only when `given` is used).
    pub fn instance(&self) -> std::borrow::Cow<'q, Term> {
        match self.given {
            Some(theta) => std::borrow::Cow::Owned(theta.apply(self.query)),
            None => std::borrow::Cow::Borrowed(self.query),
        }
    }

    /// The index key of the instance's first argument (`None`: no argument, or a variable).
    pub(crate) fn first_key(&self) -> Option<Key> {
        let first = self.query.args().first()?;
        match (first, self.given) {
            (Term::Var(v), Some(theta)) => theta.get(*v).and_then(Key::of_term),
            _ => Key::of_term(first),
        }
    }

    /// Matches the instance against the ground goal fact `fact`, binding its variables (but
    /// `_`) in reading order into `s`; false when they differ.
    pub fn match_fact(&self, fact: &Term, s: &mut Subst) -> bool {
        match_fact_under(self.query, self.given, fact, s)
    }

    /// The predicate of the query when only goal facts answer it (a goal without facts of it
    /// has no answer).
    pub fn fact_predicate(&self) -> Option<(crate::term::Sym, usize)> {
        self.key.filter(|_| self.only_facts)
    }

    /// The answers of a one-literal query over a goal's facts by plain unification, when the
    /// goal has facts of the query's predicate and knowledge does not define it (then the
    /// engine would only match those facts too). `None`: ask the engine.
    pub(super) fn facts_only(&self, g: &Goal) -> Option<Vec<Subst>> {
        Some(
            self.matching_facts(g)?
                .into_iter()
                .map(|(a, _)| a)
                .collect(),
        )
    }

    /// [`GoalQuery::facts_only`] with the goal fact each answer matched (the query
    /// instantiated by the answer, when the query has no anonymous `_` of its own).
    pub fn matching_facts<'g>(&self, g: &'g Goal) -> Option<SmallVec<[(Subst, &'g Term); 1]>> {
        let key = self.key?;
        let mut of_key = false;
        let mut out: SmallVec<[(Subst, &Term); 1]> = SmallVec::new();
        for f in g.facts.iter().filter(|f| f.functor() == Some(key)) {
            of_key = true;
            let mut a = Subst::new();
            if self.match_fact(f, &mut a) && !out.iter().any(|(b, _)| *b == a) {
                out.push((a, f));
            }
        }
        of_key.then_some(out)
    }
}

/// `match_fact_under` with nothing given.
#[cfg(test)]
fn match_fact(pattern: &Term, fact: &Term, s: &mut Subst) -> bool {
    match_fact_under(pattern, None, fact, s)
}

/// Matches the instance of `pattern` under `given` (which binds variables to ground terms only)
/// against the ground `fact`, binding the pattern's other variables (but `_`, which matches
/// anything) in reading order, as the engine's answers do; false when they differ. `given` is
/// read in place: a variable it binds matches what equals its value.
fn match_fact_under(pattern: &Term, given: Option<&Subst>, fact: &Term, s: &mut Subst) -> bool {
    if let Some(matched) = match_flat(pattern, given, fact, s) {
        return matched;
    }
    // Argument lists still to match, the innermost last (leftmost argument first).
    let mut work: SmallVec<[(&[Term], &[Term]); 8]> =
        smallvec![(std::slice::from_ref(pattern), std::slice::from_ref(fact))];
    while let Some((ps, fs)) = work.last_mut() {
        let (Some((p, p_rest)), Some((f, f_rest))) = (ps.split_first(), fs.split_first()) else {
            work.pop();
            continue;
        };
        (*ps, *fs) = (p_rest, f_rest);
        match (p, f) {
            (Term::Compound(p), Term::Compound(f)) => {
                if p.name != f.name || p.args.len() != f.args.len() {
                    return false;
                }
                work.push((&p.args, &f.args));
            }
            _ => {
                if !match_leaf(p, given, f, s) {
                    return false;
                }
            }
        }
    }
    true
}

/// [`match_fact_under`] of a pattern whose arguments have no compound term (`fib(N)`,
/// `at(a, X)`): one pass over the arguments; `None` for other patterns.
fn match_flat(pattern: &Term, given: Option<&Subst>, fact: &Term, s: &mut Subst) -> Option<bool> {
    let (Term::Compound(p), Term::Compound(f)) = (pattern, fact) else {
        return None;
    };
    if p.args.iter().any(|a| matches!(a, Term::Compound(_))) {
        return None;
    }
    if p.name != f.name || p.args.len() != f.args.len() {
        return Some(false);
    }
    Some(
        p.args
            .iter()
            .zip(f.args.iter())
            .all(|(p, f)| match_leaf(p, given, f, s)),
    )
}

/// [`match_fact_under`] of a pattern that is a variable or atomic against a fact's term.
#[inline]
fn match_leaf(p: &Term, given: Option<&Subst>, f: &Term, s: &mut Subst) -> bool {
    match p {
        Term::Var(v) if *v == wk::UNDERSCORE => true,
        Term::Var(v) => match given.and_then(|g| g.get(*v)).or_else(|| s.get(*v)) {
            Some(bound) => bound == f,
            None => {
                s.bind(*v, f.clone());
                true
            }
        },
        _ => p == f,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn term(text: &str) -> Term {
        let mut r = crate::syntax::prolog::Reader::new("test");
        r.term(text, 0).expect("term").term
    }

    fn matched(pattern: &str, fact: &str) -> Option<String> {
        let mut s = Subst::new();
        match_fact(&term(pattern), &term(fact), &mut s).then(|| {
            s.iter()
                .map(|(v, t)| format!("{}={t}", v.name()))
                .collect::<Vec<_>>()
                .join(" ")
        })
    }

    #[test]
    fn goal_facts_match_binding_variables_in_reading_order() {
        assert_eq!(
            matched("p(X, f(Y, Z), X)", "p(a, f(g(b), 1), a)").as_deref(),
            Some("X=a Y=g(b) Z=1")
        );
        assert_eq!(matched("p(X, f(Y), X)", "p(a, f(b), c)"), None);
        assert_eq!(matched("p(X, 2)", "p(a, 2.0)"), None);
        assert_eq!(matched("p(X)", "q(a)"), None);
        // The reader names each `_` apart; a bare `_` matches anything, as in the engine.
        assert_eq!(
            matched("p(_, _)", "p(a, b)").as_deref(),
            Some("_G1=a _G2=b")
        );
        let bare = Term::compound("p", vec![Term::Var(wk::UNDERSCORE); 2]);
        let mut s = Subst::new();
        assert!(match_fact(&bare, &term("p(a, b)"), &mut s) && s.is_empty());
    }

    #[test]
    fn a_goal_query_under_ground_bindings_answers_as_its_instance() {
        let kn = Knowledge::load(&[]).expect("knowledge");
        let goal = Goal::new(term("(p(a, f(1), b), p(c, f(2), a), q(f(1)), q(2))"));
        let cases: [(&str, &[(&str, &str)]); 6] = [
            ("p(X, Y, Z)", &[("Y", "f(1)")]),
            ("p(X, f(W), Z)", &[("W", "2"), ("V", "x")]),
            ("q(Y)", &[("Y", "f(1)")]),
            ("p(X, Y, X)", &[("X", "a")]),
            ("p(X, Y, Z)", &[("X", "c"), ("Z", "a")]),
            ("p(_, f(N), _)", &[("N", "3")]),
        ];
        for (q, binds) in cases {
            let q = term(q);
            let mut theta = Subst::new();
            for (v, t) in binds {
                theta.bind(Sym::intern(v), term(t));
            }
            let under = GoalQuery::under(&kn, &q, &theta).expect("ground bindings");
            let inst = theta.apply(&q);
            let built = GoalQuery::new(&kn, &inst);
            assert_eq!(under.first_key(), built.first_key(), "{q}");
            let answers = |gq: &GoalQuery<'_>| gq.facts_only(&goal);
            assert_eq!(answers(&under), answers(&built), "{q} under {theta:?}");
        }
        // Bindings that are not ground, or hold a float, are not read in place.
        let q = term("q(Y)");
        for t in ["g(Z)", "1.5", "f(2.0)"] {
            let mut theta = Subst::new();
            theta.bind(Sym::intern("Y"), term(t));
            assert!(GoalQuery::under(&kn, &q, &theta).is_none(), "{t}");
        }
        assert!(GoalQuery::under(&kn, &term("X"), &Subst::new()).is_none());
    }
}
