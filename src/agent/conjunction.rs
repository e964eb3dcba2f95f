//! Belief conditions answered without the engine: a conjunction of fact patterns (of
//! predicates only facts answer), negated fact patterns, `is/2`, integer comparisons and
//! `=`/`\=` over atomic values, run left to right with backtracking exactly as the engine
//! would, so the answers, their order and their number are the engine's. A condition is
//! analysed once ([`Plan::prepare`], kept in its literal's [`PlanCell`]); anything the plan
//! cannot decide at run time (an unbound arithmetic operand, an overflow, a float, a
//! non-ground fact, more work than a small budget) hands the WHOLE query to the engine, which
//! then answers or raises its usual error.

use super::kr_bridge::{FactBase, Knowledge};
use super::lookup::{size_if_ground, MAX_CANDIDATES, MAX_CELLS};
use super::mailbox::{is_mail_predicate, Arrived};
use super::mental_state::MentalState;
use crate::kr::native::code::Key;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};
use std::sync::{Arc, OnceLock, Weak};

mod batch;
mod run;

pub use batch::Batch;

/// The answers of a plan: mostly none or one, kept inline.
pub type Answers = SmallVec<[Subst; 1]>;

/// Most conjuncts a plan takes (its run recurses once per conjunct).
const MAX_GOALS: usize = 16;
/// Most variables a plan takes (a run keeps their values in a fixed array).
const MAX_VARS: usize = 16;
/// Deepest arithmetic expression a plan evaluates (by recursion).
const MAX_EXPR_DEPTH: usize = 8;
/// Deepest pattern a plan instantiates for a lookup by hash (by recursion).
const MAX_INSTANCE_DEPTH: usize = 32;

/// An arithmetic comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cmp {
    Lt,
    Gt,
    Le,
    Ge,
    Eq,
    Ne,
}

/// One conjunct of a plan, its variables numbered (a variable's register is its place in
/// the plan's [`Plan::vars`]).
#[derive(Debug)]
enum Step {
    /// `true`.
    True,
    /// A fact pattern matched against the fact bases.
    Fact(Pattern),
    /// `not(P)` / `\+ P` of a fact pattern: no fact matches.
    Absent(Pattern),
    /// `Lhs is Expr` (the left side a variable or an integer).
    Is(Arg, Expr),
    /// An arithmetic comparison of two expressions.
    Compare(Cmp, Expr, Expr),
    /// `A = B` of variables, atoms and integers.
    Unify(Arg, Arg),
    /// `A \= B` of variables, atoms and integers.
    Differ(Arg, Arg),
}

/// A part of a conjunct: a variable's register, `_`, a compound of parts or any other term.
#[derive(Debug)]
enum Arg {
    Reg(usize),
    Anon,
    Compound(Sym, Vec<Arg>),
    Const(Term),
}

/// An integer expression of a plan.
#[derive(Debug)]
enum Expr {
    Int(i64),
    Reg(usize),
    Neg(Box<Expr>),
    Bin(Op, Box<Expr>, Box<Expr>),
    /// A variable and an integer under an operator (`N - 1`, the usual case): evaluated
    /// without a recursion into its operands.
    RegInt(Op, usize, i64),
}

/// A fact pattern of a plan.
#[derive(Debug)]
struct Pattern {
    name: Sym,
    arity: usize,
    args: Vec<Arg>,
    /// The pattern as written (its variables are the plan's): what a lookup by hash hashes.
    term: Term,
    /// Looked up by hash once its instance is ground: it has a compound argument (which the
    /// fact index does not narrow) and is no mail fact (the mailbox may hold open messages,
    /// which would unify with it).
    by_hash: bool,
}

/// A belief query analysed for answering without the engine.
#[derive(Debug)]
pub struct Plan {
    steps: Vec<Step>,
    /// The query's variables in the order of their first occurrence: the order in which the
    /// engine reports their bindings.
    vars: Vec<Sym>,
}

/// The plan of one condition literal, made on first use for the agent knowledge it was made
/// with (a literal asked with other knowledge is not planned).
#[derive(Default)]
pub struct PlanCell(OnceLock<(Weak<Knowledge>, Option<Arc<Plan>>)>);

impl Clone for PlanCell {
    fn clone(&self) -> PlanCell {
        PlanCell(self.0.clone())
    }
}

impl std::fmt::Debug for PlanCell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("PlanCell")
    }
}

impl PartialEq for PlanCell {
    /// A cache: never part of what a literal is.
    fn eq(&self, _: &PlanCell) -> bool {
        true
    }
}

impl PlanCell {
    /// The plan of `query` under `kn` (made now if this is the first call); `None` when the
    /// query has none, or this cell was filled for other knowledge.
    pub fn get(&self, query: &Term, kn: &Arc<Knowledge>) -> Option<&Plan> {
        let (owner, plan) = self
            .0
            .get_or_init(|| (Arc::downgrade(kn), Plan::prepare(query, kn).map(Arc::new)));
        if !std::ptr::eq(owner.as_ptr(), Arc::as_ptr(kn)) {
            return None;
        }
        plan.as_deref()
    }
}

impl Plan {
    /// The plan of `query` under the knowledge `kn`; `None` when some conjunct is not one a
    /// plan decides (a predicate knowledge or a built-in answers, a float, a control construct).
    pub fn prepare(query: &Term, kn: &Knowledge) -> Option<Plan> {
        let parts = query.conjuncts();
        if parts.len() > MAX_GOALS {
            return None;
        }
        let vars = vars_in_order(query);
        // A register each in a run.
        if vars.len() > MAX_VARS {
            return None;
        }
        let steps = parts
            .iter()
            .map(|p| step(p, kn, &vars))
            .collect::<Option<Vec<_>>>()?;
        Some(Plan { steps, vars })
    }

    /// The first `cap` answers of the plan's query under `theta` in the fact bases of `ms`
    /// (each binding the query's variables `theta` leaves free, in the engine's order) and
    /// whether `cap` stopped them; `None`: ask the engine.
    pub fn answers(&self, ms: &MentalState, theta: &Subst, cap: usize) -> Option<(Answers, bool)> {
        if !ms.native_roomy() {
            return None;
        }
        let (bases, arrived) = ms.plan_bases();
        run::answers(self, &bases, arrived, theta, cap)
    }

    /// The predicate of the plan's first conjunct when it is a fact pattern (a predicate only
    /// facts answer, matched before anything else runs).
    pub fn first_fact(&self) -> Option<(Sym, usize)> {
        match self.steps.first()? {
            Step::Fact(p) => Some((p.name, p.arity)),
            _ => None,
        }
    }

    /// [`Plan::answers`] over the fact bases `bases` (the caller checked the limits).
    pub fn answers_in(
        &self,
        bases: &[&FactBase],
        theta: &Subst,
        cap: usize,
    ) -> Option<(Vec<Subst>, bool)> {
        run::answers(self, bases, Arrived::default(), theta, cap)
            .map(|(found, cut)| (found.into_vec(), cut))
    }
}

/// The step of conjunct `t` (whose variables are `vars`); `None` when a plan cannot take it
/// (a predicate knowledge or a built-in answers, a float, a control construct).
fn step(t: &Term, kn: &Knowledge, vars: &[Sym]) -> Option<Step> {
    let (name, arity) = t.functor()?;
    let args = t.args();
    let side = |a: &Term| arg(a, vars, 0);
    Some(match (name, arity) {
        (wk::TRUE, 0) => Step::True,
        (wk::NOT | wk::NAF, 1) => Step::Absent(pattern(&args[0], kn, vars)?),
        (wk::IS, 2) if matches!(args[0], Term::Var(_) | Term::Int(_)) => {
            Step::Is(side(&args[0])?, expr(&args[1], vars, 0)?)
        }
        (wk::EQUALS, 2) if atomic_side(&args[0]) && atomic_side(&args[1]) => {
            Step::Unify(side(&args[0])?, side(&args[1])?)
        }
        (_, 2) if name.name() == "\\=" && atomic_side(&args[0]) && atomic_side(&args[1]) => {
            Step::Differ(side(&args[0])?, side(&args[1])?)
        }
        (_, 2) if comparison(name).is_some() => Step::Compare(
            comparison(name)?,
            expr(&args[0], vars, 0)?,
            expr(&args[1], vars, 0)?,
        ),
        _ => Step::Fact(pattern(t, kn, vars)?),
    })
}

/// `t` as a fact pattern: a predicate only facts answer, and no float.
fn pattern(t: &Term, kn: &Knowledge, vars: &[Sym]) -> Option<Pattern> {
    let (name, arity) = t.functor()?;
    if kn.resolves(name, arity) || has_float(t) {
        return None;
    }
    let mail = is_mail_predicate(name, arity);
    Some(Pattern {
        name,
        arity,
        args: t
            .args()
            .iter()
            .map(|a| arg(a, vars, 1))
            .collect::<Option<_>>()?,
        term: t.clone(),
        by_hash: !mail && t.args().iter().any(|a| matches!(a, Term::Compound(_))),
    })
}

/// The term `t` (at `depth`) with its variables as registers; `None` when deeper than
/// [`MAX_INSTANCE_DEPTH`] (by recursion).
fn arg(t: &Term, vars: &[Sym], depth: usize) -> Option<Arg> {
    if depth > MAX_INSTANCE_DEPTH {
        return None;
    }
    Some(match t {
        Term::Var(v) if *v == wk::UNDERSCORE => Arg::Anon,
        Term::Var(v) => Arg::Reg(vars.iter().position(|w| w == v)?),
        Term::Compound(c) => Arg::Compound(
            c.name,
            c.args
                .iter()
                .map(|a| arg(a, vars, depth + 1))
                .collect::<Option<_>>()?,
        ),
        t => Arg::Const(t.clone()),
    })
}

/// True for a side of `=`/`\=` a plan compares: a variable, an atom or an integer.
fn atomic_side(t: &Term) -> bool {
    matches!(t, Term::Var(_) | Term::Atom(_) | Term::Int(_))
}

/// The comparison named `name`, if it is one.
fn comparison(name: Sym) -> Option<Cmp> {
    Some(match name.name() {
        "<" => Cmp::Lt,
        ">" => Cmp::Gt,
        "=<" => Cmp::Le,
        ">=" => Cmp::Ge,
        "=:=" => Cmp::Eq,
        "=\\=" => Cmp::Ne,
        _ => return None,
    })
}

/// The integer operator of `name/arity` a plan evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Add,
    Sub,
    Mul,
    IntDiv,
    Mod,
    Neg,
}

fn operator(name: Sym, arity: usize) -> Option<Op> {
    Some(match (name, arity) {
        (wk::PLUS, 2) => Op::Add,
        (wk::MINUS, 2) => Op::Sub,
        (wk::STAR, 2) => Op::Mul,
        (wk::MINUS, 1) => Op::Neg,
        _ => match (name.name(), arity) {
            ("//", 2) => Op::IntDiv,
            ("mod", 2) => Op::Mod,
            _ => return None,
        },
    })
}

/// The expression `t` a plan evaluates: integers and variables under [`operator`]s, at most
/// [`MAX_EXPR_DEPTH`] deep (by recursion); `None` for anything else.
fn expr(t: &Term, vars: &[Sym], depth: usize) -> Option<Expr> {
    if depth > MAX_EXPR_DEPTH {
        return None;
    }
    match t {
        Term::Int(i) => Some(Expr::Int(*i)),
        Term::Var(v) if *v != wk::UNDERSCORE => Some(Expr::Reg(vars.iter().position(|w| w == v)?)),
        Term::Compound(c) => {
            let op = operator(c.name, c.args.len())?;
            let x = Box::new(expr(&c.args[0], vars, depth + 1)?);
            match op {
                Op::Neg => Some(Expr::Neg(x)),
                _ => Some(match (*x, expr(&c.args[1], vars, depth + 1)?) {
                    (Expr::Reg(k), Expr::Int(i)) => Expr::RegInt(op, k, i),
                    (x, y) => Expr::Bin(op, Box::new(x), Box::new(y)),
                }),
            }
        }
        _ => None,
    }
}

/// True when `t` has a float anywhere.
fn has_float(t: &Term) -> bool {
    let mut stack: SmallVec<[&Term; 16]> = smallvec![t];
    while let Some(t) = stack.pop() {
        match t {
            Term::Float(_) => return true,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    false
}

/// The variables of `t` (not `_`) in the order of their first occurrence, depth first and
/// left to right: the order in which the engine places them.
fn vars_in_order(t: &Term) -> Vec<Sym> {
    let mut out = Vec::new();
    let mut stack: SmallVec<[&Term; 16]> = smallvec![t];
    while let Some(t) = stack.pop() {
        match t {
            Term::Var(v) if *v != wk::UNDERSCORE && !out.contains(v) => out.push(*v),
            Term::Compound(c) => stack.extend(c.args.iter().rev()),
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn term(text: &str) -> Term {
        let mut r = crate::syntax::prolog::Reader::new("test");
        r.term(text, 0).expect("term").term
    }

    fn knowledge(text: &str) -> Arc<Knowledge> {
        let mut r = crate::syntax::prolog::Reader::new("test");
        let (clauses, _) = r.clauses(text, 0);
        Knowledge::load(&clauses.into_iter().map(|c| c.term).collect::<Vec<_>>())
            .expect("knowledge")
    }

    #[test]
    fn open_mail_is_left_to_the_engine_even_for_a_ground_pattern() {
        let mut mail = FactBase::new();
        mail.insert(term("received(a, int(at(_, red)))"));
        let kn = knowledge("k(1).");
        for q in [
            "received(a, int(at(b, red)))",
            "received(S, int(at(X, red)))",
        ] {
            let plan = Plan::prepare(&term(q), &kn).expect("planned");
            assert!(plan.answers_in(&[&mail], &Subst::new(), 9).is_none(), "{q}");
        }
        // Beliefs are ground: a ground pattern with a compound argument is looked up by hash.
        let mut beliefs = FactBase::new();
        beliefs.insert(term("seen(f(1), 2)"));
        let plan = Plan::prepare(&term("seen(f(1), 2), not(seen(f(2), 2))"), &kn).expect("plan");
        let (found, cut) = plan
            .answers_in(&[&beliefs, &beliefs], &Subst::new(), 9)
            .expect("answered");
        assert_eq!((found.len(), cut), (2, false));
    }

    #[test]
    fn a_plan_cell_serves_only_the_knowledge_it_was_made_for() {
        let (k1, k2) = (knowledge("k(1)."), knowledge("p(X) :- k(X)."));
        let q = term("p(X)");
        let cell = PlanCell::default();
        assert!(cell.get(&q, &k1).is_some());
        // `p/1` is a rule under `k2`: the plan made for `k1` must not answer for it.
        assert!(cell.get(&q, &k2).is_none());
        assert!(PlanCell::default().get(&q, &k2).is_none());
    }
}
