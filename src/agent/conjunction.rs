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
use super::mailbox::is_mail_predicate;
use super::mental_state::MentalState;
use crate::kr::native::code::Key;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};
use std::sync::{Arc, OnceLock, Weak};

/// Most conjuncts a plan takes (its run recurses once per conjunct).
const MAX_GOALS: usize = 16;
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

/// One conjunct of a plan.
#[derive(Debug)]
enum Step {
    /// `true`.
    True,
    /// A fact pattern matched against the fact bases.
    Fact(Pattern),
    /// `not(P)` / `\+ P` of a fact pattern: no fact matches.
    Absent(Pattern),
    /// `Lhs is Expr` (the left side a variable or an integer).
    Is(Term, Term),
    /// An arithmetic comparison of two expressions.
    Compare(Cmp, Term, Term),
    /// `A = B` of variables, atoms and integers.
    Unify(Term, Term),
    /// `A \= B` of variables, atoms and integers.
    Differ(Term, Term),
}

/// A fact pattern of a plan.
#[derive(Debug)]
struct Pattern {
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
        let steps = parts
            .iter()
            .map(|p| step(p, kn))
            .collect::<Option<Vec<_>>>()?;
        let vars = vars_in_order(query);
        // One bit each in a run's `given`.
        if vars.len() > 64 {
            return None;
        }
        Some(Plan { steps, vars })
    }

    /// The first `cap` answers of the plan's query under `theta` in the fact bases of `ms`
    /// (each binding the query's variables `theta` leaves free, in the engine's order) and
    /// whether `cap` stopped them; `None`: ask the engine.
    pub fn answers(
        &self,
        ms: &MentalState,
        theta: &Subst,
        cap: usize,
    ) -> Option<(Vec<Subst>, bool)> {
        if !ms.native_roomy() {
            return None;
        }
        self.answers_in(&ms.bases(), theta, cap)
    }

    /// [`Plan::answers`] over the fact bases `bases` (the caller checked the limits).
    pub fn answers_in(
        &self,
        bases: &[&FactBase],
        theta: &Subst,
        cap: usize,
    ) -> Option<(Vec<Subst>, bool)> {
        let mut run = Run {
            plan: self,
            bases,
            vals: SmallVec::with_capacity(self.vars.len()),
            given: 0,
            trail: SmallVec::new(),
            steps: 0,
            cells: 0,
            cap,
            out: Vec::new(),
        };
        for (i, v) in self.vars.iter().enumerate() {
            let val = theta.get(*v);
            if let Some(t) = val {
                if matches!(t, Term::Compound(_) | Term::Var(_)) && !t.is_ground() {
                    return None;
                }
                run.given |= 1 << i;
            }
            run.vals.push(val.map(Val::T));
        }
        match run.solve(0) {
            // As the engine reports it: stopped when `cap` answers were reached.
            Ok(()) | Err(Halt::Cap) => {
                let cut = run.out.len() >= cap;
                Some((run.out, cut))
            }
            Err(Halt::Bail) => None,
        }
    }
}

/// The step of conjunct `t`; `None` when a plan cannot take it.
fn step(t: &Term, kn: &Knowledge) -> Option<Step> {
    let (name, arity) = t.functor()?;
    let args = t.args();
    Some(match (name, arity) {
        (wk::TRUE, 0) => Step::True,
        (wk::NOT | wk::NAF, 1) => Step::Absent(pattern(&args[0], kn)?),
        (wk::IS, 2) if matches!(args[0], Term::Var(_) | Term::Int(_)) => {
            expr(&args[1], 0)?;
            Step::Is(args[0].clone(), args[1].clone())
        }
        (wk::EQUALS, 2) if atomic_side(&args[0]) && atomic_side(&args[1]) => {
            Step::Unify(args[0].clone(), args[1].clone())
        }
        (_, 2) if name.name() == "\\=" && atomic_side(&args[0]) && atomic_side(&args[1]) => {
            Step::Differ(args[0].clone(), args[1].clone())
        }
        (_, 2) if comparison(name).is_some() => {
            expr(&args[0], 0)?;
            expr(&args[1], 0)?;
            Step::Compare(comparison(name)?, args[0].clone(), args[1].clone())
        }
        _ => Step::Fact(pattern(t, kn)?),
    })
}

/// `t` as a fact pattern: a predicate only facts answer, and no float.
fn pattern(t: &Term, kn: &Knowledge) -> Option<Pattern> {
    let (name, arity) = t.functor()?;
    if kn.resolves(name, arity) || has_float(t) {
        return None;
    }
    let mail = is_mail_predicate(name, arity);
    Some(Pattern {
        term: t.clone(),
        by_hash: !mail && t.args().iter().any(|a| matches!(a, Term::Compound(_))),
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
#[derive(Clone, Copy, PartialEq, Eq)]
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

/// Checks that `t` is an expression a plan evaluates: integers and variables under
/// [`operator`]s, at most [`MAX_EXPR_DEPTH`] deep.
fn expr(t: &Term, depth: usize) -> Option<()> {
    if depth > MAX_EXPR_DEPTH {
        return None;
    }
    match t {
        Term::Int(_) => Some(()),
        Term::Var(v) if *v != wk::UNDERSCORE => Some(()),
        Term::Compound(c) => {
            operator(c.name, c.args.len())?;
            c.args.iter().try_for_each(|a| expr(a, depth + 1))
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

/// A variable's value during a run: a ground term (of `theta`, a fact or the query) or the
/// integer an `is/2` computed.
#[derive(Clone, Copy, Debug)]
enum Val<'a> {
    T(&'a Term),
    I(i64),
}

impl Val<'_> {
    fn int(self) -> Option<i64> {
        match self {
            Val::I(i) | Val::T(&Term::Int(i)) => Some(i),
            _ => None,
        }
    }

    fn term(self) -> Term {
        match self {
            Val::T(t) => t.clone(),
            Val::I(i) => Term::Int(i),
        }
    }

    /// The index key of the value; `None` for a float (whose key does not decide a match).
    fn key(self) -> Option<Key> {
        match self {
            Val::I(i) => Some(Key::Int(i)),
            Val::T(Term::Float(_)) => None,
            Val::T(t) => Key::of_term(t),
        }
    }
}

/// Why a run stopped early.
enum Halt {
    /// `cap` answers found.
    Cap,
    /// Something the plan does not decide: the engine answers the query.
    Bail,
}

type Go = Result<(), Halt>;

/// One run of a plan: the variables' values (by the plan's order), the trail of those bound
/// since, and the budget spent.
struct Run<'a> {
    plan: &'a Plan,
    bases: &'a [&'a FactBase],
    vals: SmallVec<[Option<Val<'a>>; 12]>,
    /// The variables `theta` binds (a bit each), left out of the answers.
    given: u64,
    trail: SmallVec<[usize; 16]>,
    steps: usize,
    cells: usize,
    cap: usize,
    out: Vec<Subst>,
}

impl<'a> Run<'a> {
    /// Runs conjuncts `i..` under the values bound so far, adding each answer.
    fn solve(&mut self, i: usize) -> Go {
        let plan = self.plan;
        let Some(step) = plan.steps.get(i) else {
            return self.answer();
        };
        self.tick()?;
        match step {
            Step::True => self.solve(i + 1),
            Step::Fact(p) => self.each_match(p, &mut |run| run.solve(i + 1)),
            Step::Absent(p) => {
                let mut found = false;
                self.each_match(p, &mut |_| {
                    found = true;
                    Err(Halt::Cap)
                })
                .or_else(|h| if found { Ok(()) } else { Err(h) })?;
                if found {
                    Ok(())
                } else {
                    self.solve(i + 1)
                }
            }
            Step::Is(lhs, e) => {
                let v = self.eval(e)?;
                self.bind_int(lhs, v, i)
            }
            Step::Compare(op, a, b) => {
                let (a, b) = (self.eval(a)?, self.eval(b)?);
                let holds = match op {
                    Cmp::Lt => a < b,
                    Cmp::Gt => a > b,
                    Cmp::Le => a <= b,
                    Cmp::Ge => a >= b,
                    Cmp::Eq => a == b,
                    Cmp::Ne => a != b,
                };
                if holds {
                    self.solve(i + 1)
                } else {
                    Ok(())
                }
            }
            Step::Unify(a, b) => self.unify_atomic(a, b, i),
            Step::Differ(a, b) => match (self.side(a), self.side(b)) {
                (Some(x), Some(y)) => {
                    if same(x, y).ok_or(Halt::Bail)? {
                        Ok(())
                    } else {
                        self.solve(i + 1)
                    }
                }
                // An unbound side unifies: `\=` fails.
                _ => Ok(()),
            },
        }
    }

    /// Counts one unit of work against the budget.
    fn tick(&mut self) -> Go {
        self.steps += 1;
        if self.steps > MAX_CANDIDATES {
            return Err(Halt::Bail);
        }
        Ok(())
    }

    /// Adds the answer of the values bound now.
    fn answer(&mut self) -> Go {
        let mut s = Subst::with_capacity(self.plan.vars.len());
        for (k, v) in self.plan.vars.iter().enumerate() {
            if self.given & (1 << k) != 0 {
                continue;
            }
            if let Some(val) = self.vals[k] {
                s.bind(*v, val.term());
            }
        }
        self.out.push(s);
        if self.out.len() >= self.cap {
            return Err(Halt::Cap);
        }
        Ok(())
    }

    /// The slot of variable `v` in the plan's order.
    fn slot(&self, v: Sym) -> usize {
        self.plan
            .vars
            .iter()
            .position(|&w| w == v)
            .expect("the plan lists every variable of its query")
    }

    fn bind(&mut self, k: usize, val: Val<'a>) {
        self.vals[k] = Some(val);
        self.trail.push(k);
    }

    fn undo(&mut self, mark: usize) {
        while self.trail.len() > mark {
            if let Some(k) = self.trail.pop() {
                self.vals[k] = None;
            }
        }
    }

    /// The value of a side of `=`/`\=` (`None`: an unbound variable).
    fn side(&self, t: &'a Term) -> Option<Val<'a>> {
        match t {
            t if is_anonymous(t) => None,
            Term::Var(v) => self.vals[self.slot(*v)],
            t => Some(Val::T(t)),
        }
    }

    /// `a = b` of variables, atoms and integers, then the conjuncts after `i`.
    fn unify_atomic(&mut self, a: &'a Term, b: &'a Term, i: usize) -> Go {
        match (self.side(a), self.side(b)) {
            (Some(x), Some(y)) => {
                if same(x, y).ok_or(Halt::Bail)? {
                    self.solve(i + 1)
                } else {
                    Ok(())
                }
            }
            (None, Some(val)) => self.bind_then(a, val, i),
            (Some(val), None) => self.bind_then(b, val, i),
            // One variable with itself; two unbound ones the engine would alias.
            (None, None) if a == b && !is_anonymous(a) => self.solve(i + 1),
            (None, None) => Err(Halt::Bail),
        }
    }

    /// Binds the unbound variable `var` to `val`, then runs the conjuncts after `i`.
    fn bind_then(&mut self, var: &'a Term, val: Val<'a>, i: usize) -> Go {
        let Term::Var(v) = var else {
            return Err(Halt::Bail);
        };
        if *v == wk::UNDERSCORE {
            return self.solve(i + 1);
        }
        let mark = self.trail.len();
        self.bind(self.slot(*v), val);
        let r = self.solve(i + 1);
        self.undo(mark);
        r
    }

    /// `lhs is <v>`, then the conjuncts after `i`.
    fn bind_int(&mut self, lhs: &'a Term, v: i64, i: usize) -> Go {
        match lhs {
            Term::Int(j) => {
                if *j == v {
                    self.solve(i + 1)
                } else {
                    Ok(())
                }
            }
            Term::Var(x) if *x == wk::UNDERSCORE => self.solve(i + 1),
            Term::Var(x) => match self.vals[self.slot(*x)] {
                None => self.bind_then(lhs, Val::I(v), i),
                Some(val) => match val.int() {
                    Some(j) if j == v => self.solve(i + 1),
                    Some(_) => Ok(()),
                    None => Err(Halt::Bail),
                },
            },
            _ => Err(Halt::Bail),
        }
    }

    /// The integer value of the expression `t` (checked by [`expr`]); `Bail` for anything the
    /// engine might answer otherwise (an unbound or non-integer operand, an overflow, a zero
    /// divisor).
    fn eval(&self, t: &Term) -> Result<i64, Halt> {
        match t {
            Term::Int(i) => Ok(*i),
            Term::Var(v) => self.vals[self.slot(*v)]
                .and_then(Val::int)
                .ok_or(Halt::Bail),
            Term::Compound(c) => {
                let op = operator(c.name, c.args.len()).ok_or(Halt::Bail)?;
                let x = self.eval(&c.args[0])?;
                if op == Op::Neg {
                    return x.checked_neg().ok_or(Halt::Bail);
                }
                let y = self.eval(&c.args[1])?;
                match op {
                    Op::Add => x.checked_add(y),
                    Op::Sub => x.checked_sub(y),
                    Op::Mul => x.checked_mul(y),
                    Op::IntDiv if y != 0 => x.checked_div(y),
                    Op::Mod if y != 0 => x.checked_rem(y).map(|r| {
                        if r != 0 && (r < 0) != (y < 0) {
                            r + y
                        } else {
                            r
                        }
                    }),
                    _ => None,
                }
                .ok_or(Halt::Bail)
            }
            _ => Err(Halt::Bail),
        }
    }

    /// The index key of argument `i` of the pattern `p` now (`Ok(None)`: unbound or absent).
    fn arg_key(&self, p: &Term, i: usize) -> Result<Option<Key>, Halt> {
        let Some(a) = p.args().get(i) else {
            return Ok(None);
        };
        let val = match a {
            Term::Var(v) if *v == wk::UNDERSCORE => return Ok(None),
            Term::Var(v) => match self.vals[self.slot(*v)] {
                Some(val) => val,
                None => return Ok(None),
            },
            t => Val::T(t),
        };
        val.key().map(Some).ok_or(Halt::Bail)
    }

    /// Calls `then` once for each fact that matches the pattern `p` (with the pattern's free
    /// variables bound to the fact's parts), in the engine's order: base by base, each in
    /// insertion order.
    fn each_match(&mut self, pat: &'a Pattern, then: &mut dyn FnMut(&mut Run<'a>) -> Go) -> Go {
        let p = &pat.term;
        let Some((name, arity)) = p.functor() else {
            return Err(Halt::Bail);
        };
        let bases = self.bases;
        // A ground instance is looked up by hash, as the engine looks up a ground fact.
        if pat.by_hash {
            if let Some(inst) = self.instance(p, 0)? {
                for base in bases.iter().filter(|b| b.has_pred(name, arity)) {
                    self.tick()?;
                    if base.contains(&inst) {
                        then(self)?;
                    }
                }
                return Ok(());
            }
        }
        let (k1, k2) = (self.arg_key(p, 0)?, self.arg_key(p, 1)?);
        for base in bases.iter().filter(|b| b.has_pred(name, arity)) {
            let mut scan = base.scan(name, arity as u32, k1, k2);
            while let Some(fact) = base.advance(&mut scan) {
                self.tick()?;
                let mark = self.trail.len();
                let r = match self.match_fact(p, fact) {
                    Ok(true) => then(self),
                    Ok(false) => Ok(()),
                    Err(h) => Err(h),
                };
                self.undo(mark);
                r?;
            }
        }
        Ok(())
    }

    /// The pattern `p` under the values bound now, when that is ground (`Ok(None)`: it is
    /// not); `Bail` on a float (whose equality is not its unifiability) or a deep term.
    fn instance(&self, p: &Term, depth: usize) -> Result<Option<Term>, Halt> {
        if depth > MAX_INSTANCE_DEPTH {
            return Err(Halt::Bail);
        }
        Ok(Some(match p {
            Term::Var(v) if *v == wk::UNDERSCORE => return Ok(None),
            Term::Var(v) => match self.vals[self.slot(*v)] {
                None => return Ok(None),
                Some(Val::I(i)) => Term::Int(i),
                Some(Val::T(t)) => {
                    if has_float(t) {
                        return Err(Halt::Bail);
                    }
                    t.clone()
                }
            },
            Term::Compound(c) => {
                let mut args = Vec::with_capacity(c.args.len());
                for a in c.args.iter() {
                    match self.instance(a, depth + 1)? {
                        Some(t) => args.push(t),
                        None => return Ok(None),
                    }
                }
                Term::compound(c.name, args)
            }
            Term::Float(_) => return Err(Halt::Bail),
            t => t.clone(),
        }))
    }

    /// Matches the pattern `p` against `fact`, binding the pattern's free variables in
    /// reading order; `Bail` when plain comparison cannot decide (a variable in the fact, a
    /// float, too many cells bound).
    fn match_fact(&mut self, p: &'a Term, fact: &'a Term) -> Result<bool, Halt> {
        let mut work: SmallVec<[(&'a Term, &'a Term); 8]> = smallvec![(p, fact)];
        while let Some((p, f)) = work.pop() {
            match (p, f) {
                (_, Term::Var(_)) => return Err(Halt::Bail),
                (Term::Var(v), f) if *v == wk::UNDERSCORE => {
                    if !f.is_ground() {
                        return Err(Halt::Bail);
                    }
                }
                (Term::Var(v), f) => {
                    let k = self.slot(*v);
                    match self.vals[k] {
                        Some(val) => {
                            if !same(val, Val::T(f)).ok_or(Halt::Bail)? {
                                return Ok(false);
                            }
                        }
                        None => {
                            self.cells += size_if_ground(f).ok_or(Halt::Bail)?;
                            if self.cells > MAX_CELLS {
                                return Err(Halt::Bail);
                            }
                            self.bind(k, Val::T(f));
                        }
                    }
                }
                (Term::Compound(pc), f) => {
                    let Term::Compound(fc) = f else {
                        if matches!(f, Term::Float(_)) {
                            return Err(Halt::Bail);
                        }
                        return Ok(false);
                    };
                    if pc.name != fc.name || pc.args.len() != fc.args.len() {
                        return Ok(false);
                    }
                    // Reversed, so that the leftmost argument is matched first.
                    work.extend(pc.args.iter().zip(fc.args.iter()).rev());
                }
                (Term::Float(_), _) | (_, Term::Float(_)) => return Err(Halt::Bail),
                (p, f) => {
                    if p != f {
                        return Ok(false);
                    }
                }
            }
        }
        Ok(true)
    }
}

fn is_anonymous(t: &Term) -> bool {
    matches!(t, Term::Var(v) if *v == wk::UNDERSCORE)
}

/// Whether two ground values are equal, which for them is whether they unify; `None` when a
/// float or a variable makes plain comparison unreliable.
fn same(a: Val<'_>, b: Val<'_>) -> Option<bool> {
    let (a, b) = match (a, b) {
        (Val::I(x), Val::I(y)) => return Some(x == y),
        (Val::I(x), Val::T(t)) | (Val::T(t), Val::I(x)) => {
            return match t {
                Term::Int(y) => Some(x == *y),
                Term::Float(_) | Term::Var(_) => None,
                _ => Some(false),
            }
        }
        (Val::T(a), Val::T(b)) => (a, b),
    };
    let mut work: SmallVec<[(&Term, &Term); 8]> = smallvec![(a, b)];
    while let Some((a, b)) = work.pop() {
        match (a, b) {
            (Term::Var(_) | Term::Float(_), _) | (_, Term::Var(_) | Term::Float(_)) => return None,
            (Term::Compound(x), Term::Compound(y)) => {
                if x.name != y.name || x.args.len() != y.args.len() {
                    return Some(false);
                }
                work.extend(x.args.iter().zip(y.args.iter()).rev());
            }
            (a, b) => {
                if a != b {
                    return Some(false);
                }
            }
        }
    }
    Some(true)
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
