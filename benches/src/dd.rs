//! Double-double arithmetic: a value is hi + lo with |lo| ≤ ½ulp(hi), about
//! 106 significant bits (unit roundoff u ≈ 2⁻¹⁰⁵ ≈ 2.5·10⁻³²).
//!
//! Algorithms (Dekker 1971; Shewchuk 1997; Hida, Li & Bailey 2001, "QD"):
//! error-free `two_sum` and `two_prod` (Dekker's split, no FMA needed), the
//! accurate ("IEEE") addition, multiplication with the cross terms, division
//! by three quotient digits, square root by one Newton step from the f64
//! root, exp by argument reduction (x = k ln2 + r, r/2¹⁰) with a Taylor series
//! and ten squarings, ln by two Newton steps on exp. Relative errors: + − ×
//! ≈ 2u, ÷ √ ≈ 4u, exp ln ≈ 10u (checked in the tests against identities and
//! exactly representable results). This is the number type of the
//! high-precision reference ([`crate::reference`]); it is never timed.

use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::real::Real;

/// A double-double number hi + lo.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

#[inline]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let t = SPLITTER * a;
    let hi = t - (t - a);
    (hi, a - hi)
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if !p.is_finite() {
        return (p, 0.0);
    }
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl Dd {
    pub const fn new(hi: f64, lo: f64) -> Self {
        Dd { hi, lo }
    }

    /// ln 2 to double-double precision.
    pub const LN2: Dd = Dd::new(std::f64::consts::LN_2, 2.319_046_813_846_299_6e-17);

    #[inline]
    fn renorm(hi: f64, lo: f64) -> Self {
        if !hi.is_finite() {
            return Dd::new(hi, 0.0);
        }
        let (h, l) = quick_two_sum(hi, lo);
        Dd::new(h, l)
    }

    /// Multiply by a power of two (exact).
    pub fn ldexp(self, k: i32) -> Self {
        let s = 2f64.powi(k);
        Dd::new(self.hi * s, self.lo * s)
    }

    /// An integer as a double-double (exact for |n| < 2¹⁰⁶).
    pub fn from_i128(n: i128) -> Self {
        let hi = n as f64;
        let rest = n - hi as i128;
        Dd::renorm(hi, rest as f64)
    }
}

impl Add for Dd {
    type Output = Dd;
    #[inline]
    fn add(self, b: Dd) -> Dd {
        let (s1, s2) = two_sum(self.hi, b.hi);
        if !s1.is_finite() {
            return Dd::new(s1, 0.0);
        }
        let (t1, t2) = two_sum(self.lo, b.lo);
        let (s1, s2) = quick_two_sum(s1, s2 + t1);
        Dd::renorm(s1, s2 + t2)
    }
}

impl Neg for Dd {
    type Output = Dd;
    #[inline]
    fn neg(self) -> Dd {
        Dd::new(-self.hi, -self.lo)
    }
}

impl Sub for Dd {
    type Output = Dd;
    #[inline]
    fn sub(self, b: Dd) -> Dd {
        self + (-b)
    }
}

impl Mul for Dd {
    type Output = Dd;
    #[inline]
    fn mul(self, b: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, b.hi);
        if !p.is_finite() {
            return Dd::new(p, 0.0);
        }
        Dd::renorm(p, e + (self.hi * b.lo + self.lo * b.hi))
    }
}

impl Div for Dd {
    type Output = Dd;
    #[inline]
    fn div(self, b: Dd) -> Dd {
        let q1 = self.hi / b.hi;
        if !q1.is_finite() || b.hi == 0.0 {
            return Dd::new(q1, 0.0);
        }
        let r = self - b * Dd::new(q1, 0.0);
        let q2 = r.hi / b.hi;
        let r = r - b * Dd::new(q2, 0.0);
        let q3 = r.hi / b.hi;
        let (h, l) = quick_two_sum(q1, q2);
        Dd::new(h, l) + Dd::new(q3, 0.0)
    }
}

impl PartialOrd for Dd {
    fn partial_cmp(&self, o: &Dd) -> Option<std::cmp::Ordering> {
        match self.hi.partial_cmp(&o.hi) {
            Some(std::cmp::Ordering::Equal) => self.lo.partial_cmp(&o.lo),
            c => c,
        }
    }
}

impl Real for Dd {
    const EPS: f64 = 2.465_190_328_815_662e-32; // 2^-105

    #[inline]
    fn from_f64(x: f64) -> Self {
        Dd::new(x, 0.0)
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    fn from_ratio(n: i128, d: i128) -> Self {
        Dd::from_i128(n) / Dd::from_i128(d)
    }

    fn sqrt(self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Dd::new(self.hi.sqrt(), 0.0);
        }
        let x = self.hi.sqrt();
        let x2 = Dd::from_f64(x) * Dd::from_f64(x);
        let corr = (self - x2).hi / (2.0 * x);
        let (h, l) = two_sum(x, corr);
        Dd::renorm(h, l)
    }

    fn exp(self) -> Self {
        if self.hi > 709.0 {
            return Dd::from_f64(f64::INFINITY);
        }
        if self.hi < -745.0 {
            return Dd::zero();
        }
        if !self.hi.is_finite() {
            return Dd::from_f64(self.hi.exp());
        }
        let k = (self.hi / Dd::LN2.hi).round();
        let r = (self - Dd::LN2 * Dd::from_f64(k)).ldexp(-10);
        // Taylor series of e^r − 1 for |r| ≤ 3.4e-4: 12 terms reach 1e-50.
        let mut term = r;
        let mut sum = r;
        for n in 2..=14 {
            term = term * r / Dd::from_f64(n as f64);
            sum = sum + term;
            if term.hi.abs() < 1e-36 * sum.hi.abs().max(1e-300) {
                break;
            }
        }
        // (1 + s)² − 1 = 2s + s², ten times: e^{r·2^10} − 1
        for _ in 0..10 {
            sum = sum.ldexp(1) + sum * sum;
        }
        (sum + Dd::one()).ldexp(k as i32)
    }

    fn ln(self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Dd::from_f64(self.hi.ln());
        }
        let mut x = Dd::from_f64(self.hi.ln());
        for _ in 0..2 {
            x = x + self * (-x).exp() - Dd::one();
        }
        x
    }

    fn powf(self, y: Self) -> Self {
        if self.hi < 0.0 {
            return Dd::from_f64(f64::NAN);
        }
        if self.hi == 0.0 {
            return Dd::from_f64(0f64.powf(y.hi));
        }
        (y * self.ln()).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: Dd, b: Dd) -> f64 {
        ((a - b).to_f64() / b.to_f64()).abs()
    }

    #[test]
    fn arithmetic_is_double_double_accurate() {
        let third = Dd::one() / Dd::from_f64(3.0);
        assert!(rel(third * Dd::from_f64(3.0), Dd::one()) < 1e-31);
        let s = Dd::from_f64(2.0).sqrt();
        assert!(rel(s * s, Dd::from_f64(2.0)) < 1e-31);
        // 1 + 2^-80 survives (f64 would drop it)
        let tiny = Dd::from_f64(2f64.powi(-80));
        assert_eq!(((Dd::one() + tiny) - Dd::one()).to_f64(), 2f64.powi(-80));
    }

    #[test]
    fn exp_and_ln_are_inverse_and_exact_on_known_values() {
        for x in [-30.0, -1.0, -1e-9, 0.3, 1.0, 7.5, 100.0] {
            let x = Dd::from_f64(x);
            let back = x.exp().ln();
            assert!((back - x).to_f64().abs() <= 1e-30 * x.to_f64().abs().max(1.0));
        }
        let l2 = Dd::from_f64(2.0).ln();
        assert!(rel(l2, Dd::LN2) < 1e-30);
        assert!(rel(Dd::from_f64(4.0).ln(), Dd::LN2.ldexp(1)) < 1e-30);
        assert!(
            rel(
                Dd::from_f64(8.0).powf(Dd::one() / Dd::from_f64(3.0)),
                Dd::from_f64(2.0)
            ) < 1e-30
        );
        assert!(rel(Dd::from_f64(4.0).powf(Dd::from_f64(1.5)), Dd::from_f64(8.0)) < 1e-30);
    }
}
