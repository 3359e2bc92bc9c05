//! The precision of a split factor: double, or mixed (the halves in single
//! precision, the separator in double).
//!
//! A mixed factor M = L̃L̃ᵀ of A solves A x = b only to a relative error of
//! about κ(A)·2⁻²⁴, so [`crate::linear::LinearSystem::solve`] uses it as the
//! preconditioner of CG in double on A itself (classical mixed-precision
//! iterative refinement, with CG as the outer iteration): the residual is
//! computed and reduced in f64, so the direction meets the same relative
//! residual as any other linear solve of the Newton step (capped at
//! [`crate::linear::mixed::MIXED_REL_TOL`]), and a factor that cannot reach
//! it falls back to double for good ([`super::CholeskyFactor::to_double`]).
//! A single-precision factorisation that breaks down is retried on the same
//! matrix in double: if that succeeds the factor stays double; if it fails
//! too the matrix is indefinite (a raw Hessian: the Newton shift takes
//! over), the factor stays mixed and its later breakdowns are reported
//! without the retry (one double attempt per factor). The retry and the
//! fallback allocate the double factor beside the mixed one: for a moment
//! 1.5× the double factor's memory (`factor_bytes` and `auto`'s memory
//! limit count the mixed factor's own, half the halves' bytes). Only split
//! factors (the large systems, [`super::SPLIT_MIN_FLOPS`]) are ever mixed:
//! below, the factorisation is cheap next to the assembly and stays double.
//!
//! **Where it pays** ([`FactorPrecision::Auto`], the default: mixed from
//! [`MIXED_MIN_FLOPS`]). Single precision halves the bytes the
//! factorisation moves and doubles the SIMD width of its dense kernels,
//! which pays on large supernodes only. Measured per factorisation, 2
//! threads, split (2026-12-02, stop 26): camelhead (1.5e8 flops) 17 ms in
//! f32 against 20 ms in f64, where the Tutte start's first Hessian breaks
//! down in f32 and the double fallback (fresh storage, a second
//! factorisation) cost 35 ms, +0.04–0.1 s per solve over the double
//! factor; armadillo_cut_low (2.2e8) breaks down at once too (+0.06 s);
//! hand.mesh SNH (1.0e9 flops) 30 ms against 51 ms, 4.4 s against 6.5 s
//! over 56 Newton steps; the 1M-triangle disk (6e10) 0.85 s against
//! 1.7 s.

use serde::{Deserialize, Serialize};

use super::FactorizeError;
use super::split::SplitFactor;
use super::tree::Tree;
use crate::error::FemError;
use crate::pattern::Pattern;

/// Scalar of the split factor's halves. The names (`"auto"`, `"mixed"`,
/// `"double"`) are stable.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FactorPrecision {
    /// [`FactorPrecision::Mixed`] for factors of at least
    /// [`MIXED_MIN_FLOPS`], [`FactorPrecision::Double`] below (module docs,
    /// "Where it pays"). The default.
    #[default]
    Auto,
    /// Halves in f32, separator in f64, solutions refined by CG in f64
    /// (module docs).
    Mixed,
    /// Everything in f64.
    Double,
}

/// Smallest factor (flops of the plain analysis, Σ c² over the columns as
/// in [`super::CholeskyFactor::factor_flops`]) that
/// [`FactorPrecision::Auto`] makes mixed: between camelhead's and
/// armadillo_cut_low's 1.5–2.2e8, where f32 gains 15 % per factorisation
/// and a breakdown costs two, and hand.mesh's 1.0e9, where it gains 40 %
/// (module docs).
pub const MIXED_MIN_FLOPS: f64 = 5e8;

impl FactorPrecision {
    /// The concrete precision for a factor of `flops`
    /// ([`FactorPrecision::Auto`] resolved).
    pub fn resolve(self, flops: f64) -> FactorPrecision {
        match self {
            FactorPrecision::Auto if flops >= MIXED_MIN_FLOPS => FactorPrecision::Mixed,
            FactorPrecision::Auto => FactorPrecision::Double,
            p => p,
        }
    }
}

/// A split factor of either precision.
pub(super) enum Split {
    Double(SplitFactor<f64>),
    Mixed(SplitFactor<f32>),
}

/// `$body` with `$s` bound to the split factor of either precision.
macro_rules! each {
    ($split:expr, $s:ident => $body:expr) => {
        match $split {
            Split::Double($s) => $body,
            Split::Mixed($s) => $body,
        }
    };
}

impl Split {
    /// [`SplitFactor::analyse_tree`] in the scalar of `precision` (resolved
    /// for the plain factor's `flops`).
    pub(super) fn analyse(
        pattern: &Pattern,
        perm: Option<&[usize]>,
        tree: &Tree,
        precision: FactorPrecision,
        flops: f64,
    ) -> Result<Option<Self>, FemError> {
        Ok(match precision.resolve(flops) {
            FactorPrecision::Mixed => {
                SplitFactor::analyse_tree(pattern, perm, tree, false)?.map(Split::Mixed)
            }
            _ => SplitFactor::analyse_tree(pattern, perm, tree, false)?.map(Split::Double),
        })
    }

    pub(super) fn is_mixed(&self) -> bool {
        matches!(self, Split::Mixed(_))
    }

    /// The double-precision split of the same structure (storage fresh);
    /// `None` if it already is.
    pub(super) fn double(&self) -> Result<Option<Self>, FemError> {
        match self {
            Split::Double(_) => Ok(None),
            Split::Mixed(s) => Ok(Some(Split::Double(s.with_scalar()?))),
        }
    }

    pub(super) fn factorize(&mut self, values: &[f64]) -> Result<(), FactorizeError> {
        each!(self, s => s.factorize(values))
    }

    pub(super) fn solve_in_place(&mut self, rhs: &mut [f64]) {
        each!(self, s => s.solve_in_place(rhs))
    }

    pub(super) fn phases(&self) -> [f64; 4] {
        each!(self, s => s.phases())
    }

    pub(super) fn separator_len(&self) -> usize {
        each!(self, s => s.separator_len())
    }

    pub(super) fn nnz(&self) -> usize {
        each!(self, s => s.nnz())
    }

    pub(super) fn bytes(&self) -> usize {
        each!(self, s => s.bytes())
    }

    pub(super) fn flops(&self) -> f64 {
        each!(self, s => s.flops())
    }

    pub(super) fn critical_flops(&self) -> f64 {
        each!(self, s => s.critical_flops())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_is_mixed_from_the_threshold_and_the_others_stay() {
        use FactorPrecision::*;
        assert_eq!(FactorPrecision::default(), Auto);
        assert_eq!(Auto.resolve(MIXED_MIN_FLOPS), Mixed);
        assert_eq!(Auto.resolve(MIXED_MIN_FLOPS * 0.99), Double);
        for f in [0.0, MIXED_MIN_FLOPS, 1e12] {
            assert_eq!(Mixed.resolve(f), Mixed);
            assert_eq!(Double.resolve(f), Double);
        }
        for (p, name) in [(Auto, "auto"), (Mixed, "mixed"), (Double, "double")] {
            assert_eq!(serde_json::to_value(p).unwrap(), name);
        }
    }
}
