//! Running a [`Plan`]: the conjuncts left to right with backtracking over the variables'
//! values, the engine's order of answers, and the budget that hands a query back to the engine.

use super::*;
use crate::term::instance::{Instance, Value};

/// The answers of `plan` over `bases` under `theta`, at most `cap`, and whether `cap` stopped
/// them; `None`: something the plan does not decide, so the engine answers.
pub(super) fn answers(
    plan: &Plan,
    bases: &[&FactBase],
    arrived: Arrived<'_>,
    theta: &Subst,
    cap: usize,
) -> Option<(Answers, bool)> {
    let mut out = Answers::new();
    let cut = answers_into(plan, bases, arrived, theta, cap, &mut out)?;
    Some((out, cut))
}

/// [`answers`] added to `out` (empty when called); `None` (and `out` left with some answers
/// perhaps): the engine answers.
pub(super) fn answers_into(
    plan: &Plan,
    bases: &[&FactBase],
    arrived: Arrived<'_>,
    theta: &Subst,
    cap: usize,
    out: &mut Answers,
) -> Option<bool> {
    let mut run = Run {
        plan,
        bases,
        arrived,
        vals: [None; MAX_VARS],
        given: 0,
        trail: [0; MAX_VARS],
        bound: 0,
        steps: 0,
        cells: 0,
        cap,
        out,
    };
    // Each binding of `theta` placed in its variable's register (a look for each binding, not
    // one through `theta` for each variable: `theta` binds few).
    for (v, t) in theta.iter() {
        let Some(i) = plan.vars.iter().position(|w| *w == v) else {
            continue;
        };
        if matches!(t, Term::Compound(_) | Term::Var(_)) && !t.is_ground() {
            return None;
        }
        run.given |= 1 << i;
        run.vals[i] = Some(Val::T(t));
    }
    match run.solve(0) {
        // As the engine reports it: stopped when `cap` answers were reached.
        Ok(()) | Err(Halt::Cap) => Some(run.out.len() >= cap),
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
struct Run<'a, 'o> {
    plan: &'a Plan,
    bases: &'a [&'a FactBase],
    /// Mailbox facts read after one of `bases` (see [`Arrived`]).
    arrived: Arrived<'a>,
    vals: [Option<Val<'a>>; MAX_VARS],
    /// The variables `theta` binds (a bit each), left out of the answers.
    given: u64,
    /// The registers bound since the run began, the last `bound` entries of which count (a
    /// register is bound at most once at a time: at most [`MAX_VARS`] entries).
    trail: [u8; MAX_VARS],
    bound: usize,
    steps: usize,
    cells: usize,
    cap: usize,
    out: &'o mut Answers,
}

impl<'a> Run<'a, '_> {
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
                let v = self.value(e)?;
                self.bind_int(lhs, v, i)
            }
            Step::Compare(op, a, b) => {
                let (a, b) = (self.value(a)?, self.value(b)?);
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
                // The plan's variables are distinct: no earlier binding to look for.
                s.bind_new(*v, val.term());
            }
        }
        self.out.push(s);
        if self.out.len() >= self.cap {
            return Err(Halt::Cap);
        }
        Ok(())
    }

    fn bind(&mut self, k: usize, val: Val<'a>) {
        self.vals[k] = Some(val);
        self.trail[self.bound] = k as u8;
        self.bound += 1;
    }

    fn undo(&mut self, mark: usize) {
        while self.bound > mark {
            self.bound -= 1;
            self.vals[self.trail[self.bound] as usize] = None;
        }
    }

    /// The value of a side of `=`/`\=` (`None`: an unbound variable or `_`).
    fn side(&self, t: &'a Arg) -> Option<Val<'a>> {
        match t {
            Arg::Anon => None,
            Arg::Reg(k) => self.vals[*k],
            Arg::Const(t) => Some(Val::T(t)),
            // Not made by `prepare` for a side; a compound never equals an atomic value.
            Arg::Compound(..) => None,
        }
    }

    /// `a = b` of variables, atoms and integers, then the conjuncts after `i`.
    fn unify_atomic(&mut self, a: &'a Arg, b: &'a Arg, i: usize) -> Go {
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
            (None, None) => match (a, b) {
                (Arg::Reg(x), Arg::Reg(y)) if x == y => self.solve(i + 1),
                _ => Err(Halt::Bail),
            },
        }
    }

    /// Binds the unbound variable `var` to `val`, then runs the conjuncts after `i`.
    fn bind_then(&mut self, var: &'a Arg, val: Val<'a>, i: usize) -> Go {
        match var {
            Arg::Anon => self.solve(i + 1),
            Arg::Reg(k) => {
                let mark = self.bound;
                self.bind(*k, val);
                let r = self.solve(i + 1);
                self.undo(mark);
                r
            }
            _ => Err(Halt::Bail),
        }
    }

    /// `lhs is <v>`, then the conjuncts after `i`.
    fn bind_int(&mut self, lhs: &'a Arg, v: i64, i: usize) -> Go {
        match lhs {
            Arg::Const(Term::Int(j)) => {
                if *j == v {
                    self.solve(i + 1)
                } else {
                    Ok(())
                }
            }
            Arg::Anon => self.solve(i + 1),
            Arg::Reg(k) => match self.vals[*k] {
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

    /// [`Run::eval`] with a leaf (an integer, a variable) or a variable and an integer under
    /// an operator (`K - 1`) evaluated in place: most sides of a comparison or `is/2` are one.
    #[inline(always)]
    fn value(&self, e: &Expr) -> Result<i64, Halt> {
        match e {
            Expr::Int(i) => Ok(*i),
            Expr::Reg(k) => self.vals[*k].and_then(Val::int).ok_or(Halt::Bail),
            Expr::RegInt(op, k, y) => {
                let x = self.vals[*k].and_then(Val::int).ok_or(Halt::Bail)?;
                apply(*op, x, *y).ok_or(Halt::Bail)
            }
            _ => self.eval(e),
        }
    }

    /// The integer value of the expression `e`; `Bail` for anything the engine might answer
    /// otherwise (an unbound or non-integer operand, an overflow, a zero divisor).
    fn eval(&self, e: &Expr) -> Result<i64, Halt> {
        match e {
            Expr::Int(i) => Ok(*i),
            Expr::Reg(k) => self.vals[*k].and_then(Val::int).ok_or(Halt::Bail),
            Expr::Neg(x) => self.eval(x)?.checked_neg().ok_or(Halt::Bail),
            Expr::Bin(op, x, y) => {
                let x = self.eval(x)?;
                let y = self.eval(y)?;
                apply(*op, x, y).ok_or(Halt::Bail)
            }
            Expr::RegInt(op, k, y) => {
                let x = self.vals[*k].and_then(Val::int).ok_or(Halt::Bail)?;
                apply(*op, x, *y).ok_or(Halt::Bail)
            }
        }
    }

    /// The index key of argument `i` of the pattern `p` now (`Ok(None)`: unbound or absent).
    fn arg_key(&self, p: &Pattern, i: usize) -> Result<Option<Key>, Halt> {
        let val = match p.args.get(i) {
            None | Some(Arg::Anon) => return Ok(None),
            Some(Arg::Reg(k)) => match self.vals[*k] {
                Some(val) => val,
                None => return Ok(None),
            },
            Some(Arg::Compound(name, args)) => return Ok(Some(Key::Fun(*name, args.len() as u32))),
            Some(Arg::Const(t)) => Val::T(t),
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
    fn each_match(&mut self, p: &'a Pattern, then: &mut dyn FnMut(&mut Self) -> Go) -> Go {
        let (name, arity) = (p.name, p.arity);
        let bases = self.bases;
        // A ground instance is looked up by hash, as the engine looks up a ground fact.
        if p.by_hash && self.ground_now(&p.args)? {
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
        // The base after which the messages waiting aside are read (none for other predicates).
        let mail_after = match (name, arity) == (wk::RECEIVED, 2) {
            true => self.arrived.after,
            false => usize::MAX,
        };
        for (i, base) in bases.iter().enumerate() {
            // The quick filter only: a scan of an absent predicate finds nothing.
            if base.may_have_pred(name, arity) {
                let mut scan = base.scan(name, arity as u32, k1, k2);
                while let Some(fact) = base.advance(&mut scan) {
                    self.try_match(then, |run| run.match_fact(p, fact))?;
                }
            }
            if i == mail_after {
                for args in self.arrived.received {
                    self.try_match(then, |run| run.match_args(p, args))?;
                }
            }
        }
        Ok(())
    }

    /// Calls `then` when `matches` (matching one fact) binds the pattern's variables, then
    /// takes the bindings back (see [`Run::each_match`]).
    fn try_match(
        &mut self,
        then: &mut dyn FnMut(&mut Self) -> Go,
        matches: impl FnOnce(&mut Self) -> Result<bool, Halt>,
    ) -> Go {
        self.tick()?;
        let mark = self.bound;
        let r = match matches(self) {
            Ok(true) => then(self),
            Ok(false) => Ok(()),
            Err(h) => Err(h),
        };
        self.undo(mark);
        r
    }

    /// Whether the parts `args` are ground under the values bound now (looked at left to
    /// right, up to the first unbound variable); `Bail` on a float (whose equality is not its
    /// unifiability). By recursion: parts are at most [`MAX_INSTANCE_DEPTH`] deep.
    fn ground_now(&self, args: &[Arg]) -> Result<bool, Halt> {
        for a in args {
            let ground = match a {
                Arg::Anon => false,
                Arg::Reg(k) => match self.vals[*k] {
                    None => false,
                    Some(Val::I(_)) => true,
                    Some(Val::T(t)) if has_float(t) => return Err(Halt::Bail),
                    Some(Val::T(_)) => true,
                },
                Arg::Compound(_, parts) => self.ground_now(parts)?,
                Arg::Const(Term::Float(_)) => return Err(Halt::Bail),
                Arg::Const(_) => true,
            };
            if !ground {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// The pattern `p` under the values bound now, as a fact base looks it up (see
    /// [`Run::ground_now`]).
    fn instance<'r>(
        &'r self,
        p: &'a Pattern,
    ) -> Instance<'a, impl Fn(Sym) -> Option<Value<'a>> + 'r> {
        Instance::new(&p.term, move |v| {
            let k = self.plan.vars.iter().position(|w| *w == v)?;
            self.vals[k].map(|val| match val {
                Val::T(t) => Value::Term(t),
                Val::I(i) => Value::Int(i),
            })
        })
    }

    /// Matches the pattern `p` against `fact`, binding the pattern's free variables in
    /// reading order; `Bail` when plain comparison cannot decide (a variable in the fact, a
    /// float, too many cells bound).
    fn match_fact(&mut self, p: &'a Pattern, fact: &'a Term) -> Result<bool, Halt> {
        let fc = match fact {
            Term::Var(_) | Term::Float(_) => return Err(Halt::Bail),
            Term::Compound(fc) if p.arity > 0 => fc,
            // A pattern of no arguments is an atom: the fact is that atom or another term.
            Term::Atom(a) => return Ok(p.arity == 0 && *a == p.name),
            _ => return Ok(false),
        };
        if fc.name != p.name {
            return Ok(false);
        }
        self.match_args(p, &fc.args)
    }

    /// [`Run::match_fact`] of a fact of the pattern's predicate with arguments `args`.
    fn match_args(&mut self, p: &'a Pattern, args: &'a [Term]) -> Result<bool, Halt> {
        if args.len() != p.args.len() {
            return Ok(false);
        }
        self.match_parts(&p.args, args)
    }

    /// Matches the pattern parts `parts` against the fact parts `args` (as many) left to
    /// right, each compound part's own parts before the next part: the order of reading, in
    /// which variables are bound and the first mismatch or `Bail` is met. By recursion over
    /// the pattern, which is at most [`MAX_INSTANCE_DEPTH`] deep (no work list to fill).
    fn match_parts(&mut self, parts: &'a [Arg], args: &'a [Term]) -> Result<bool, Halt> {
        for (p, f) in parts.iter().zip(args) {
            match (p, f) {
                (_, Term::Var(_)) => return Err(Halt::Bail),
                (Arg::Anon, f) => {
                    if !f.is_ground() {
                        return Err(Halt::Bail);
                    }
                }
                (Arg::Reg(k), f) => match self.vals[*k] {
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
                        self.bind(*k, Val::T(f));
                    }
                },
                (Arg::Compound(name, parts), f) => {
                    let Term::Compound(fc) = f else {
                        if matches!(f, Term::Float(_)) {
                            return Err(Halt::Bail);
                        }
                        return Ok(false);
                    };
                    if *name != fc.name || parts.len() != fc.args.len() {
                        return Ok(false);
                    }
                    if !self.match_parts(parts, &fc.args)? {
                        return Ok(false);
                    }
                }
                (Arg::Const(Term::Float(_)), _) | (_, Term::Float(_)) => return Err(Halt::Bail),
                (Arg::Const(p), f) => {
                    if p != f {
                        return Ok(false);
                    }
                }
            }
        }
        Ok(true)
    }
}

/// The binary operator `op` on `x` and `y`; `None` on an overflow or a zero divisor (the
/// engine then raises its error).
fn apply(op: Op, x: i64, y: i64) -> Option<i64> {
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
        // Atomic values are compared at once (the walk below would do the same).
        (Val::T(a @ Term::Compound(_)), Val::T(b @ Term::Compound(_))) => (a, b),
        (Val::T(Term::Var(_) | Term::Float(_)), _) | (_, Val::T(Term::Var(_) | Term::Float(_))) => {
            return None
        }
        (Val::T(a), Val::T(b)) => return Some(a == b),
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
