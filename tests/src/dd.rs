//! Double-double arithmetic: a value is `hi + lo` with |lo| ≤ ulp(hi)/2,
//! about 106 significant bits (unit roundoff u ≈ 2⁻¹⁰⁴ ≈ 5·10⁻³²).
//!
//! Error-free transformations (Knuth's two-sum, FMA two-product) give the
//! basic operations; `sqrt` is one Newton step on the f64 root; `exp` uses
//! x = k·ln2 + r, r/2¹⁰, a degree-22 Taylor series and ten squarings; `ln`
//! is one Newton step y ← y + x·e⁻ʸ − 1 on the f64 logarithm. Each is
//! accurate to a few u relative (enough for a reference that must be far
//! more accurate than f64, not correctly rounded). Non-finite inputs give
//! non-finite outputs (NaN for the log of a negative number, as in f64).
//!
//! This is the number type of the independent references: the `hard_*`
//! tests (`tests/tests/hard_ref`) and the benchmark report's accuracy
//! columns (`ecc-benches`, through [`crate::real::Real`]). It is never timed.

use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A double-double number `hi + lo`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dd {
    /// The leading part (the value rounded to f64).
    pub hi: f64,
    /// The trailing part.
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
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Dd {
    /// Zero.
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };
    /// One.
    pub const ONE: Dd = Dd { hi: 1.0, lo: 0.0 };
    /// ln 2 to double-double precision.
    pub const LN2: Dd = Dd {
        hi: std::f64::consts::LN_2,
        lo: 2.319_046_813_846_299_6e-17,
    };
    /// NaN.
    pub const NAN: Dd = Dd {
        hi: f64::NAN,
        lo: f64::NAN,
    };

    /// The exact value of an f64.
    #[inline]
    pub const fn from_f64(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// Nearest f64.
    #[inline]
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// Both parts finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    /// |self|.
    #[inline]
    pub fn abs(self) -> Dd {
        if self.hi < 0.0 { -self } else { self }
    }

    /// Exact scaling by a power of two (`p` must be one: other factors
    /// would round both parts separately; multiply by `Dd::from_f64(p)`).
    #[inline]
    pub fn scale(self, p: f64) -> Dd {
        debug_assert!(p.abs().log2().fract() == 0.0, "scale by {p}");
        Dd {
            hi: self.hi * p,
            lo: self.lo * p,
        }
    }

    /// Square root (NaN for negative input).
    pub fn sqrt(self) -> Dd {
        if self.hi == 0.0 {
            return Dd::ZERO;
        }
        if self.hi < 0.0 || !self.is_finite() {
            return Dd::from_f64(self.hi.sqrt());
        }
        let y = self.hi.sqrt();
        let yy = Dd::from_f64(y) * Dd::from_f64(y);
        let corr = (self - yy).hi / (2.0 * y);
        let (h, l) = two_sum(y, corr);
        Dd { hi: h, lo: l }
    }

    /// eˣ.
    pub fn exp(self) -> Dd {
        if !self.is_finite() {
            return Dd::from_f64(self.hi.exp());
        }
        if self.hi > 709.0 {
            return Dd::from_f64(f64::INFINITY);
        }
        if self.hi < -745.0 {
            return Dd::ZERO;
        }
        let k = (self.hi / std::f64::consts::LN_2).round();
        let r = (self - Dd::LN2 * Dd::from_f64(k)).scale(1.0 / 1024.0);
        // Taylor series of e^r − 1 for |r| ≤ ln2/2048 ≈ 3.4e-4: 22 terms ≫ enough.
        let mut term = r;
        let mut sum = r;
        for n in 2..=22 {
            term = term * r / Dd::from_f64(n as f64);
            sum = sum + term;
            if term.hi.abs() < 1e-40 * sum.hi.abs().max(1e-300) {
                break;
            }
        }
        // (1 + s)² − 1 = s(2 + s): square ten times without losing the small part.
        for _ in 0..10 {
            sum = sum * (sum + Dd::from_f64(2.0));
        }
        let e = sum + Dd::ONE;
        // 2^k in two halves: 2^k alone underflows for k < −1074.
        let (k1, k2) = (k as i32 / 2, k as i32 - k as i32 / 2);
        e.scale(2f64.powi(k1)).scale(2f64.powi(k2))
    }

    /// Natural logarithm (NaN for negative input, −∞ at 0).
    pub fn ln(self) -> Dd {
        if self.hi <= 0.0 || !self.is_finite() {
            return Dd::from_f64(self.hi.ln());
        }
        let y = Dd::from_f64(self.hi.ln());
        y + self * (-y).exp() - Dd::ONE
    }

    /// selfⁿ by repeated squaring (n may be negative).
    pub fn powi(self, n: i64) -> Dd {
        let mut base = self;
        let mut e = n.unsigned_abs();
        let mut acc = Dd::ONE;
        while e > 0 {
            if e & 1 == 1 {
                acc = acc * base;
            }
            base = base * base;
            e >>= 1;
        }
        if n < 0 { Dd::ONE / acc } else { acc }
    }

    /// An integer, exactly for |n| < 2¹⁰⁶.
    pub fn from_i128(n: i128) -> Dd {
        let hi = n as f64;
        let rest = n - hi as i128;
        let (hi, lo) = quick_two_sum(hi, rest as f64);
        Dd { hi, lo }
    }

    /// self · 2ᵏ (exact unless it over- or underflows).
    pub fn ldexp(self, k: i32) -> Dd {
        let (k1, k2) = (k / 2, k - k / 2);
        self.scale(2f64.powi(k1)).scale(2f64.powi(k2))
    }

    /// selfʸ for self ≥ 0 as exp(y ln self) (NaN for self < 0, as `powf`
    /// for a non-integer y; 0ʸ as in f64).
    pub fn powf(self, y: Dd) -> Dd {
        if self.hi < 0.0 {
            return Dd::NAN;
        }
        if self.hi == 0.0 {
            return Dd::from_f64(0f64.powf(y.hi));
        }
        (y * self.ln()).exp()
    }

    /// A decimal integer given as text (`-123`), accurate to double-double.
    pub fn from_decimal_integer(text: &str) -> Option<Dd> {
        let (neg, digits) = match text.strip_prefix('-') {
            Some(d) => (true, d),
            None => (false, text),
        };
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let mut acc = Dd::ZERO;
        for chunk in digits.as_bytes().chunks(15) {
            let v: f64 = std::str::from_utf8(chunk).ok()?.parse().ok()?;
            acc = acc * Dd::from_f64(10f64.powi(chunk.len() as i32)) + Dd::from_f64(v);
        }
        Some(if neg { -acc } else { acc })
    }
}

impl Neg for Dd {
    type Output = Dd;
    #[inline]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Add for Dd {
    type Output = Dd;
    #[inline]
    fn add(self, b: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        if hi.is_finite() {
            Dd { hi, lo }
        } else {
            Dd::from_f64(self.hi + b.hi)
        }
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
        let e = e + (self.hi * b.lo + self.lo * b.hi);
        let (hi, lo) = quick_two_sum(p, e);
        if hi.is_finite() {
            Dd { hi, lo }
        } else {
            Dd::from_f64(self.hi * b.hi)
        }
    }
}

impl Div for Dd {
    type Output = Dd;
    fn div(self, b: Dd) -> Dd {
        if !b.is_finite() || b.hi == 0.0 || !self.is_finite() {
            return Dd::from_f64(self.hi / b.hi);
        }
        // Long division: three f64 quotient digits.
        let q1 = self.hi / b.hi;
        let r = self - b * Dd::from_f64(q1);
        let q2 = r.hi / b.hi;
        let r = r - b * Dd::from_f64(q2);
        let q3 = r.hi / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Dd { hi, lo } + Dd::from_f64(q3)
    }
}

impl PartialOrd for Dd {
    fn partial_cmp(&self, other: &Dd) -> Option<Ordering> {
        match self.hi.partial_cmp(&other.hi)? {
            Ordering::Equal => self.lo.partial_cmp(&other.lo),
            o => Some(o),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: Dd, b: Dd) -> f64 {
        ((a - b).to_f64() / b.to_f64()).abs()
    }

    #[test]
    fn identities_hold_to_double_double_precision() {
        // Tolerances: a few u ≈ 5e-32 each; 1e-29 leaves room for ~100 u.
        let x = Dd::from_f64(1.7) / Dd::from_f64(3.0);
        assert!(rel(x * Dd::from_f64(3.0), Dd::from_f64(1.7)) < 1e-30);
        let s = Dd::from_f64(2.0).sqrt();
        assert!(rel(s * s, Dd::from_f64(2.0)) < 1e-30);
        for v in [1e-8, 0.3, 1.0, 2.5, 40.0, -3.7] {
            let x = Dd::from_f64(v) / Dd::from_f64(7.0);
            assert!(rel(x.exp().ln(), x) < 1e-29, "ln exp {v}");
            let y = Dd::from_f64(v.abs() + 0.1);
            assert!(rel(y.ln().exp(), y) < 1e-29, "exp ln {v}");
        }
        // e = Σ 1/n! to 32 digits: 2.71828182845904523536028747135266
        let e = Dd::ONE.exp();
        let want = Dd::from_f64(std::f64::consts::E) + Dd::from_f64(1.445_646_891_729_250_2e-16);
        assert!(rel(e, want) < 1e-30, "{e:?}");
        assert!(Dd::from_f64(-1.0).ln().hi.is_nan());
        assert_eq!(Dd::ZERO.ln().hi, f64::NEG_INFINITY);
        let big = Dd::from_decimal_integer("123456789012345678901234567890").unwrap();
        assert!(rel(big, Dd::from_f64(1.2345678901234568e29)) < 1e-16);
        assert!(
            rel(
                Dd::from_f64(1.1).powi(-7) * Dd::from_f64(1.1).powi(7),
                Dd::ONE
            ) < 1e-30
        );
    }

    #[test]
    fn integers_powers_and_ratios() {
        // 1 + 2^-80 survives (f64 would drop it)
        let tiny = Dd::from_f64(2f64.powi(-80));
        assert_eq!(((Dd::ONE + tiny) - Dd::ONE).to_f64(), 2f64.powi(-80));
        let n = (1i128 << 100) + 12345;
        let d = Dd::from_i128(n);
        assert_eq!(d.hi as i128 + d.lo as i128, n);
        assert!(rel(Dd::from_f64(4.0).ln(), Dd::LN2.ldexp(1)) < 1e-30);
        let third = Dd::ONE / Dd::from_f64(3.0);
        assert!(rel(Dd::from_f64(8.0).powf(third), Dd::from_f64(2.0)) < 1e-30);
        assert!(rel(Dd::from_f64(4.0).powf(Dd::from_f64(1.5)), Dd::from_f64(8.0)) < 1e-30);
        assert!(Dd::from_f64(-2.0).powf(Dd::from_f64(0.5)).hi.is_nan());
        assert_eq!(Dd::ONE.ldexp(-1074).hi, f64::from_bits(1));
    }
}
