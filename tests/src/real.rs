//! A minimal real-number trait so the same code runs in `f32`, `f64` and
//! double-double ([`crate::dd::Dd`]): the benchmarks' generic element kernel
//! (f32 vs f64, in `ecc-benches`) and their high-precision reference share it.

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::dd::Dd;

/// The operations the generic kernel and the reference need.
pub trait Real:
    Copy
    + Debug
    + PartialOrd
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Unit roundoff of the type (2⁻²⁴, 2⁻⁵³, 2⁻¹⁰⁵).
    const EPS: f64;
    /// Rounded from f64 (exact for f64 and double-double).
    fn from_f64(x: f64) -> Self;
    /// Rounded to f64.
    fn to_f64(self) -> f64;
    fn sqrt(self) -> Self;
    fn ln(self) -> Self;
    fn exp(self) -> Self;
    /// x^y for x > 0 (NaN for x < 0 unless y is an integer, as `powf`).
    fn powf(self, y: Self) -> Self;
    fn abs(self) -> Self {
        if self < Self::zero() { -self } else { self }
    }
    /// n/d (rounded once for f32/f64; to double-double precision for [`crate::dd::Dd`]).
    fn from_ratio(n: i128, d: i128) -> Self {
        Self::from_f64(n as f64 / d as f64)
    }
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    fn is_finite(self) -> bool {
        self.to_f64().is_finite()
    }
    /// x^n by repeated squaring (n may be negative).
    fn powi(self, n: i32) -> Self {
        let mut base = if n < 0 { Self::one() / self } else { self };
        let mut e = n.unsigned_abs();
        let mut acc = Self::one();
        while e > 0 {
            if e & 1 == 1 {
                acc = acc * base;
            }
            base = base * base;
            e >>= 1;
        }
        acc
    }
}

macro_rules! impl_float {
    ($t:ty, $eps:expr) => {
        impl Real for $t {
            const EPS: f64 = $eps;
            #[inline]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline]
            fn ln(self) -> Self {
                <$t>::ln(self)
            }
            #[inline]
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            #[inline]
            fn powf(self, y: Self) -> Self {
                <$t>::powf(self, y)
            }
            #[inline]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline]
            fn powi(self, n: i32) -> Self {
                <$t>::powi(self, n)
            }
        }
    };
}

impl_float!(f32, 5.960_464_477_539_063e-8);
impl_float!(f64, 1.110_223_024_625_156_5e-16);

impl Real for Dd {
    const EPS: f64 = 2.465_190_328_815_662e-32; // 2^-105
    #[inline]
    fn from_f64(x: f64) -> Self {
        Dd::from_f64(x)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        Dd::to_f64(self)
    }
    fn from_ratio(n: i128, d: i128) -> Self {
        Dd::from_i128(n) / Dd::from_i128(d)
    }
    fn sqrt(self) -> Self {
        Dd::sqrt(self)
    }
    fn ln(self) -> Self {
        Dd::ln(self)
    }
    fn exp(self) -> Self {
        Dd::exp(self)
    }
    fn powf(self, y: Self) -> Self {
        Dd::powf(self, y)
    }
    fn abs(self) -> Self {
        Dd::abs(self)
    }
    fn is_finite(self) -> bool {
        Dd::is_finite(self)
    }
    fn powi(self, n: i32) -> Self {
        Dd::powi(self, n as i64)
    }
}
