//! Numeric baselines: nalgebra projection and central differences.
//!
//! Used by tests, benchmarks and the CLI's `ecc check`. They are deliberately
//! independent of the analytic machinery: [`project_psd_numeric`] uses
//! nalgebra's `SymmetricEigen`, and the finite differences only ever evaluate
//! Ψ(F) through [`psi_f`].

#[cfg(feature = "cases")]
pub mod cases;
pub mod check;
mod fd;

pub use fd::{fd_gradient, fd_gradient_f, fd_gradient_vec, fd_hessian, fd_hessian_f};

use crate::dim::{Dim, FMat, Space};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::svd::signed_svd;
use nalgebra::allocator::Allocator;
use nalgebra::{
    ArrayStorage, Const, DefaultAllocator, DimDiff, DimSub, SMatrix, SymmetricEigen, U1,
};

/// Filter a symmetric matrix numerically: H = Q diag(filter(λ)) Qᵀ with
/// nalgebra's `SymmetricEigen` (the baseline the analytic path is compared to).
/// Only the symmetric part of `h` is used.
pub fn project_psd_numeric<const N: usize>(
    h: &SMatrix<f64, N, N>,
    filter: Filter,
) -> SMatrix<f64, N, N>
where
    Const<N>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<N>, U1>>,
{
    let mut sym = [[0.0; N]; N];
    for (j, col) in sym.iter_mut().enumerate() {
        for (i, x) in col.iter_mut().enumerate() {
            *x = 0.5 * (h[(i, j)] + h[(j, i)]);
        }
    }
    if filter.is_raw() {
        return SMatrix::from_array_storage(ArrayStorage(sym));
    }
    if !sym.iter().flatten().all(|x| x.is_finite()) {
        return SMatrix::from_array_storage(ArrayStorage([[0.0; N]; N]));
    }
    let eig = SymmetricEigen::<f64, Const<N>>::new(SMatrix::from_array_storage(ArrayStorage(sym)));
    let q = &eig.eigenvectors;
    let lam: [f64; N] = std::array::from_fn(|k| filter.apply(eig.eigenvalues[k]));
    let mut out = [[0.0; N]; N];
    for j in 0..N {
        for i in j..N {
            let mut acc = 0.0;
            for (k, l) in lam.iter().enumerate() {
                acc += q[(i, k)] * l * q[(j, k)];
            }
            out[j][i] = acc;
            out[i][j] = acc;
        }
    }
    SMatrix::from_array_storage(ArrayStorage(out))
}

/// [`project_psd_numeric`] of a d² × d² F-space Hessian, for d = 2 or 3.
pub fn project_psd_f<const D: usize>(h: &FMat<D>, filter: Filter) -> FMat<D>
where
    Space<D>: Dim<D>,
{
    <Space<D> as Dim<D>>::project_psd_numeric(h, filter)
}

/// Ψ(F) through the signed SVD: `e.psi(σ(F))` (NaN for a non-finite F).
pub fn psi_f<E: Energy<D> + ?Sized, const D: usize>(e: &E, f: &SMatrix<f64, D, D>) -> f64 {
    if !f.iter().all(|x| x.is_finite()) {
        return f64::NAN;
    }
    e.psi(&signed_svd(f).sigma)
}

/// The reference of [`crate::element_curvature`]: dlᵀ H dl with the raw
/// element Hessian of [`crate::element_eval`] (`Filter::None`; +∞ for a
/// non-finite ψ, as the trust-region pass before it), and the rounding
/// scale |q|‖H‖max‖dl‖² of that sum.
pub fn curvature_reference<const D: usize>(
    e: &dyn Energy<D>,
    rest: &crate::Rest<D>,
    x: &crate::Nodes<D>,
    dx: &crate::Nodes<D>,
) -> (f64, f64)
where
    Space<D>: Dim<D>,
{
    let ev = crate::element_eval(e, rest, x, Filter::None, true);
    if !ev.psi.is_finite() {
        return (f64::INFINITY, 0.0);
    }
    let dl: Vec<f64> = dx.as_ref().iter().flatten().copied().collect();
    let (mut acc, mut hmax) = (0.0, 0.0f64);
    for (a, &da) in dl.iter().enumerate() {
        for (b, &db) in dl.iter().enumerate() {
            acc += da * ev.hess[(a, b)] * db;
            hmax = hmax.max(ev.hess[(a, b)].abs());
        }
    }
    (acc, hmax * dl.iter().map(|v| v * v).sum::<f64>())
}
