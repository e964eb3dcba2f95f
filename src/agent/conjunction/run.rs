//! Running a [`Plan`]: the conjuncts left to right with backtracking over the variables'
//! values, the engine's order of answers, and the budget that hands a query back to the engine.

use super::*;
use crate::term::instance::{Instance, Value};

/// The answers of `plan` over `bases` under `theta`, at most `cap`, and whether `cap` stopped
/// them; `None`: something the plan does not decide, so the engine answers.
pub(super) fn answers(
    plan: &Plan,
    bases: &[&FactBase],
    theta: &Subst,
    cap: usize,
) -> Option<(Vec<Subst>, bool)> {
    let mut run = Run {
        plan,
        bases,
        vals: SmallVec::with_capacity(plan.vars.len()),
        given: 0,
        trail: SmallVec::new(),
        steps: 0,
        cells: 0,
        cap,
        out: Vec::new(),
    };
    for (i, v) in plan.vars.iter().enumerate() {
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
            Step::Absent(p) => match self.any_match(p)? {
                true => Ok(()),
                false => self.solve(i + 1),
            },
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

    /// Whether some fact matches the pattern `p` (the search stops at the first).
    fn any_match(&mut self, p: &'a Pattern) -> Result<bool, Halt> {
        let mut found = false;
        match self.each_match(p, &mut |_| {
            found = true;
            Err(Halt::Cap)
        }) {
            Err(Halt::Cap) if found => Ok(true),
            r => r.map(|()| false),
        }
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
        if pat.by_hash && self.ground_now(p, 0)? {
            for base in bases.iter().filter(|b| b.has_pred(name, arity)) {
                self.tick()?;
                // The instance is hashed and compared in place, never built.
                if base.contains_instance(&self.instance(p)) {
                    then(self)?;
                }
            }
            return Ok(());
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

    /// Whether the pattern `p` is ground under the values bound now (looked at left to right,
    /// up to the first unbound variable); `Bail` on a float (whose equality is not its
    /// unifiability) or a deep term.
    fn ground_now(&self, p: &Term, depth: usize) -> Result<bool, Halt> {
        if depth > MAX_INSTANCE_DEPTH {
            return Err(Halt::Bail);
        }
        match p {
            Term::Var(v) if *v == wk::UNDERSCORE => Ok(false),
            Term::Var(v) => match self.vals[self.slot(*v)] {
                None => Ok(false),
                Some(Val::I(_)) => Ok(true),
                Some(Val::T(Term::Float(_))) => Err(Halt::Bail),
                // Only a compound value is walked for floats.
                Some(Val::T(t @ Term::Compound(_))) if has_float(t) => Err(Halt::Bail),
                Some(Val::T(_)) => Ok(true),
            },
            Term::Compound(c) => {
                for a in c.args.iter() {
                    if !self.ground_now(a, depth + 1)? {
                        return Ok(false);
                    }
                }
                Ok(true)
            }
            Term::Float(_) => Err(Halt::Bail),
            _ => Ok(true),
        }
    }

    /// The pattern `p` under the values bound now, as a fact base looks it up (see
    /// [`Run::ground_now`]).
    fn instance<'r>(&'r self, p: &'a Term) -> Instance<'a, impl Fn(Sym) -> Option<Value<'a>> + 'r> {
        Instance::new(p, move |v| {
            self.vals[self.slot(v)].map(|val| match val {
                Val::T(t) => Value::Term(t),
                Val::I(i) => Value::Int(i),
            })
        })
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
