//! The chain rule from F-space fibre derivatives to an element's nodes.
//!
//! F = Ds Dm⁻¹ is linear in the node positions: ∂F_rc/∂x_{n,r} = w_n[c] with
//! w_n = row n − 1 of Dm⁻¹ (n ≥ 1) and w_0 = −Σ_{n≥1} w_n. With the
//! d² × d(d+1) matrix W[(c, r), (n, r')] = w_n[c] δ_rr' (vec(F) = W x),
//!
//!   ∇ψ_e = |q| Wᵀ vec(∂ψ/∂F),   ∇²ψ_e = |q| Wᵀ H W,                       (E1)
//!
//! and a PSD F-space H gives a PSD element Hessian (as for the isotropic
//! elements, [`crate::element`]).

use nalgebra::{SMatrix, SVector};

use super::frame::{Frame, fa_i5};
use crate::element::Rest;
use crate::fibre::{FibreEnergy, FibreUse};

/// W of eq. E1 for K = d + 1 nodes.
pub(crate) fn chain_matrix<const D: usize, const K: usize, const N: usize, const NE: usize>(
    rest: &Rest<D>,
) -> SMatrix<f64, N, NE> {
    let w = |n: usize, c: usize| {
        if n == 0 {
            -(0..D).map(|m| rest.dm_inv[(m, c)]).sum::<f64>()
        } else {
            rest.dm_inv[(n - 1, c)]
        }
    };
    SMatrix::from_fn(|i, j| {
        let (c, r) = (i / D, i % D);
        let (n, r2) = (j / D, j % D);
        if r == r2 { w(n, c) } else { 0.0 }
    })
}

/// |q| ψ(F) alone (the line search's path; the SVD only when ψ uses I4).
pub(crate) fn psi_kernel<const D: usize, E: FibreEnergy<D> + ?Sized>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    measure: f64,
) -> f64 {
    if !f.iter().all(|x| x.is_finite()) {
        return f64::NAN;
    }
    let i5 = fa_i5(f, a).1;
    let i4 = match e.uses() {
        FibreUse::I4 | FibreUse::Both => Frame::new(f, a).i4,
        FibreUse::I5 | FibreUse::None => f64::NAN,
    };
    measure * e.fibre_psi(i4, i5)
}
