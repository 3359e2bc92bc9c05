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
//! limit count the mixed factor's own, half the halves' bytes). Only split factors (the large
//! systems, [`super::SPLIT_MIN_FLOPS`]) are ever mixed: below, the
//! factorisation is cheap next to the assembly and stays double.

use serde::{Deserialize, Serialize};

use super::split::{SplitFactor, SplitPivot};
use crate::error::FemError;
use crate::pattern::Pattern;
use faer::sparse::linalg::cholesky::SymbolicCholesky;

/// Scalar of the split factor's halves. The names (`"mixed"`, `"double"`)
/// are stable.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FactorPrecision {
    /// Halves in f32, separator in f64, solutions refined by CG in f64
    /// (module docs). The default.
    #[default]
    Mixed,
    /// Everything in f64.
    Double,
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
    /// [`SplitFactor::analyse`] in the scalar of `precision`.
    pub(super) fn analyse(
        pattern: &Pattern,
        symbolic: &SymbolicCholesky<usize>,
        precision: FactorPrecision,
    ) -> Result<Option<Self>, FemError> {
        Ok(match precision {
            FactorPrecision::Double => {
                SplitFactor::analyse(pattern, symbolic, false)?.map(Split::Double)
            }
            FactorPrecision::Mixed => {
                SplitFactor::analyse(pattern, symbolic, false)?.map(Split::Mixed)
            }
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

    pub(super) fn factorize(&mut self, values: &[f64]) -> Result<(), SplitPivot> {
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
