//! F-space quantities at one point: gradient, raw/filtered Hessian, eigenpairs.
//!
//! Vectorisation is column-major (Smith et al. 2019, eq. 1): vec(F)[c·d + r] = F_rc.
//! The gradient is vec(U diag(∂Ψ/∂σ) Vᵀ); the Hessian is Σ λ e eᵀ over the
//! scaling, twist and flip modes (see the crate docs; element Hessians reuse the same modes).
//! One generic function per quantity, for d = 2 or 3 (see [`crate::dim`]).
//!
//! If the SVD is not finite (F had a NaN/∞ entry) the *filtered* Hessian and the
//! gradient are zero; the raw Hessian is NaN.

use crate::dim::{Dim, FMat, FVec, Space};
use crate::filter::Filter;
use crate::spectral::Spectral;
use crate::svd::Svd;

/// vec(∂Ψ/∂F) = vec(U diag(∂Ψ/∂σ) Vᵀ) (column-major, d² entries).
#[inline]
pub fn gradient_f<const D: usize>(svd: &Svd<D>, s: &Spectral<D>) -> FVec<D>
where
    Space<D>: Dim<D>,
{
    <Space<D> as Dim<D>>::gradient_f(svd, s)
}

/// ∂²Ψ/∂f² = Σ λ e eᵀ over the d² modes (Zhu 2020 eq. 28), each eigenvalue
/// filtered by `filter` (`Filter::None` = raw).
#[inline]
pub fn hessian_f<const D: usize>(svd: &Svd<D>, s: &Spectral<D>, filter: Filter) -> FMat<D>
where
    Space<D>: Dim<D>,
{
    <Space<D> as Dim<D>>::hessian_f(svd, s, filter)
}

/// Raw eigenpairs of ∂²Ψ/∂f², values ascending (NaN sorts last).
pub fn eigen_f<const D: usize>(
    svd: &Svd<D>,
    s: &Spectral<D>,
) -> (<Space<D> as Dim<D>>::FVals, <Space<D> as Dim<D>>::FVecs)
where
    Space<D>: Dim<D>,
{
    <Space<D> as Dim<D>>::eigen_f(svd, s)
}
