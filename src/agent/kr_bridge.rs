//! Adapter between the agent and the KR layer: the fact bases the agent keeps and the one query
//! entry point it needs. Until the `kr` branch is merged this file carries a small stand-in
//! resolver (facts, knowledge rules, conjunction, negation, unification, comparison,
//! arithmetic), so the interpreter can be built and tested; only this file changes at the merge.

use crate::term::{well_known as wk, Subst, Sym, Term};
use rand_chacha::ChaCha8Rng;
use std::collections::HashSet;
use std::sync::Arc;

/// Resource limits of one query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Maximum number of predicate calls per query.
    pub max_inferences: u64,
    /// Maximum proof depth.
    pub max_depth: u32,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_inferences: 1_000_000,
            max_depth: 10_000,
        }
    }
}

/// An error raised by a query.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KrError(pub String);

impl std::fmt::Display for KrError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// An insertion-ordered set of ground facts.
#[derive(Clone, Debug, Default)]
pub struct FactBase {
    order: Vec<Term>,
    set: HashSet<Term>,
}

impl FactBase {
    /// An empty base.
    pub fn new() -> FactBase {
        FactBase::default()
    }
    /// Adds a fact; false when already present.
    pub fn insert(&mut self, t: Term) -> bool {
        if self.set.insert(t.clone()) {
            self.order.push(t);
            true
        } else {
            false
        }
    }
    /// Removes a fact; false when absent.
    pub fn delete(&mut self, t: &Term) -> bool {
        if self.set.remove(t) {
            self.order.retain(|x| x != t);
            true
        } else {
            false
        }
    }
    /// True when the fact is present.
    pub fn contains(&self, t: &Term) -> bool {
        self.set.contains(t)
    }
    /// Facts in insertion order.
    pub fn iter(&self) -> impl Iterator<Item = &Term> + '_ {
        self.order.iter()
    }
    /// Number of facts.
    pub fn len(&self) -> usize {
        self.order.len()
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }
}

/// Compiled knowledge (shared by every agent of a program).
#[derive(Debug, Default)]
pub struct Knowledge {
    clauses: Vec<(Term, Vec<Term>)>,
}

/// Loads knowledge clauses.
pub fn load_knowledge(clauses: &[Term]) -> Result<Arc<Knowledge>, KrError> {
    let mut k = Knowledge::default();
    for c in clauses {
        if c.is_functor(wk::NECK, 2) {
            let body = c.args()[1].conjuncts().into_iter().cloned().collect();
            k.clauses.push((c.args()[0].clone(), body));
        } else if c.functor().is_some() {
            k.clauses.push((c.clone(), Vec::new()));
        } else {
            return Err(KrError(format!("{c} cannot be a clause")));
        }
    }
    Ok(Arc::new(k))
}

/// Where a query looks: knowledge plus either fact bases (belief view) or one goal's facts.
pub struct View<'a> {
    pub knowledge: &'a Knowledge,
    pub bases: &'a [&'a FactBase],
    pub goal_facts: &'a [Term],
}

/// All answers of `query` in `view`, restricted to the query's variables, without duplicates.
pub fn query(
    view: &View<'_>,
    query: &Term,
    limits: Limits,
    _rng: &mut ChaCha8Rng,
    _out: &mut String,
) -> Result<Vec<Subst>, KrError> {
    let vars = query.vars();
    let mut st = Stub {
        view,
        limits,
        inferences: 0,
        fresh: 0,
    };
    let mut out = Vec::new();
    st.solve(vec![query.clone()], Subst::new(), 0, &mut |s| {
        let mut a = Subst::new();
        for v in &vars {
            let t = s.apply(&Term::Var(*v));
            if t != Term::Var(*v) {
                a.bind(*v, t);
            }
        }
        if !out.contains(&a) {
            out.push(a);
        }
    })?;
    Ok(out)
}

struct Stub<'a, 'b> {
    view: &'b View<'a>,
    limits: Limits,
    inferences: u64,
    fresh: u64,
}

fn num(t: &Term, s: &Subst) -> Result<i64, KrError> {
    let t = s.apply(t);
    match &t {
        Term::Int(i) => Ok(*i),
        Term::Compound(_) if t.args().len() == 2 => {
            let a = num(&t.args()[0], s)?;
            let b = num(&t.args()[1], s)?;
            let name = t.functor().map(|f| f.0.name()).unwrap_or("");
            Ok(match name {
                "+" => a.wrapping_add(b),
                "-" => a.wrapping_sub(b),
                "*" => a.wrapping_mul(b),
                "//" if b != 0 => a / b,
                "mod" if b != 0 => a.rem_euclid(b),
                "max" => a.max(b),
                "min" => a.min(b),
                _ => return Err(KrError(format!("cannot evaluate {t}"))),
            })
        }
        _ => Err(KrError(format!("error(instantiation_error, {t})"))),
    }
}

impl Stub<'_, '_> {
    fn rename(&mut self, head: &Term, body: &[Term]) -> (Term, Vec<Term>) {
        self.fresh += 1;
        let mut s = Subst::new();
        let mut all = head.vars();
        for b in body {
            all.extend(b.vars());
        }
        for v in all {
            s.bind(
                v,
                Term::Var(Sym::intern(&format!("_K{}_{}", self.fresh, v.name()))),
            );
        }
        (s.apply(head), body.iter().map(|b| s.apply(b)).collect())
    }

    fn solve(
        &mut self,
        mut goals: Vec<Term>,
        s: Subst,
        depth: u32,
        k: &mut dyn FnMut(&Subst),
    ) -> Result<(), KrError> {
        let Some(g) = goals.pop() else {
            k(&s);
            return Ok(());
        };
        self.inferences += 1;
        if self.inferences > self.limits.max_inferences {
            return Err(KrError("inference budget exceeded".into()));
        }
        if depth > self.limits.max_depth.min(500) {
            return Err(KrError("proof depth limit exceeded".into()));
        }
        let g = s.apply(&g);
        let name = g.functor().map(|f| (f.0.name(), f.1));
        let args = g.args();
        let simple =
            |ok: bool, this: &mut Self, goals: Vec<Term>, s: Subst, k: &mut dyn FnMut(&Subst)| {
                if ok {
                    this.solve(goals, s, depth + 1, k)
                } else {
                    Ok(())
                }
            };
        match name {
            Some((",", 2)) => {
                goals.push(args[1].clone());
                goals.push(args[0].clone());
                self.solve(goals, s, depth + 1, k)
            }
            Some(("true", 0)) => self.solve(goals, s, depth + 1, k),
            Some(("fail", 0)) | Some(("false", 0)) => Ok(()),
            Some(("not", 1)) | Some(("\\+", 1)) => {
                let mut found = false;
                self.solve(vec![args[0].clone()], s.clone(), depth + 1, &mut |_| {
                    found = true
                })?;
                simple(!found, self, goals, s, k)
            }
            Some(("=", 2)) => {
                let mut s2 = s.clone();
                let ok = s2.unify(&args[0], &args[1], false);
                simple(ok, self, goals, s2, k)
            }
            Some(("\\=", 2)) => {
                let mut s2 = s.clone();
                let ok = !s2.unify(&args[0], &args[1], false);
                simple(ok, self, goals, s, k)
            }
            Some(("==", 2)) => simple(args[0] == args[1], self, goals, s, k),
            Some(("\\==", 2)) => simple(args[0] != args[1], self, goals, s, k),
            Some(("is", 2)) => {
                let v = num(&args[1], &s)?;
                let mut s2 = s.clone();
                let ok = s2.unify(&args[0], &Term::Int(v), false);
                simple(ok, self, goals, s2, k)
            }
            Some((op @ ("<" | ">" | "=<" | ">=" | "=:=" | "=\\="), 2)) => {
                let (a, b) = (num(&args[0], &s)?, num(&args[1], &s)?);
                let ok = match op {
                    "<" => a < b,
                    ">" => a > b,
                    "=<" => a <= b,
                    ">=" => a >= b,
                    "=:=" => a == b,
                    _ => a != b,
                };
                simple(ok, self, goals, s, k)
            }
            Some(_) => {
                let view = self.view;
                let facts = view
                    .bases
                    .iter()
                    .flat_map(|b| b.iter())
                    .chain(view.goal_facts.iter());
                for f in facts {
                    let mut s2 = s.clone();
                    if s2.unify(&g, f, false) {
                        self.solve(goals.clone(), s2, depth + 1, k)?;
                    }
                }
                for (h, b) in &view.knowledge.clauses {
                    if h.functor() != g.functor() {
                        continue;
                    }
                    let (h, b) = self.rename(h, b);
                    let mut s2 = s.clone();
                    if s2.unify(&g, &h, false) {
                        let mut gs = goals.clone();
                        gs.extend(b.into_iter().rev());
                        self.solve(gs, s2, depth + 1, k)?;
                    }
                }
                Ok(())
            }
            None => Err(KrError(format!("{g} is not callable"))),
        }
    }
}
