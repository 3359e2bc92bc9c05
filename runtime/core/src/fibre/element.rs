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

use super::frame::{Frame, fa_i5, mul0};
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

/// The element Hessian of the closed form (eqs. P3–P5) without forming
/// the d² × d² matrix: with β_n = a · w_n and n the unit F a,
/// Wᵀ H W = f0 (w_n · w_m) δ_rr' + (f_across − f0) β_n β_m δ_rr'
///        + (f_along − f_across) β_n β_m n_r n_r', times |q|.            (E2)
pub(crate) fn closed_element<const D: usize, const K: usize, const NE: usize>(
    rest: &Rest<D>,
    a: &SVector<f64, D>,
    f: [f64; 3],
    n: &[f64; D],
) -> SMatrix<f64, NE, NE> {
    let w: [[f64; D]; K] = std::array::from_fn(|k| {
        std::array::from_fn(|c| {
            if k == 0 {
                -(0..D).map(|m| rest.dm_inv[(m, c)]).sum::<f64>()
            } else {
                rest.dm_inv[(k - 1, c)]
            }
        })
    });
    let beta: [f64; K] = std::array::from_fn(|k| (0..D).map(|c| a[c] * w[k][c]).sum());
    let [f1, f2, f0] = f;
    let m = rest.measure;
    SMatrix::from_fn(|i, j| {
        let (p, r, q, s) = (i / D, i % D, j / D, j % D);
        let bb = beta[p] * beta[q];
        let iso = if r == s {
            let ww: f64 = (0..D).map(|c| w[p][c] * w[q][c]).sum();
            mul0(f0, ww - bb) + mul0(f2, bb * (1.0 - n[r] * n[r]))
        } else {
            mul0(f2, -bb * n[r] * n[s])
        };
        m * (iso + mul0(f1, bb * n[r] * n[s]))
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
