//! Everything `ecc eval` reports at one deformation gradient, from an [`Energy`].
//!
//! With the signed SVD F = U diag(σ) Vᵀ the runtime lifts the energy's
//! stretch-space description to F-space (column-major vec, Smith et al. 2019
//! eq. 1): the gradient vec(U diag(∂Ψ/∂σ) Vᵀ), the raw Hessian ∂²Ψ/∂f² as the
//! sum of its analytic eigenpairs (scaling, twist, flip modes), the projected
//! Hessian with every eigenvalue clamped to max(λ, 0), and the eigenvalues.

use ecc_runtime::{Energy, Filter, Spectral, Svd, signed_svd};
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

fn rows<const N: usize>(m: &SMatrix<f64, N, N>) -> Vec<Vec<f64>> {
    (0..N)
        .map(|i| (0..N).map(|j| m[(i, j)]).collect())
        .collect()
}

/// (gradient, raw Hessian rows, projected Hessian rows, eigenvalues).
pub type Lifted = (Vec<f64>, Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<f64>);

/// The per-dimension runtime entry points, so [`evaluate`] is written once.
pub trait PointOps<const D: usize> {
    /// (gradient, raw Hessian rows, projected Hessian rows, eigenvalues).
    fn lift(svd: &Svd<D>, s: &Spectral<D>) -> Lifted;
}

/// Marker type selecting the 2D or 3D runtime functions.
pub struct Ops;

impl PointOps<2> for Ops {
    fn lift(svd: &Svd<2>, s: &Spectral<2>) -> Lifted {
        let g = ecc_runtime::gradient_f2(svd, s);
        let h = ecc_runtime::hessian_f2(svd, s, Filter::None);
        let p = ecc_runtime::hessian_f2(svd, s, Filter::Clamp);
        let (ev, _) = ecc_runtime::eigen_f2(svd, s);
        (g.as_slice().to_vec(), rows(&h), rows(&p), ev.to_vec())
    }
}

impl PointOps<3> for Ops {
    fn lift(svd: &Svd<3>, s: &Spectral<3>) -> Lifted {
        let g = ecc_runtime::gradient_f3(svd, s);
        let h = ecc_runtime::hessian_f3(svd, s, Filter::None);
        let p = ecc_runtime::hessian_f3(svd, s, Filter::Clamp);
        let (ev, _) = ecc_runtime::eigen_f3(svd, s);
        (g.as_slice().to_vec(), rows(&h), rows(&p), ev.to_vec())
    }
}

/// Evaluate `e` at `f` (outside the domain: Ψ = +∞ and all derivatives empty).
pub fn evaluate<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>) -> PointEval
where
    Ops: PointOps<D>,
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
    let (gradient, hessian, hessian_projected, eigenvalues) = Ops::lift(&svd, &s);
    PointEval {
        dim: D,
        sigma,
        psi: s.psi,
        gradient,
        hessian,
        hessian_projected,
        eigenvalues,
    }
}
