//! Queries placed on the heap once and reused. A rule condition is asked again and again under
//! different bindings of the same variables (`bel(N < 2)` once for each goal `fib(N)`): its
//! cells are built the first time and copied afterwards, with the bound variables' values
//! written into cells of their own that the query's cells refer to.

use super::store::{Cell, Store};
use crate::kr::fxhash::FxHashMap;
use crate::term::{well_known as wk, Subst, Sym, Term};
use std::sync::Arc;

/// Most queries kept: past this the cache starts over (a program has a fixed number of
/// conditions, so only generated queries ever reach it).
const MAX_QUERIES: usize = 512;

/// A query as placed on an empty heap: cells `0..env.len()` for the variables bound from
/// outside, then the query's own cells (referring to those).
struct Prepared {
    /// The query itself: held (never read) so that its address, the cache key, is not reused.
    #[allow(dead_code)]
    query: Term,
    /// The variables bound from outside, in the order of their cells.
    env: Vec<Sym>,
    /// The heap after the environment's cells.
    cells: Vec<Cell>,
    /// The string table the query's cells refer to.
    strs: Vec<Arc<str>>,
    goal: Cell,
    /// The query's variables (the environment's first), as the solver reports answers.
    vars: Vec<(Sym, Cell)>,
}

/// The prepared queries of one engine, by the address of the query term.
#[derive(Default)]
pub(crate) struct Cache {
    queries: FxHashMap<usize, Vec<Prepared>>,
}

impl Clone for Cache {
    /// A copy starts empty (it is only a cache).
    fn clone(&self) -> Cache {
        Cache::default()
    }
}

impl std::fmt::Debug for Cache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Cache({} queries)", self.queries.len())
    }
}

impl Cache {
    /// Places `query` under `env` (ground bindings) on the emptied store, as
    /// `Solver::start` wants it: the goal, the variables, how many of them `env` binds.
    pub fn place(
        &mut self,
        st: &mut Store,
        query: &Term,
        env: &Subst,
    ) -> (Cell, Vec<(Sym, Cell)>, usize) {
        let Term::Compound(c) = query else {
            return place_plain(st, query, env);
        };
        if env.iter().any(|(v, _)| v == wk::UNDERSCORE) {
            return place_plain(st, query, env);
        }
        if self.queries.len() >= MAX_QUERIES {
            self.queries.clear();
        }
        let shapes = self.queries.entry(Arc::as_ptr(c) as usize).or_default();
        let same = |p: &&Prepared| p.env.iter().copied().eq(env.iter().map(|(v, _)| v));
        let k = env.len();
        let (goal, vars) = match shapes.iter().find(same) {
            Some(p) => {
                st.heap.extend((0..k as u32).map(Cell::Ref));
                st.heap.extend_from_slice(&p.cells);
                st.strs.extend(p.strs.iter().cloned());
                (p.goal, p.vars.clone())
            }
            None => {
                let mut vars = Vec::with_capacity(16);
                for (v, _) in env.iter() {
                    st.put_term(&Term::Var(v), &mut vars);
                }
                let goal = st.put_term(query, &mut vars);
                shapes.push(Prepared {
                    query: query.clone(),
                    env: env.iter().map(|(v, _)| v).collect(),
                    cells: st.heap[k..].to_vec(),
                    strs: st.strs.clone(),
                    goal,
                    vars: vars.clone(),
                });
                (goal, vars)
            }
        };
        // The values go into the environment's cells (larger ones after the query's cells).
        let mut none = Vec::new();
        for (i, (_, t)) in env.iter().enumerate() {
            let c = st.put_term(t, &mut none);
            st.heap[i] = c;
        }
        (goal, vars, k)
    }
}

/// Places `query` under `env` (ground bindings) directly: the bound variables' values first,
/// shared wherever the query names them, so the query runs as `env` applied to it without that
/// term being built.
pub(crate) fn place_plain(
    st: &mut Store,
    query: &Term,
    env: &Subst,
) -> (Cell, Vec<(Sym, Cell)>, usize) {
    // Sized for the usual query, so that placing it does not grow the vector step by step.
    let mut vars = Vec::with_capacity(16);
    for (v, t) in env.iter() {
        let c = st.put_term(t, &mut vars);
        vars.push((v, c));
    }
    let bound = vars.len();
    let goal = st.put_term(query, &mut vars);
    (goal, vars, bound)
}

#[cfg(test)]
mod tests {
    use crate::kr::{FactBase, Knowledge, NativeEngine, View};
    use crate::syntax::prolog::Reader;
    use crate::term::{Subst, Sym, Term};

    fn term(r: &mut Reader, text: &str) -> Term {
        r.term(text, 0).expect("term").term
    }

    fn show(answers: &[Subst]) -> Vec<String> {
        answers
            .iter()
            .map(|s| {
                s.iter()
                    .map(|(v, t)| format!("{}={t}", v.name()))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect()
    }

    #[test]
    fn a_query_asked_again_under_other_bindings_answers_as_if_built_anew() {
        let mut r = Reader::new("test");
        let (clauses, _) = r.clauses("twice(X, Y) :- Y is X * 2.", 0);
        let kn = Knowledge::load(&clauses.into_iter().map(|c| c.term).collect::<Vec<_>>())
            .expect("knowledge");
        let mut facts = FactBase::new();
        for f in ["p(1, a)", "p(2, \"s\")", "p(f(b), c)", "p(2, d)"] {
            facts.insert(term(&mut r, f));
        }
        let bases = [&facts];
        let view = View::beliefs(&kn, &bases);
        let q = term(
            &mut r,
            "(p(K, V), twice(N, M), atom_length(\"abc\", L), N == K)",
        );
        let mut e = NativeEngine::new(1);
        let (n, k) = (Sym::intern("N"), Sym::intern("K"));
        for value in ["2", "1", "f(b)", "\"s\"", "2"] {
            let mut env = Subst::new();
            env.bind(n, term(&mut r, value));
            let outcome = |r: crate::kr::KrResult<(Vec<Subst>, bool)>| match r {
                Ok((answers, _)) => show(&answers),
                Err(err) => vec![err.to_string()],
            };
            let reused = outcome(
                e.query_upto_in(&view, &q, &env, usize::MAX)
                    .expect("ground"),
            );
            let fresh = outcome(NativeEngine::new(1).query_upto(&view, &env.apply(&q), usize::MAX));
            assert_eq!(reused, fresh, "N = {value}");
        }
        // Another order of the same variables is another placement.
        let mut env = Subst::new();
        env.bind(k, Term::Int(2));
        env.bind(n, Term::Int(2));
        let (answers, _) = e
            .query_upto_in(&view, &q, &env, usize::MAX)
            .expect("ground")
            .expect("answers");
        assert_eq!(show(&answers), ["V=\"s\" M=4 L=3", "V=d M=4 L=3"]);
    }
}
