//! Element (x-space) energy, gradient and Hessian of linear triangles/tets.
//!
//! Vectors are node-major ([x0.x, x0.y, (x0.z), x1.x, …]) and every returned
//! quantity is already multiplied by the rest measure |q| (area or volume):
//! ψ_e = |q| Ψ(F), ∇ψ_e = |q| Bᵀ vec(∂Ψ/∂F), ∇²ψ_e = |q| Bᵀ H B with f = B x.
//! B is never formed: see [`crate::modes`] for the structured chain rule.
//! One generic function per quantity, for d = 2 (triangles) or 3 (tetrahedra).
//!
//! Outside the energy's domain (Ψ = +∞) the gradient and Hessian are zero; a
//! non-finite deformed position gives ψ = NaN with zero gradient and Hessian.

use super::rest::Rest;
use crate::dim::{Dim, ElemMat, ElemVec, Nodes, Space};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::svd::signed_svd;
use nalgebra::SMatrix;

/// Energy, gradient and (optionally) Hessian of one element, times its rest measure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementEval<const D: usize>
where
    Space<D>: Dim<D>,
{
    /// |q| Ψ(F).
    pub psi: f64,
    /// |q| ∂Ψ/∂x (node-major, d(d + 1) entries).
    pub grad: ElemVec<D>,
    /// |q| ∂²Ψ/∂x², filtered; zero when the Hessian was not requested.
    pub hess: ElemMat<D>,
}

/// F = Ds Dm⁻¹ with Ds = [x1 − x0, …, x_d − x0] (deformed edge vectors as columns).
#[inline]
pub fn element_f<const D: usize>(rest: &Rest<D>, x: &Nodes<D>) -> SMatrix<f64, D, D>
where
    Space<D>: Dim<D>,
{
    let x = x.as_ref();
    let ds = SMatrix::<f64, D, D>::from_fn(|i, j| x[j + 1][i] - x[0][i]);
    ds * rest.dm_inv
}

/// det F for D = 2 or 3.
#[inline]
pub(crate) fn det<const D: usize>(f: &SMatrix<f64, D, D>) -> f64 {
    if D == 2 {
        f[(0, 0)] * f[(1, 1)] - f[(0, 1)] * f[(1, 0)]
    } else {
        f[(0, 0)] * (f[(1, 1)] * f[(2, 2)] - f[(1, 2)] * f[(2, 1)])
            - f[(0, 1)] * (f[(1, 0)] * f[(2, 2)] - f[(1, 2)] * f[(2, 0)])
            + f[(0, 2)] * (f[(1, 0)] * f[(2, 1)] - f[(1, 1)] * f[(2, 0)])
    }
}

/// Ψ from F: the SVD-free fast path when the energy offers it, else Ψ(σ).
fn psi_of_f<const D: usize, E: Energy<D> + ?Sized>(e: &E, f: &SMatrix<f64, D, D>) -> f64 {
    if !f.iter().all(|x| x.is_finite()) {
        return f64::NAN;
    }
    if e.info().svd_free_psi
        && let Some(p) = e.psi_i2_i3(f.norm_squared(), det(f))
    {
        return p;
    }
    e.psi(&signed_svd(f).sigma)
}

/// |q| Ψ(F) of an element (SVD-free when `info().svd_free_psi`).
pub fn element_psi<const D: usize, E: Energy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    x: &Nodes<D>,
) -> f64
where
    Space<D>: Dim<D>,
{
    rest.measure * psi_of_f(e, &element_f(rest, x))
}

/// Energy, gradient and (if `want_hessian`) filtered Hessian of an element.
#[inline]
pub fn element_eval<const D: usize, E: Energy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    x: &Nodes<D>,
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<D>
where
    Space<D>: Dim<D>,
{
    let f = element_f(rest, x);
    <Space<D> as Dim<D>>::element_kernel(e, &f, rest, filter, want_hessian)
}
