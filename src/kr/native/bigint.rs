//! Unbounded integers in arithmetic, as in SWI-Prolog: evaluation runs on `i64` and comes here
//! only when an operand is already big or a 64-bit operation overflowed; results that fit in
//! 64 bits go back to `Num::I`.

use super::arith::{eval_err, Num};
use crate::kr::error::{KrError, KrResult};
use crate::term::{Sym, Term};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{FromPrimitive, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::sync::Arc;

/// Largest big integer a computation may produce, in bits (about 300,000 decimal digits), so
/// `2^(10^12)` is an error rather than an exhausted memory.
const MAX_BITS: u64 = 1 << 20;

/// A big-integer result, normalised to `Num::I` when it fits.
pub(crate) fn norm(n: BigInt) -> KrResult<Num> {
    if n.bits() > MAX_BITS {
        return Err(KrError::iso(
            Term::compound("resource_error", vec![Term::atom("big_integer")]),
            None,
        ));
    }
    Ok(match n.to_i64() {
        Some(i) => Num::I(i),
        None => Num::B(Arc::new(n)),
    })
}

/// The value of an integer `Num` as a big integer (`None` for floats).
pub(crate) fn big(n: &Num) -> Option<BigInt> {
    match n {
        Num::I(i) => Some(BigInt::from(*i)),
        Num::B(b) => Some((**b).clone()),
        Num::F(_) => None,
    }
}

/// The float nearest to a big integer.
pub(crate) fn to_f64(b: &BigInt) -> f64 {
    b.to_f64().unwrap_or(if b.is_negative() {
        f64::NEG_INFINITY
    } else {
        f64::INFINITY
    })
}

/// Numeric comparison when at least one side may be big.
pub(crate) fn compare(a: &Num, b: &Num) -> Ordering {
    match (big(a), big(b)) {
        (Some(x), Some(y)) => x.cmp(&y),
        _ => a.f().partial_cmp(&b.f()).unwrap_or(Ordering::Equal),
    }
}

/// A float rounded by `round` to an integer of any size.
pub(crate) fn from_float(f: f64) -> KrResult<Num> {
    if !f.is_finite() {
        return Err(eval_err("undefined"));
    }
    norm(BigInt::from_f64(f).unwrap_or_default())
}

fn need_int(n: &Num) -> KrResult<BigInt> {
    big(n).ok_or_else(|| {
        KrError::iso(
            Term::compound("type_error", vec![Term::atom("integer"), Term::from(n.f())]),
            None,
        )
    })
}

fn small_exponent(e: &BigInt) -> KrResult<u32> {
    e.to_u32()
        .filter(|e| u64::from(*e) <= MAX_BITS)
        .ok_or_else(|| {
            KrError::iso(
                Term::compound("resource_error", vec![Term::atom("big_integer")]),
                None,
            )
        })
}

/// A unary function on an integer that is big or overflowed in 64 bits.
pub(crate) fn eval1(f: Sym, x: &Num) -> KrResult<Option<Num>> {
    if let Num::F(v) = x {
        return Ok(match f.name() {
            "integer" => Some(from_float(v.round())?),
            "truncate" => Some(from_float(v.trunc())?),
            "round" => Some(from_float(v.round())?),
            "ceiling" => Some(from_float(v.ceil())?),
            "floor" => Some(from_float(v.floor())?),
            _ => None,
        });
    }
    let b = need_int(x)?;
    Ok(Some(match f.name() {
        "-" => norm(-b)?,
        "+" | "integer" | "truncate" | "round" | "ceiling" | "floor" => norm(b)?,
        "abs" => norm(b.abs())?,
        "sign" => Num::I(if b.is_negative() { -1 } else { 1 }),
        "float" => Num::F(to_f64(&b)),
        "succ" => norm(b + 1)?,
        "\\" => norm(-b - 1)?,
        "msb" => Num::I(b.bits() as i64 - 1),
        _ => return Ok(None),
    }))
}

/// A binary function on integers at least one of which is big (or whose 64-bit result
/// overflowed); `None` when the function is not an integer one (the caller uses floats).
pub(crate) fn eval2(f: Sym, x: &Num, y: &Num) -> KrResult<Option<Num>> {
    let (Some(a), Some(b)) = (big(x), big(y)) else {
        return Ok(None);
    };
    let zero_div = || Err(eval_err("zero_divisor"));
    Ok(Some(match f.name() {
        "+" => norm(a + b)?,
        "-" => norm(a - b)?,
        "*" => norm(a * b)?,
        "/" => {
            if b.is_zero() {
                return zero_div();
            }
            if (&a % &b).is_zero() {
                norm(a / b)?
            } else {
                Num::F(to_f64(&a) / to_f64(&b))
            }
        }
        "//" | "rem" | "mod" | "div" if b.is_zero() => return zero_div(),
        "//" => norm(a / b)?,
        "rem" => norm(a % b)?,
        "mod" => norm(a.mod_floor(&b))?,
        "div" => norm(a.div_floor(&b))?,
        "min" => norm(a.min(b))?,
        "max" => norm(a.max(b))?,
        "gcd" => norm(a.gcd(&b))?,
        "/\\" => norm(a & b)?,
        "\\/" => norm(a | b)?,
        "xor" => norm(a ^ b)?,
        "<<" => norm(a << small_exponent(&b)?)?,
        ">>" => norm(a >> small_exponent(&b)?)?,
        "^" | "**" if b.is_negative() => return Ok(None),
        "^" | "**" => {
            let e = small_exponent(&b)?;
            if a.bits().saturating_mul(u64::from(e)) > MAX_BITS + 64 {
                return norm(BigInt::from(1) << (MAX_BITS + 1)).map(Some);
            }
            norm(num_traits::pow(a, e as usize))?
        }
        _ => return Ok(None),
    }))
}
