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

/// gcd(|a|, |b|) (0 when both are 0). When one side fits a machine word the
/// other is first reduced modulo it (linear in its size): `num-bigint`'s
/// binary gcd costs O(bits²) word operations even for gcd(a, 1), which made
/// canonicalising sums with many distinct coefficient denominators (content
/// lcm(1…n) ≈ 1.44 n bits, e.g. Σ_k exp(I1/k)) quadratic per operation.
pub fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    let small = |x: &BigInt| x.magnitude().to_u64();
    match (small(a), small(b)) {
        (Some(x), Some(y)) => BigInt::from(num_integer::Integer::gcd(&x, &y)),
        (_, Some(0)) => a.abs(),
        (Some(0), _) => b.abs(),
        (_, Some(y)) => word_gcd(a, y),
        (Some(x), _) => word_gcd(b, x),
        _ => num_integer::Integer::gcd(a, b),
    }
}

/// gcd(|a|, y) for a word y > 0.
fn word_gcd(a: &BigInt, y: u64) -> BigInt {
    let r = (a.magnitude() % y).to_u64().unwrap_or(0);
    BigInt::from(num_integer::Integer::gcd(&r, &y))
}

/// lcm(|a|, |b|) with the fast [`gcd`].
pub fn lcm(a: &BigInt, b: &BigInt) -> BigInt {
    if a.is_zero() || b.is_zero() {
        return BigInt::zero();
    }
    (a / gcd(a, b) * b).abs()
}

/// `a + b`, exactly what `BigRational`'s `+` gives (reduced, positive
/// denominator), with the fast [`gcd`] and Knuth's reduction (TAOCP 4.5.1):
/// with g = gcd(b₁, b₂), t = a₁(b₂/g) + a₂(b₁/g) and g₂ = gcd(t, g),
/// a₁/b₁ + a₂/b₂ = (t/g₂) / ((b₁/g)(b₂/g₂)) in lowest terms — only gcds
/// with g, which is small when one denominator is, so summing n fractions
/// whose common denominator grows to O(n) bits costs O(n) per addition.
pub fn add(a: &BigRational, b: &BigRational) -> BigRational {
    if a.is_zero() {
        return b.clone();
    }
    if b.is_zero() {
        return a.clone();
    }
    let (b1, b2) = (a.denom(), b.denom());
    let g = gcd(b1, b2);
    if g.is_one() {
        let n = a.numer() * b2 + b.numer() * b1;
        return BigRational::new_raw(n, b1 * b2);
    }
    let t = a.numer() * (b2 / &g) + b.numer() * (b1 / &g);
    if t.is_zero() {
        return BigRational::zero();
    }
    let g2 = gcd(&t, &g);
    BigRational::new_raw(&t / &g2, (b1 / &g) * (b2 / &g2))
}

/// `a · b`, exactly what `BigRational`'s `*` gives, with the fast [`gcd`]
/// (cross-cancelled: the result is reduced without a final gcd).
pub fn mul(a: &BigRational, b: &BigRational) -> BigRational {
    if a.is_zero() || b.is_zero() {
        return BigRational::zero();
    }
    if a.is_one() {
        return b.clone();
    }
    if b.is_one() {
        return a.clone();
    }
    let g1 = gcd(a.numer(), b.denom());
    let g2 = gcd(b.numer(), a.denom());
    let n = (a.numer() / &g1) * (b.numer() / &g2);
    let d = (a.denom() / &g2) * (b.denom() / &g1);
    BigRational::new_raw(n, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rationals with small, word-sized and multi-word parts, both signs.
    fn samples() -> Vec<BigRational> {
        let big = |k: u32| num_traits::pow(BigInt::from(3), k as usize) * BigInt::from(7 + k);
        let mut ints: Vec<BigInt> = vec![0.into(), 1.into(), 2.into(), 6.into(), 35.into()];
        ints.push(BigInt::from(u64::MAX));
        ints.push(BigInt::from(u64::MAX) * 2);
        ints.extend([40, 90, 300].map(big));
        let mut out = Vec::new();
        for n in &ints {
            for d in ints.iter().filter(|d| !d.is_zero()) {
                out.push(BigRational::new(n.clone(), d.clone()));
                out.push(-BigRational::new(n.clone(), d.clone()));
            }
        }
        out
    }

    #[test]
    fn fast_arithmetic_is_num_rational_arithmetic() {
        let s = samples();
        for a in &s {
            for b in &s {
                let (x, y) = (add(a, b), a + b);
                assert_eq!((x.numer(), x.denom()), (y.numer(), y.denom()), "{a} + {b}");
                let (x, y) = (mul(a, b), a * b);
                assert_eq!((x.numer(), x.denom()), (y.numer(), y.denom()), "{a} * {b}");
                let (an, bn) = (a.numer(), b.numer());
                assert_eq!(
                    gcd(an, bn),
                    num_integer::Integer::gcd(an, bn),
                    "gcd({an}, {bn})"
                );
                assert_eq!(
                    lcm(an, bn),
                    num_integer::Integer::lcm(an, bn),
                    "lcm({an}, {bn})"
                );
            }
        }
    }
}
