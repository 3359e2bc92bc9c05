//! Exact rational helpers.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Largest |n| for which `r^n` is folded exactly (larger powers stay symbolic).
pub const MAX_FOLD_EXPONENT: u32 = 4096;
/// Largest result size (in bits of numerator + denominator) produced by folding.
const MAX_FOLD_BITS: u64 = 1 << 16;

/// `n` as a rational.
pub fn int(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

/// `r` as `i64` if it is an integer that fits.
pub fn as_i64(r: &BigRational) -> Option<i64> {
    if r.is_integer() {
        r.to_integer().to_i64()
    } else {
        None
    }
}

/// `r` as f64 (nearest; ±∞ when out of range).
pub fn to_f64(r: &BigRational) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

/// `base^n` exactly, when the exponent and result are of reasonable size and
/// the power is defined (`0^-n` is not).
pub fn pow_int(base: &BigRational, n: i64) -> Option<BigRational> {
    if n.unsigned_abs() > MAX_FOLD_EXPONENT as u64 {
        return if base.is_zero() && n > 0 || base.is_one() {
            Some(base.clone())
        } else {
            None
        };
    }
    if base.is_zero() && n < 0 {
        return None;
    }
    let bits = base.numer().bits() + base.denom().bits();
    if bits.saturating_mul(n.unsigned_abs()) > MAX_FOLD_BITS {
        return None;
    }
    let p = num_traits::pow(base.clone(), n.unsigned_abs() as usize);
    Some(if n < 0 { p.recip() } else { p })
}

/// `base^(p/q)` exactly when it is rational (e.g. 4^(1/2) = 2, (-8)^(1/3) = -2).
pub fn pow_rat(base: &BigRational, e: &BigRational) -> Option<BigRational> {
    if e.is_integer() {
        return pow_int(base, as_i64(e)?);
    }
    let q = e.denom().to_u32()?;
    if q > 64 {
        return None;
    }
    if base.is_negative() && q % 2 == 0 {
        return None;
    }
    let root = |n: &BigInt| -> Option<BigInt> {
        let r = if n.is_negative() {
            -((-n).nth_root(q))
        } else {
            n.nth_root(q)
        };
        (num_traits::pow(r.clone(), q as usize) == *n).then_some(r)
    };
    let r = BigRational::new(root(base.numer())?, root(base.denom())?);
    pow_int(&r, e.numer().to_i64()?)
}

/// Parse a decimal literal (`12`, `0.25`, `.5`, `1e-3`, `2.5E+4`) exactly.
/// `None` when the literal is absurdly large (more than 4096 digits or
/// |exponent| > 4096).
pub fn parse_decimal(text: &str) -> Option<BigRational> {
    let (mantissa, exp) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], text[i + 1..].parse::<i64>().ok()?),
        None => (text, 0),
    };
    let (int_part, frac_part) = match mantissa.find('.') {
        Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
        None => (mantissa, ""),
    };
    if int_part.len() + frac_part.len() > MAX_FOLD_EXPONENT as usize {
        return None;
    }
    let digits = format!("{int_part}{frac_part}");
    let digits = if digits.is_empty() {
        "0".to_string()
    } else {
        digits
    };
    let n: BigInt = digits.parse().ok()?;
    let scale = exp.checked_sub(frac_part.len() as i64)?;
    if scale.unsigned_abs() > MAX_FOLD_EXPONENT as u64 {
        return None;
    }
    let ten = BigInt::from(10u32);
    let p = num_traits::pow(ten, scale.unsigned_abs() as usize);
    Some(if scale >= 0 {
        BigRational::from_integer(n * p)
    } else {
        BigRational::new(n, p)
    })
}

/// `|r| == 1`?
pub fn is_unit(r: &BigRational) -> bool {
    r.abs().is_one()
}
