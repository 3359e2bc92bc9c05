//! Signed singular value decomposition of 2×2 and 3×3 matrices.
//!
//! F = U diag(σ) Vᵀ with U, V ∈ SO(d) (proper rotations, det = +1). A
//! reflection, if F has one (det F < 0), is moved into the singular value of
//! smallest magnitude, so σ is ordered |σ_0| ≥ |σ_1| ≥ |σ_2| and only the last
//! entry may be negative (Irving et al. 2004; Smith et al. 2019 §3).
//!
//! * 2×2: closed form from the similarity / anti-similarity split of F
//!   ([`signed_svd2`]); no iteration, exact at repeated and zero σ.
//! * 3×3: analytic eigenvectors of FᵀF (trigonometric eigenvalues, a
//!   cross-product eigenvector for the best-separated eigenvalue, one exact
//!   Jacobi rotation for the remaining 2×2 block), then a Gram–Schmidt QR of F V
//!   (U = [u_0, u_1, u_0 × u_1] ∈ SO(3)) with σ = diag(R) of
//!   *absolute* accuracy ≈ ε‖F‖ even for tiny σ ([`signed_svd3`]).
//!
//! Non-finite input yields σ = NaN and U = V = I (never a panic).

mod three;
mod two;

use nalgebra::{Matrix2, Matrix3, SMatrix};

pub use three::signed_svd3;
pub(crate) use two::conformal_parts;
pub use two::signed_svd2;

/// A signed SVD F = U diag(σ) Vᵀ with U, V ∈ SO(D).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Svd<const D: usize> {
    /// Left rotation (columns are the left singular vectors u_i).
    pub u: SMatrix<f64, D, D>,
    /// Signed singular values, |σ_0| ≥ |σ_1| ≥ … ; only the last may be < 0.
    pub sigma: [f64; D],
    /// Right rotation (columns are the right singular vectors v_i).
    pub v: SMatrix<f64, D, D>,
}

impl<const D: usize> Svd<D> {
    /// U diag(σ) Vᵀ (for checks and reconstruction).
    pub fn reconstruct(&self) -> SMatrix<f64, D, D> {
        let mut us = self.u;
        for (j, s) in self.sigma.iter().enumerate() {
            for i in 0..D {
                us[(i, j)] *= s;
            }
        }
        us * self.v.transpose()
    }

    /// True when U, V and σ are all finite.
    pub fn is_finite(&self) -> bool {
        self.sigma.iter().all(|s| s.is_finite())
            && self.u.iter().all(|x| x.is_finite())
            && self.v.iter().all(|x| x.is_finite())
    }
}

/// Signed SVD for D = 2 or 3 (dispatches to [`signed_svd2`] / [`signed_svd3`]).
///
/// Any other `D` is rejected at compile time.
pub fn signed_svd<const D: usize>(f: &SMatrix<f64, D, D>) -> Svd<D> {
    const { assert!(D == 2 || D == 3, "signed_svd supports D = 2 or 3") };
    if D == 2 {
        let m = Matrix2::from_fn(|i, j| f[(i, j)]);
        let s = signed_svd2(&m);
        Svd {
            u: SMatrix::from_fn(|i, j| s.u[(i, j)]),
            sigma: std::array::from_fn(|i| s.sigma[i]),
            v: SMatrix::from_fn(|i, j| s.v[(i, j)]),
        }
    } else {
        let m = Matrix3::from_fn(|i, j| f[(i, j)]);
        let s = signed_svd3(&m);
        Svd {
            u: SMatrix::from_fn(|i, j| s.u[(i, j)]),
            sigma: std::array::from_fn(|i| s.sigma[i]),
            v: SMatrix::from_fn(|i, j| s.v[(i, j)]),
        }
    }
}

/// The result for a matrix with a non-finite entry.
pub(crate) fn non_finite<const D: usize>() -> Svd<D> {
    Svd {
        u: SMatrix::identity(),
        sigma: [f64::NAN; D],
        v: SMatrix::identity(),
    }
}
