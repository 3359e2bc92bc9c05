//! Everything `Energy.eval` returns at one deformation gradient: the same
//! composition of runtime calls as `ecc eval` (app/cli/src/point.rs). With the
//! signed SVD F = U diag(σ) Vᵀ the runtime lifts the energy's stretch-space
//! description to F-space (column-major vec, Smith et al. 2019 eq. 1): the
//! gradient vec(U diag(∂Ψ/∂σ) Vᵀ), the raw Hessian ∂²Ψ/∂f² as the sum of its
//! analytic eigenpairs, the projected Hessian (every eigenvalue clamped to
//! max(λ, 0)) and the eigenvalues, ascending.

use ecc_runtime::{Dim, Energy, FMat, Filter, Space, eigen_f, gradient_f, hessian_f, signed_svd};
use nalgebra::SMatrix;

/// The quantities at one F, written into preallocated flat buffers.
pub struct PointOut<'a> {
    /// σ, d entries.
    pub sigma: &'a mut [f64],
    /// Ψ.
    pub psi: &'a mut f64,
    /// vec(∂Ψ/∂F), d² entries (column-major).
    pub gradient: &'a mut [f64],
    /// Raw Hessian, d⁴ entries by rows.
    pub hessian: &'a mut [f64],
    /// Projected Hessian, d⁴ entries by rows.
    pub hessian_projected: &'a mut [f64],
    /// The d² eigenvalues of the raw Hessian, ascending.
    pub eigenvalues: &'a mut [f64],
}

fn copy_rows<const D: usize>(m: &FMat<D>, out: &mut [f64])
where
    Space<D>: Dim<D>,
{
    let n = D * D;
    for i in 0..n {
        for j in 0..n {
            out[i * n + j] = m[(i, j)];
        }
    }
}

/// Evaluate `e` at `f`. Outside the energy's domain Ψ = +∞ and every
/// derivative entry is NaN (`ecc eval --json` writes them as null).
pub fn evaluate<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>, out: PointOut<'_>)
where
    Space<D>: Dim<D>,
{
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    out.sigma.copy_from_slice(&svd.sigma);
    *out.psi = s.psi;
    if s.psi == f64::INFINITY {
        for buf in [
            out.gradient,
            out.hessian,
            out.hessian_projected,
            out.eigenvalues,
        ] {
            buf.fill(f64::NAN);
        }
        return;
    }
    let g = gradient_f(&svd, &s);
    for (k, v) in out.gradient.iter_mut().enumerate() {
        *v = g[k];
    }
    copy_rows::<D>(&hessian_f(&svd, &s, Filter::None), out.hessian);
    copy_rows::<D>(&hessian_f(&svd, &s, Filter::Clamp), out.hessian_projected);
    let (eigenvalues, _) = eigen_f(&svd, &s);
    out.eigenvalues.copy_from_slice(eigenvalues.as_ref());
}
