//! Substitutions (variable name to term) and syntactic unification over [`Term`]s.
//!
//! This is the light-weight unifier used outside the KR engine (matching action calls against
//! action specs, macro expansion, test conditions). The KR engine has its own binding store.

use super::sym::Sym;
use super::term::Term;
use smallvec::{smallvec, SmallVec};

/// Nesting depth up to which [`Subst::apply`] recurses.
const SHALLOW: usize = 64;

/// True when `new` is `old` itself or an atomic copy of it (cheap: no deep comparison).
fn same(new: &Term, old: &Term) -> bool {
    match (new, old) {
        (Term::Compound(a), Term::Compound(b)) => std::sync::Arc::ptr_eq(a, b),
        (Term::Compound(_), _) | (_, Term::Compound(_)) => false,
        _ => new == old,
    }
}

/// A substitution: bindings from variable names to terms, kept in insertion order so that
/// printing and iteration are deterministic.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Subst {
    bindings: Vec<(Sym, Term)>,
}

impl Subst {
    /// The empty substitution.
    pub fn new() -> Subst {
        Subst::default()
    }

    /// An empty substitution with room for `n` bindings.
    pub fn with_capacity(n: usize) -> Subst {
        Subst {
            bindings: Vec::with_capacity(n),
        }
    }

    /// The term bound to `var`, if any (not dereferenced further).
    pub fn get(&self, var: Sym) -> Option<&Term> {
        self.bindings
            .iter()
            .find(|(v, _)| *v == var)
            .map(|(_, t)| t)
    }

    /// Binds `var` to `term`, replacing an earlier binding.
    pub fn bind(&mut self, var: Sym, term: Term) {
        match self.bindings.iter_mut().find(|(v, _)| *v == var) {
            Some(slot) => slot.1 = term,
            None => self.bindings.push((var, term)),
        }
    }

    /// Binds `var`, which this substitution does not bind yet (no search for a binding to
    /// replace).
    pub fn bind_new(&mut self, var: Sym, term: Term) {
        debug_assert!(self.get(var).is_none());
        self.bindings.push((var, term));
    }

    /// This substitution with the bindings of `more` added (replacing bindings of the same
    /// variables), allocated once.
    pub fn extended(&self, more: &Subst) -> Subst {
        let mut bindings = Vec::with_capacity(self.bindings.len() + more.bindings.len());
        bindings.extend_from_slice(&self.bindings);
        let mut s = Subst { bindings };
        s.extend(more);
        s
    }

    /// Adds the bindings of `more` (replacing bindings of the same variables).
    pub fn extend(&mut self, more: &Subst) {
        for (v, t) in more.iter() {
            self.bind(v, t.clone());
        }
    }

    /// Removes the binding of `var`.
    pub fn unbind(&mut self, var: Sym) {
        self.bindings.retain(|(v, _)| *v != var);
    }

    /// The bindings in insertion order.
    pub fn iter(&self) -> impl Iterator<Item = (Sym, &Term)> {
        self.bindings.iter().map(|(v, t)| (*v, t))
    }

    /// Number of bindings.
    pub fn len(&self) -> usize {
        self.bindings.len()
    }

    /// True when nothing is bound.
    pub fn is_empty(&self) -> bool {
        self.bindings.is_empty()
    }

    /// Keeps only the bindings of the given variables.
    pub fn restrict(&self, vars: &[Sym]) -> Subst {
        Subst {
            bindings: self
                .bindings
                .iter()
                .filter(|(v, _)| vars.contains(v))
                .cloned()
                .collect(),
        }
    }

    /// Follows variable bindings until an unbound variable or a non-variable term.
    pub fn walk<'a>(&'a self, mut t: &'a Term) -> &'a Term {
        while let Term::Var(v) = t {
            // A variable bound to itself ends the chain; it is told by its name alone, without
            // a general term comparison per step.
            match self.get(*v) {
                Some(Term::Var(w)) if w == v => break,
                Some(next) => t = next,
                None => break,
            }
        }
        t
    }

    /// Applies the substitution to `t` completely (bindings are followed transitively).
    pub fn apply(&self, t: &Term) -> Term {
        if self.bindings.is_empty() {
            return t.clone();
        }
        self.apply_shallow(t, 0)
    }

    /// [`Subst::apply`] by recursion while the term is shallow (the usual case: no work
    /// stacks to allocate); sub-terms deeper than [`SHALLOW`] go to the iterative walk.
    fn apply_shallow(&self, t: &Term, depth: usize) -> Term {
        match self.walk(t) {
            Term::Compound(_) if depth >= SHALLOW => self.apply_depth(t, depth),
            w @ Term::Compound(c) => {
                // Arguments the substitution leaves alone are shared, not rebuilt: a new
                // argument vector is only made from the first argument that changes.
                for (i, a) in c.args.iter().enumerate() {
                    let first = self.apply_shallow(a, depth + 1);
                    if same(&first, a) {
                        continue;
                    }
                    let mut args: Vec<Term> = Vec::with_capacity(c.args.len());
                    args.extend(c.args[..i].iter().cloned());
                    args.push(first);
                    args.extend(
                        c.args[i + 1..]
                            .iter()
                            .map(|a| self.apply_shallow(a, depth + 1)),
                    );
                    return Term::compound(c.name, args);
                }
                w.clone()
            }
            other => other.clone(),
        }
    }

    /// The iterative walk behind [`Subst::apply`]. Parts nested deeper than
    /// [`Subst::MAX_APPLY_DEPTH`] are left as they are: only a cyclic binding (possible
    /// without the occurs check, `X = f(X)`) gets there.
    fn apply_depth(&self, t: &Term, depth: usize) -> Term {
        enum W<'a> {
            Visit(&'a Term, usize),
            /// The walked compound, and whether walking left the original term.
            Build(&'a Term, bool),
        }
        let mut work: SmallVec<[W; 16]> = smallvec![W::Visit(t, depth)];
        // Each result with whether it differs from the term it came from.
        let mut out: SmallVec<[(Term, bool); 8]> = SmallVec::new();
        while let Some(w) = work.pop() {
            match w {
                W::Visit(t, d) => match self.walk(t) {
                    w @ Term::Compound(c) if d < Self::MAX_APPLY_DEPTH => {
                        work.push(W::Build(w, !std::ptr::eq(w, t)));
                        work.extend(c.args.iter().rev().map(|a| W::Visit(a, d + 1)));
                    }
                    other => out.push((other.clone(), !std::ptr::eq(other, t))),
                },
                W::Build(w, walked) => {
                    let Term::Compound(c) = w else { continue };
                    let start = out.len() - c.args.len();
                    // Unchanged arguments: share the original term instead of a copy.
                    if out[start..].iter().all(|(_, changed)| !changed) {
                        out.truncate(start);
                        out.push((w.clone(), walked));
                    } else {
                        let args = out.drain(start..).map(|(a, _)| a).collect();
                        out.push((Term::compound(c.name, args), true));
                    }
                }
            }
        }
        out.pop().map_or_else(|| t.clone(), |(r, _)| r)
    }

    /// Nesting depth beyond which [`Subst::apply`] stops following bindings.
    pub const MAX_APPLY_DEPTH: usize = 4_000_000;

    /// Unifies `a` and `b` under this substitution, extending it; on failure the substitution
    /// is left unchanged and `false` is returned.
    pub fn unify(&mut self, a: &Term, b: &Term, occurs_check: bool) -> bool {
        let saved = self.bindings.len();
        let mut snapshot: Option<Vec<(Sym, Term)>> = None;
        let ok = self.unify_inner(a, b, occurs_check, &mut snapshot);
        if !ok {
            match snapshot {
                Some(s) => self.bindings = s,
                None => self.bindings.truncate(saved),
            }
        }
        ok
    }

    fn unify_inner(
        &mut self,
        a: &Term,
        b: &Term,
        occurs_check: bool,
        snapshot: &mut Option<Vec<(Sym, Term)>>,
    ) -> bool {
        let mut stack = vec![(a.clone(), b.clone())];
        while let Some((x, y)) = stack.pop() {
            let x = self.walk(&x).clone();
            let y = self.walk(&y).clone();
            match (&x, &y) {
                (Term::Var(v), Term::Var(w)) if v == w => {}
                (Term::Var(v), other) | (other, Term::Var(v)) => {
                    if occurs_check && self.occurs(*v, other) {
                        return false;
                    }
                    if self.get(*v).is_some() && snapshot.is_none() {
                        *snapshot = Some(self.bindings.clone());
                    }
                    self.bind(*v, other.clone());
                }
                (Term::Compound(p), Term::Compound(q)) => {
                    if p.name != q.name || p.args.len() != q.args.len() {
                        return false;
                    }
                    stack.extend(p.args.iter().cloned().zip(q.args.iter().cloned()));
                }
                _ => {
                    if x != y {
                        return false;
                    }
                }
            }
        }
        true
    }

    fn occurs(&self, v: Sym, t: &Term) -> bool {
        let mut found = false;
        self.apply(t).for_each_var(&mut |w| found |= w == v);
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(args: Vec<Term>) -> Term {
        Term::compound("f", args)
    }

    #[test]
    fn unify_binds_and_applies() {
        let mut s = Subst::new();
        let (x, y) = (Term::var("X"), Term::var("Y"));
        assert!(s.unify(
            &f(vec![x.clone(), Term::atom("b")]),
            &f(vec![Term::atom("a"), y.clone()]),
            false
        ));
        assert_eq!(
            s.apply(&f(vec![x.clone(), y.clone()])),
            f(vec![Term::atom("a"), Term::atom("b")])
        );
    }

    #[test]
    fn failed_unification_leaves_substitution_unchanged() {
        let mut s = Subst::new();
        let x = Term::var("X");
        assert!(!s.unify(
            &f(vec![x.clone(), Term::atom("b")]),
            &f(vec![Term::atom("a"), Term::atom("c")]),
            false
        ));
        assert!(s.is_empty());
    }

    #[test]
    fn occurs_check_is_optional() {
        let x = Term::var("X");
        let mut s = Subst::new();
        assert!(!s.unify(&x, &f(vec![x.clone()]), true));
        assert!(s.unify(&x, &f(vec![x.clone()]), false));
    }
}
