//! Everything `ecc eval` reports at one deformation gradient, from an [`Energy`].
//!
//! With the signed SVD F = U diag(σ) Vᵀ the runtime lifts the energy's
//! stretch-space description to F-space (column-major vec, Smith et al. 2019
//! eq. 1): the gradient vec(U diag(∂Ψ/∂σ) Vᵀ), the raw Hessian ∂²Ψ/∂f² as the
//! sum of its analytic eigenpairs (scaling, twist, flip modes), the projected
//! Hessian with every eigenvalue clamped to max(λ, 0), and the eigenvalues.

use ecc_runtime::{Dim, Energy, FMat, Filter, Space, eigen_f, gradient_f, hessian_f, signed_svd};
use nalgebra::SMatrix;

/// The analytic quantities at one F (vectors column-major, matrices by rows).
#[derive(Clone, Debug, PartialEq)]
pub struct PointEval {
    /// The dimension d.
    pub dim: usize,
    /// Signed singular values of F.
    pub sigma: Vec<f64>,
    /// Ψ(F); +∞ outside the energy's domain.
    pub psi: f64,
    /// vec(∂Ψ/∂F), d² entries.
    pub gradient: Vec<f64>,
    /// Raw ∂²Ψ/∂f², d² rows of d².
    pub hessian: Vec<Vec<f64>>,
    /// The Hessian with negative eigenvalues clamped to 0.
    pub hessian_projected: Vec<Vec<f64>>,
    /// The d² eigenvalues of the raw Hessian, ascending.
    pub eigenvalues: Vec<f64>,
}

impl PointEval {
    /// Whether F lies inside the energy's domain (Ψ < +∞).
    pub fn inside_domain(&self) -> bool {
        self.psi != f64::INFINITY
    }

    /// Whether every reported number is finite.
    pub fn all_finite(&self) -> bool {
        self.psi.is_finite()
            && self.gradient.iter().all(|x| x.is_finite())
            && self.hessian.iter().flatten().all(|x| x.is_finite())
            && self
                .hessian_projected
                .iter()
                .flatten()
                .all(|x| x.is_finite())
            && self.eigenvalues.iter().all(|x| x.is_finite())
    }
}

fn rows<const D: usize>(m: &FMat<D>) -> Vec<Vec<f64>>
where
    Space<D>: Dim<D>,
{
    let n = D * D;
    (0..n)
        .map(|i| (0..n).map(|j| m[(i, j)]).collect())
        .collect()
}

/// Evaluate `e` at `f` (outside the domain: Ψ = +∞ and all derivatives empty).
pub fn evaluate<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>) -> PointEval
where
    Space<D>: Dim<D>,
{
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    let sigma = svd.sigma.to_vec();
    if s.psi == f64::INFINITY {
        return PointEval {
            dim: D,
            sigma,
            psi: f64::INFINITY,
            gradient: Vec::new(),
            hessian: Vec::new(),
            hessian_projected: Vec::new(),
            eigenvalues: Vec::new(),
        };
    }
    let g = gradient_f(&svd, &s);
    let (eigenvalues, _) = eigen_f(&svd, &s);
    PointEval {
        dim: D,
        sigma,
        psi: s.psi,
        gradient: (0..D * D).map(|k| g[k]).collect(),
        hessian: rows::<D>(&hessian_f(&svd, &s, Filter::None)),
        hessian_projected: rows::<D>(&hessian_f(&svd, &s, Filter::Clamp)),
        eigenvalues: eigenvalues.as_ref().to_vec(),
    }
}
