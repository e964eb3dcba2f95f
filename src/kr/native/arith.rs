//! Arithmetic: `is/2`, comparison, `succ/2`, `plus/3`, random numbers. Evaluation is iterative
//! (an explicit stack), integers are i64 with checked overflow, and unbounded (`bigint`) past it.

use super::bigint;
use super::builtins::{inst, type_error, Flow, B};
use super::machine::Solver;
use super::store::{Cell, Store};
use crate::kr::error::{KrError, KrResult};
use crate::term::{well_known as wk, Sym, Term};
use rand::Rng;
use std::cmp::Ordering;

/// A number during evaluation.
#[derive(Clone, Debug)]
pub(crate) enum Num {
    I(i64),
    F(f64),
    /// An integer outside the 64-bit range (never one inside it).
    B(std::sync::Arc<num_bigint::BigInt>),
}

impl Num {
    /// The number as a heap cell.
    pub fn cell(self, st: &mut Store) -> Cell {
        match self {
            Num::I(i) => Cell::Int(i),
            Num::F(f) => Cell::Flt(f),
            Num::B(b) => st.new_big(&b),
        }
    }
    /// The number as a float.
    pub fn f(&self) -> f64 {
        match self {
            Num::I(i) => *i as f64,
            Num::F(f) => *f,
            Num::B(b) => bigint::to_f64(b),
        }
    }
}

/// True for the error of a 64-bit integer operation that overflowed (redone with big integers).
fn is_overflow(e: &KrError) -> bool {
    e.to_term()
        .to_string()
        .starts_with("error(evaluation_error(int_overflow)")
}

pub(crate) fn eval_err(what: &str) -> KrError {
    KrError::iso(
        Term::compound("evaluation_error", vec![Term::atom(what)]),
        None,
    )
}

fn overflow() -> KrError {
    eval_err("int_overflow")
}

fn not_int(n: Num) -> KrError {
    let t = match n {
        Num::I(i) => Term::Int(i),
        Num::F(f) => Term::from(f),
        Num::B(b) => Term::BigInt(b),
    };
    KrError::iso(
        Term::compound("type_error", vec![Term::atom("integer"), t]),
        None,
    )
}

fn int(n: Num) -> KrResult<i64> {
    match n {
        Num::I(i) => Ok(i),
        _ => Err(not_int(n)),
    }
}

fn check_float(f: f64) -> KrResult<Num> {
    if f.is_nan() {
        Err(eval_err("undefined"))
    } else if f.is_infinite() {
        Err(eval_err("float_overflow"))
    } else {
        Ok(Num::F(f))
    }
}

fn to_int(f: f64) -> KrResult<Num> {
    if !(-9.223_372_036_854_776e18..9.223_372_036_854_776e18).contains(&f) {
        Err(overflow())
    } else {
        Ok(Num::I(f as i64))
    }
}

fn unknown(name: Sym, arity: usize) -> KrError {
    KrError::iso(
        Term::compound(
            "type_error",
            vec![
                Term::atom("evaluable"),
                Term::compound("/", vec![Term::Atom(name), Term::Int(arity as i64)]),
            ],
        ),
        None,
    )
}

fn cmp_num(a: &Num, b: &Num) -> Ordering {
    match (a, b) {
        (Num::I(x), Num::I(y)) => x.cmp(y),
        (Num::B(_), _) | (_, Num::B(_)) => bigint::compare(a, b),
        _ => a.f().partial_cmp(&b.f()).unwrap_or(Ordering::Equal),
    }
}

fn int_pow(base: i64, exp: i64) -> KrResult<Num> {
    if exp < 0 {
        return match base {
            1 => Ok(Num::I(1)),
            -1 => Ok(Num::I(if exp % 2 == 0 { 1 } else { -1 })),
            0 => Err(eval_err("zero_divisor")),
            // SWI (prefer_rationals false): a negative power of another integer is a float.
            _ => check_float((base as f64).powf(exp as f64)),
        };
    }
    let e = u32::try_from(exp).map_err(|_| overflow())?;
    base.checked_pow(e).map(Num::I).ok_or_else(overflow)
}

/// A step of the iterative evaluation: evaluate a cell, or apply a functor to the values on top.
#[derive(Clone, Copy)]
pub(crate) enum Work {
    Eval(Cell),
    Apply(Sym, u32),
}

/// The evaluation stacks, kept in the machine so that evaluating allocates nothing once they
/// have grown (most expressions are a number or one operation on two small integers).
#[derive(Default)]
pub(crate) struct ArithStacks {
    work: Vec<Work>,
    vals: Vec<Num>,
}

impl Solver<'_, '_> {
    /// Evaluates an arithmetic expression.
    pub fn eval(&mut self, c: Cell) -> KrResult<Num> {
        if let Some(n) = self.eval_small(c) {
            return Ok(n);
        }
        let mut stacks = std::mem::take(&mut self.m.arith);
        stacks.work.clear();
        stacks.vals.clear();
        let r = self.eval_with(c, &mut stacks);
        self.m.arith = stacks;
        r
    }

    /// A number, or `+`, `-` or `*` of two integers that does not overflow: the common cases,
    /// answered without the evaluation stacks. `None` for everything else (including errors).
    #[inline]
    fn eval_small(&self, c: Cell) -> Option<Num> {
        let st = &self.m.st;
        let p = match st.deref(c) {
            Cell::Int(i) => return Some(Num::I(i)),
            Cell::Flt(f) => return Some(Num::F(f)),
            Cell::Ptr(p) => p,
            _ => return None,
        };
        let Cell::Fun(f, 2) = st.heap[p as usize] else {
            return None;
        };
        let (Cell::Int(x), Cell::Int(y)) = (st.deref(self.a(p, 0)), st.deref(self.a(p, 1))) else {
            return None;
        };
        match f {
            wk::PLUS => x.checked_add(y),
            wk::MINUS => x.checked_sub(y),
            wk::STAR => x.checked_mul(y),
            _ => None,
        }
        .map(Num::I)
    }

    fn eval_with(&mut self, c: Cell, stacks: &mut ArithStacks) -> KrResult<Num> {
        let ArithStacks { work, vals } = stacks;
        work.push(Work::Eval(c));
        let (mut steps, limit) = (0usize, self.m.st.step_limit());
        while let Some(w) = work.pop() {
            // A cyclic expression (`X = f(X), Y is X`) would never end.
            if self.m.st.runaway(&mut steps, limit, &[c]) {
                return Err(self.walk_fault());
            }
            match w {
                Work::Eval(c) => match self.m.st.deref(c) {
                    Cell::Int(i) => vals.push(Num::I(i)),
                    Cell::Flt(f) => vals.push(Num::F(f)),
                    Cell::Big(i) => vals.push(bigint::norm(self.m.st.big(i))?),
                    Cell::Ref(_) => {
                        return Err(KrError::iso(Term::atom("instantiation_error"), None))
                    }
                    Cell::Atom(s) => vals.push(self.eval0(s)?),
                    Cell::Str(i) => {
                        let text = &self.m.st.strs[i as usize];
                        let mut chars = text.chars();
                        match (chars.next(), chars.next()) {
                            (Some(ch), None) => vals.push(Num::I(ch as i64)),
                            _ => {
                                let t = Term::Str(text.clone());
                                return Err(KrError::iso(
                                    Term::compound("type_error", vec![Term::atom("evaluable"), t]),
                                    None,
                                ));
                            }
                        }
                    }
                    Cell::Ptr(p) => {
                        let Some((f, n)) = self.m.st.heap[p as usize].fun() else {
                            continue;
                        };
                        if f == wk::DOT && n == 2 {
                            // "[X]" evaluates X.
                            if !matches!(self.ad(p, 1), Cell::Atom(s) if s == wk::NIL) {
                                return Err(unknown(f, 2));
                            }
                            work.push(Work::Eval(self.a(p, 0)));
                            continue;
                        }
                        work.push(Work::Apply(f, n));
                        for i in (0..n).rev() {
                            work.push(Work::Eval(self.a(p, i)));
                        }
                    }
                    Cell::Fun(..) => {}
                },
                Work::Apply(f, n) => {
                    let v = match n {
                        1 => {
                            let x = vals.pop().ok_or_else(|| eval_err("undefined"))?;
                            self.eval1(f, x)?
                        }
                        2 => {
                            let y = vals.pop().ok_or_else(|| eval_err("undefined"))?;
                            let x = vals.pop().ok_or_else(|| eval_err("undefined"))?;
                            eval2(f, x, y)?
                        }
                        _ => return Err(unknown(f, n as usize)),
                    };
                    vals.push(v);
                }
            }
        }
        vals.pop().ok_or_else(|| eval_err("undefined"))
    }

    fn eval0(&mut self, s: Sym) -> KrResult<Num> {
        Ok(match s.name() {
            "pi" => Num::F(std::f64::consts::PI),
            "e" => Num::F(std::f64::consts::E),
            "inf" | "infinite" => Num::F(f64::INFINITY),
            "nan" => Num::F(f64::NAN),
            "epsilon" => Num::F(f64::EPSILON),
            "max_tagged_integer" => Num::I((1 << 60) - 1),
            "min_tagged_integer" => Num::I(-(1 << 60)),
            "random" => Num::F(self.cx.rng.gen::<f64>()),
            "random_float" => Num::F(self.cx.rng.gen::<f64>()),
            "cputime" => Num::F(cputime()),
            "realtime" => Num::I(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_secs() as i64),
            ),
            "max_integer" => Num::I(i64::MAX),
            "min_integer" => Num::I(i64::MIN),
            "[]" => return Err(unknown(s, 0)),
            _ => return Err(unknown(s, 0)),
        })
    }

    fn eval1(&mut self, f: Sym, x: Num) -> KrResult<Num> {
        if let Num::B(_) = x {
            return match bigint::eval1(f, &x)? {
                Some(v) => Ok(v),
                None => self.eval1_small(f, Num::F(x.f())),
            };
        }
        match self.eval1_small(f, x.clone()) {
            Err(e) if is_overflow(&e) => bigint::eval1(f, &x)?.ok_or(e),
            r => r,
        }
    }

    fn eval1_small(&mut self, f: Sym, x: Num) -> KrResult<Num> {
        use Num::{F, I};
        Ok(match (f.name(), x.clone()) {
            ("-", I(i)) => I(i.checked_neg().ok_or_else(overflow)?),
            ("-", F(v)) => F(-v),
            ("+", _) => x,
            ("abs", I(i)) => I(i.checked_abs().ok_or_else(overflow)?),
            ("abs", F(v)) => F(v.abs()),
            ("sign", I(i)) => I(i.signum()),
            ("sign", F(v)) => F(if v == 0.0 { 0.0 } else { v.signum() }),
            ("min" | "max", _) => return Err(unknown(f, 1)),
            ("sqrt", _) => {
                if x.f() < 0.0 {
                    return Err(eval_err("undefined"));
                }
                F(x.f().sqrt())
            }
            ("sin", _) => F(x.f().sin()),
            ("cos", _) => F(x.f().cos()),
            ("tan", _) => F(x.f().tan()),
            ("asin", _) => check_float(x.f().asin())?,
            ("acos", _) => check_float(x.f().acos())?,
            ("atan", _) => F(x.f().atan()),
            ("sinh", _) => F(x.f().sinh()),
            ("cosh", _) => F(x.f().cosh()),
            ("tanh", _) => F(x.f().tanh()),
            ("exp", _) => check_float(x.f().exp())?,
            ("log", _) => {
                if x.f() <= 0.0 {
                    return Err(eval_err("undefined"));
                }
                F(x.f().ln())
            }
            ("log2", _) => {
                if x.f() <= 0.0 {
                    return Err(eval_err("undefined"));
                }
                F(x.f().log2())
            }
            ("float", _) => F(x.f()),
            ("integer", I(_)) => x,
            ("integer", F(v)) => to_int(v.round())?,
            ("float_integer_part", _) => F(x.f().trunc()),
            ("float_fractional_part", _) => F(x.f().fract()),
            ("truncate", I(_)) | ("round", I(_)) | ("ceiling", I(_)) | ("floor", I(_)) => x,
            ("truncate", F(v)) => to_int(v.trunc())?,
            ("round", F(v)) => to_int(v.round())?,
            ("ceiling", F(v)) => to_int(v.ceil())?,
            ("floor", F(v)) => to_int(v.floor())?,
            ("\\", _) => I(!int(x)?),
            ("msb", _) => {
                let i = int(x)?;
                if i <= 0 {
                    return Err(eval_err("undefined"));
                }
                I(63 - i.leading_zeros() as i64)
            }
            ("succ", _) => I(int(x)?.checked_add(1).ok_or_else(overflow)?),
            ("random", _) => {
                let n = int(x)?;
                if n <= 0 {
                    return Err(eval_err("undefined"));
                }
                I(self.cx.rng.gen_range(0..n))
            }
            ("random_float", _) => F(self.cx.rng.gen::<f64>()),
            _ => return Err(unknown(f, 1)),
        })
    }
}

fn cputime() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_secs_f64()
}

fn eval2(f: Sym, x: Num, y: Num) -> KrResult<Num> {
    if matches!(x, Num::B(_)) || matches!(y, Num::B(_)) {
        return match bigint::eval2(f, &x, &y)? {
            Some(v) => Ok(v),
            None => eval2_small(f, Num::F(x.f()), Num::F(y.f())),
        };
    }
    match eval2_small(f, x.clone(), y.clone()) {
        Err(e) if is_overflow(&e) => bigint::eval2(f, &x, &y)?.ok_or(e),
        r => r,
    }
}

fn eval2_small(f: Sym, x: Num, y: Num) -> KrResult<Num> {
    use Num::{F, I};
    Ok(match (f.name(), x.clone(), y.clone()) {
        ("+", I(a), I(b)) => I(a.checked_add(b).ok_or_else(overflow)?),
        ("-", I(a), I(b)) => I(a.checked_sub(b).ok_or_else(overflow)?),
        ("*", I(a), I(b)) => I(a.checked_mul(b).ok_or_else(overflow)?),
        ("+", _, _) => check_float(x.f() + y.f())?,
        ("-", _, _) => check_float(x.f() - y.f())?,
        ("*", _, _) => check_float(x.f() * y.f())?,
        ("/", I(a), I(b)) => {
            if b == 0 {
                return Err(eval_err("zero_divisor"));
            }
            if a % b == 0 {
                I(a.checked_div(b).ok_or_else(overflow)?)
            } else {
                F(a as f64 / b as f64)
            }
        }
        ("/", _, _) => {
            if y.f() == 0.0 {
                return Err(eval_err("zero_divisor"));
            }
            check_float(x.f() / y.f())?
        }
        ("//", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            if b == 0 {
                return Err(eval_err("zero_divisor"));
            }
            I(a.checked_div(b).ok_or_else(overflow)?)
        }
        ("mod", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            if b == 0 {
                return Err(eval_err("zero_divisor"));
            }
            let r = a.wrapping_rem(b);
            I(if r != 0 && (r < 0) != (b < 0) {
                r + b
            } else {
                r
            })
        }
        ("rem", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            if b == 0 {
                return Err(eval_err("zero_divisor"));
            }
            I(a.wrapping_rem(b))
        }
        ("div", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            if b == 0 {
                return Err(eval_err("zero_divisor"));
            }
            let q = a.checked_div(b).ok_or_else(overflow)?;
            I(if a % b != 0 && ((a < 0) != (b < 0)) {
                q - 1
            } else {
                q
            })
        }
        // Equal values of mixed types give the float, as in SWI (`max(1, 1.0)` is `1.0`).
        ("min" | "max", _, _) => match (cmp_num(&y, &x), f.name(), &y) {
            (Ordering::Less, "min", _) | (Ordering::Greater, "max", _) => y,
            (Ordering::Equal, _, F(_)) => y,
            _ => x,
        },
        ("**", I(a), I(b)) => {
            if b < 0 {
                check_float((a as f64).powf(b as f64))?
            } else {
                int_pow(a, b)?
            }
        }
        ("^", I(a), I(b)) => int_pow(a, b)?,
        ("**" | "^", _, _) => check_float(x.f().powf(y.f()))?,
        ("atan2" | "atan", _, _) => F(x.f().atan2(y.f())),
        ("log", _, _) => {
            if x.f() <= 0.0 || y.f() <= 0.0 {
                return Err(eval_err("undefined"));
            }
            F(y.f().ln() / x.f().ln())
        }
        ("copysign", _, _) => F(x.f().copysign(y.f())),
        (">>", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            I(if b >= 64 {
                if a < 0 {
                    -1
                } else {
                    0
                }
            } else if b < 0 {
                a.checked_shl((-b) as u32).ok_or_else(overflow)?
            } else {
                a >> b
            })
        }
        ("<<", _, _) => {
            let (a, b) = (int(x)?, int(y)?);
            if !(0..64).contains(&b) {
                return Err(overflow());
            }
            let r = a << b;
            if (r >> b) != a {
                return Err(overflow());
            }
            I(r)
        }
        ("/\\", _, _) => I(int(x)? & int(y)?),
        ("\\/", _, _) => I(int(x)? | int(y)?),
        ("xor", _, _) => I(int(x)? ^ int(y)?),
        ("gcd", _, _) => {
            let (mut a, mut b) = (int(x)?.unsigned_abs(), int(y)?.unsigned_abs());
            while b != 0 {
                let t = a % b;
                a = b;
                b = t;
            }
            I(i64::try_from(a).map_err(|_| overflow())?)
        }
        ("truncate", _, _) => return Err(unknown(f, 2)),
        _ => return Err(unknown(f, 2)),
    })
}

/// Arithmetic built-ins; `None` when `b` is not one of them.
pub(crate) fn det(s: &mut Solver, b: B, p: u32) -> KrResult<Option<Flow>> {
    let ok = |x: bool| if x { Flow::True } else { Flow::Fail };
    Ok(Some(match b {
        B::Is => {
            let v = s.eval(s.a(p, 1))?.cell(&mut s.m.st);
            let x = s.a(p, 0);
            ok(s.unify(x, v))
        }
        B::ArEq | B::ArNe | B::ArLt | B::ArLe | B::ArGt | B::ArGe => {
            let x = s.eval(s.a(p, 0))?;
            let y = s.eval(s.a(p, 1))?;
            let o = cmp_num(&x, &y);
            let nan = x.f().is_nan() || y.f().is_nan();
            ok(!nan
                && match b {
                    B::ArEq => o == Ordering::Equal,
                    B::ArNe => o != Ordering::Equal,
                    B::ArLt => o == Ordering::Less,
                    B::ArLe => o != Ordering::Greater,
                    B::ArGt => o == Ordering::Greater,
                    _ => o != Ordering::Less,
                })
        }
        B::Succ => match (s.ad(p, 0), s.ad(p, 1)) {
            (Cell::Int(x), y) => {
                if x < 0 {
                    return Err(type_error(s, "not_less_than_zero", Cell::Int(x), "succ", 2));
                }
                let v = Cell::Int(x.checked_add(1).ok_or_else(overflow)?);
                ok(s.unify(y, v))
            }
            (x @ Cell::Ref(_), Cell::Int(y)) => {
                if y < 0 {
                    return Err(type_error(s, "not_less_than_zero", Cell::Int(y), "succ", 2));
                }
                if y == 0 {
                    Flow::Fail
                } else {
                    ok(s.unify(x, Cell::Int(y - 1)))
                }
            }
            (Cell::Ref(_), Cell::Ref(_)) => return Err(inst("succ", 2)),
            (Cell::Ref(_), other) | (other, _) => {
                return Err(type_error(s, "integer", other, "succ", 2))
            }
        },
        B::Plus => {
            let (x, y, z) = (s.ad(p, 0), s.ad(p, 1), s.ad(p, 2));
            match (x, y, z) {
                (Cell::Int(a), Cell::Int(b), _) => {
                    ok(s.unify(z, Cell::Int(a.checked_add(b).ok_or_else(overflow)?)))
                }
                (Cell::Int(a), _, Cell::Int(c)) => {
                    ok(s.unify(y, Cell::Int(c.checked_sub(a).ok_or_else(overflow)?)))
                }
                (_, Cell::Int(b), Cell::Int(c)) => {
                    ok(s.unify(x, Cell::Int(c.checked_sub(b).ok_or_else(overflow)?)))
                }
                _ => return Err(inst("plus", 3)),
            }
        }
        B::RandomBetween => {
            let lo = super::builtins::int_arg(s, p, 0, "random_between", 3)?;
            let hi = super::builtins::int_arg(s, p, 1, "random_between", 3)?;
            if hi < lo {
                return Ok(Some(Flow::Fail));
            }
            let v = s.cx.rng.gen_range(lo..=hi);
            let x = s.a(p, 2);
            ok(s.unify(x, Cell::Int(v)))
        }
        B::RandomFloat => {
            let v = s.cx.rng.gen::<f64>();
            let x = s.a(p, 0);
            ok(s.unify(x, Cell::Flt(v)))
        }
        B::RandomMember => {
            let (items, end) = s.m.st.list_items(s.a(p, 1));
            if !matches!(end, Cell::Atom(n) if n == wk::NIL) {
                return Err(inst("random_member", 2));
            }
            if items.is_empty() {
                return Ok(Some(Flow::Fail));
            }
            let i = s.cx.rng.gen_range(0..items.len());
            let x = s.a(p, 0);
            ok(s.unify(x, items[i]))
        }
        B::RandomPermutation => {
            let (mut items, end) = s.m.st.list_items(s.a(p, 0));
            if !matches!(end, Cell::Atom(n) if n == wk::NIL) {
                return Err(inst("random_permutation", 2));
            }
            for i in (1..items.len()).rev() {
                let j = s.cx.rng.gen_range(0..=i);
                items.swap(i, j);
            }
            let l = s.m.st.new_list(&items, Cell::Atom(wk::NIL));
            let y = s.a(p, 1);
            ok(s.unify(l, y))
        }
        B::SumEval => {
            let (items, _) = s.m.st.list_items(s.a(p, 0));
            let mut acc = Num::I(0);
            for it in items {
                let v = s.eval(it)?;
                acc = eval2(wk::PLUS, acc, v)?;
            }
            let y = s.a(p, 1);
            let v = acc.cell(&mut s.m.st);
            ok(s.unify(y, v))
        }
        B::MaxEval => {
            // '$max_eval'(Items, max|min, Result): numeric extreme of evaluated items.
            let (items, _) = s.m.st.list_items(s.a(p, 0));
            let want_max = matches!(s.ad(p, 1), Cell::Atom(m) if m.name() == "max");
            let mut best: Option<Num> = None;
            for it in items {
                let v = s.eval(it)?;
                best = Some(match best {
                    None => v,
                    Some(b) => {
                        let o = cmp_num(&v, &b);
                        if (want_max && o == Ordering::Greater)
                            || (!want_max && o == Ordering::Less)
                        {
                            v
                        } else {
                            b
                        }
                    }
                });
            }
            match best {
                None => Flow::Fail,
                Some(v) => {
                    let y = s.a(p, 2);
                    let v = v.cell(&mut s.m.st);
                    ok(s.unify(y, v))
                }
            }
        }
        _ => return Ok(None),
    }))
}

/// Numeric comparison of two number cells (for list built-ins).
pub(crate) fn compare_cells(s: &Solver, a: Cell, b: Cell, name: &str) -> KrResult<Ordering> {
    let n = |c: Cell| match s.m.st.deref(c) {
        Cell::Int(i) => Ok(Num::I(i)),
        Cell::Flt(f) => Ok(Num::F(f)),
        Cell::Big(i) => bigint::norm(s.m.st.big(i)),
        Cell::Ref(_) => Err(inst(name, 2)),
        other => Err(type_error(s, "number", other, name, 2)),
    };
    Ok(cmp_num(&n(a)?, &n(b)?))
}
