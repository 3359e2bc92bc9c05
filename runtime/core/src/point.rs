//! F-space quantities at one point: gradient, raw/filtered Hessian, eigenpairs.
//!
//! Vectorisation is column-major (Smith et al. 2019, eq. 1): vec(F)[c·d + r] = F_rc.
//! The gradient is vec(U diag(∂Ψ/∂σ) Vᵀ); the Hessian is Σ λ e eᵀ over the
//! scaling, twist and flip modes (see the crate docs; element Hessians reuse the same modes).
//!
//! If the SVD is not finite (F had a NaN/∞ entry) the *filtered* Hessian and the
//! gradient are zero; the raw Hessian is NaN.

use crate::assemble::{Filtered, modal_sum};
use crate::filter::Filter;
use crate::modes::{Modes, gradient_vec, mode_vectors};
use crate::spectral::Spectral;
use crate::svd::Svd;
use nalgebra::{Matrix4, SMatrix, SVector, Vector4};

/// Columns of a D×D matrix as arrays.
#[inline]
pub(crate) fn columns<const D: usize>(m: &SMatrix<f64, D, D>) -> [[f64; D]; D] {
    std::array::from_fn(|j| std::array::from_fn(|i| m[(i, j)]))
}

fn gradient_f<const D: usize, const N: usize>(svd: &Svd<D>, s: &Spectral<D>) -> [f64; N] {
    if !svd.is_finite() {
        return [0.0; N];
    }
    let u = columns(&svd.u);
    let v = columns(&svd.v);
    gradient_vec::<D, D, N>(&u, &v, &s.grad, 1.0)
}

fn hessian_f<const D: usize, const N: usize>(
    svd: &Svd<D>,
    s: &Spectral<D>,
    filter: Filter,
) -> [[f64; N]; N] {
    if !svd.is_finite() {
        let fill = if filter.is_raw() { f64::NAN } else { 0.0 };
        return [[fill; N]; N];
    }
    let u = columns(&svd.u);
    let v = columns(&svd.v);
    modal_sum::<D, D, N>(&u, &v, &Filtered::new(s, filter), 1.0)
}

fn eigen_f<const D: usize, const N: usize>(
    svd: &Svd<D>,
    s: &Spectral<D>,
) -> ([f64; N], [SVector<f64, N>; N]) {
    let u = columns(&svd.u);
    let v = columns(&svd.v);
    let m = Modes::new(s);
    let (vals, vecs) = mode_vectors::<D, D, N>(&u, &v, &m);
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    order.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
    (
        std::array::from_fn(|k| vals[order[k]]),
        std::array::from_fn(|k| SVector::from_column_slice(&vecs[order[k]])),
    )
}

/// vec(∂Ψ/∂F) in 2D (column-major).
pub fn gradient_f2(svd: &Svd<2>, s: &Spectral<2>) -> Vector4<f64> {
    Vector4::from(gradient_f::<2, 4>(svd, s))
}

/// vec(∂Ψ/∂F) in 3D (column-major).
pub fn gradient_f3(svd: &Svd<3>, s: &Spectral<3>) -> SVector<f64, 9> {
    SVector::from(gradient_f::<3, 9>(svd, s))
}

/// ∂²Ψ/∂f² in 2D, filtered by `filter` (`Filter::None` = raw).
pub fn hessian_f2(svd: &Svd<2>, s: &Spectral<2>, filter: Filter) -> Matrix4<f64> {
    let h = hessian_f::<2, 4>(svd, s, filter);
    Matrix4::from_fn(|i, j| h[i][j])
}

/// ∂²Ψ/∂f² in 3D, filtered by `filter` (`Filter::None` = raw).
pub fn hessian_f3(svd: &Svd<3>, s: &Spectral<3>, filter: Filter) -> SMatrix<f64, 9, 9> {
    let h = hessian_f::<3, 9>(svd, s, filter);
    SMatrix::from_fn(|i, j| h[i][j])
}

/// Raw eigenpairs of ∂²Ψ/∂f² in 2D, values ascending (NaN sorts last).
pub fn eigen_f2(svd: &Svd<2>, s: &Spectral<2>) -> ([f64; 4], [Vector4<f64>; 4]) {
    eigen_f::<2, 4>(svd, s)
}

/// Raw eigenpairs of ∂²Ψ/∂f² in 3D, values ascending (NaN sorts last).
pub fn eigen_f3(svd: &Svd<3>, s: &Spectral<3>) -> ([f64; 9], [SVector<f64, 9>; 9]) {
    eigen_f::<3, 9>(svd, s)
}
