//! Element (x-space) energy, gradient and Hessian of linear triangles/tets.
//!
//! Vectors are node-major ([x0.x, x0.y, (x0.z), x1.x, …]) and every returned
//! quantity is already multiplied by the rest measure |q| (area or volume):
//! ψ_e = |q| Ψ(F), ∇ψ_e = |q| Bᵀ vec(∂Ψ/∂F), ∇²ψ_e = |q| Bᵀ H B with f = B x.
//! B is never formed: see [`crate::modes`] for the structured chain rule.
//!
//! Outside the energy's domain (Ψ = +∞) the gradient and Hessian are zero; a
//! non-finite deformed position gives ψ = NaN with zero gradient and Hessian.

use super::rest::{TetRest, TriRest};
use crate::assemble::{Filtered, expand_nodes, modal_sum};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::modes::gradient_vec;
use crate::point::columns;
use crate::svd::signed_svd;
use nalgebra::{ArrayStorage, Matrix2, Matrix3, SMatrix, SVector};

/// Energy, gradient and (optionally) Hessian of one element, times its rest measure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementEval<const N: usize> {
    /// |q| Ψ(F).
    pub psi: f64,
    /// |q| ∂Ψ/∂x (node-major).
    pub grad: SVector<f64, N>,
    /// |q| ∂²Ψ/∂x², filtered; zero when the Hessian was not requested.
    pub hess: SMatrix<f64, N, N>,
}

/// F = Ds Dm⁻¹ of a triangle with 2D deformed positions.
pub fn tri_f(rest: &TriRest, x: &[[f64; 2]; 3]) -> Matrix2<f64> {
    let ds = Matrix2::new(
        x[1][0] - x[0][0],
        x[2][0] - x[0][0],
        x[1][1] - x[0][1],
        x[2][1] - x[0][1],
    );
    ds * rest.dm_inv
}

/// F = Ds Dm⁻¹ of a tetrahedron.
pub fn tet_f(rest: &TetRest, x: &[[f64; 3]; 4]) -> Matrix3<f64> {
    let ds = Matrix3::from_fn(|i, j| x[j + 1][i] - x[0][i]);
    ds * rest.dm_inv
}

/// det F for D = 2 or 3.
#[inline]
fn det<const D: usize>(f: &SMatrix<f64, D, D>) -> f64 {
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

/// |q| Ψ(F) of a triangle (SVD-free when `info().svd_free_psi`).
pub fn tri_psi<E: Energy<2> + ?Sized>(e: &E, rest: &TriRest, x: &[[f64; 2]; 3]) -> f64 {
    rest.area * psi_of_f(e, &tri_f(rest, x))
}

/// |q| Ψ(F) of a tetrahedron (SVD-free when `info().svd_free_psi`).
pub fn tet_psi<E: Energy<3> + ?Sized>(e: &E, rest: &TetRest, x: &[[f64; 3]; 4]) -> f64 {
    rest.volume * psi_of_f(e, &tet_f(rest, x))
}

/// Energy, gradient and (if `want_hessian`) filtered Hessian of a triangle.
pub fn tri_eval<E: Energy<2> + ?Sized>(
    e: &E,
    rest: &TriRest,
    x: &[[f64; 2]; 3],
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<6> {
    let f = tri_f(rest, x);
    element_eval::<2, 3, 4, 6, E>(e, &f, &rest.dm_inv, rest.area, filter, want_hessian)
}

/// Energy, gradient and (if `want_hessian`) filtered Hessian of a tetrahedron.
pub fn tet_eval<E: Energy<3> + ?Sized>(
    e: &E,
    rest: &TetRest,
    x: &[[f64; 3]; 4],
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<12> {
    let f = tet_f(rest, x);
    element_eval::<3, 4, 9, 12, E>(e, &f, &rest.dm_inv, rest.volume, filter, want_hessian)
}

/// Shared kernel: D = dimension, K = D + 1 nodes, R = D·D, N = D·K.
#[inline]
fn element_eval<
    const D: usize,
    const K: usize,
    const R: usize,
    const N: usize,
    E: Energy<D> + ?Sized,
>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    dm_inv: &SMatrix<f64, D, D>,
    measure: f64,
    filter: Filter,
    want_hessian: bool,
) -> ElementEval<N> {
    let zero = |psi: f64| ElementEval {
        psi,
        grad: SVector::zeros(),
        hess: SMatrix::zeros(),
    };
    let svd = signed_svd(f);
    if !svd.is_finite() {
        return zero(f64::NAN);
    }
    let s = e.spectral(&svd.sigma);
    if !s.psi.is_finite() {
        return zero(measure * s.psi);
    }
    let u = columns(&svd.u);
    // w_b = β v_b: w_b[n] = (Dm⁻¹ v_b)[n−1] for n ≥ 1, w_b[0] = −Σ_{n≥1} w_b[n].
    let w: [[f64; K]; D] = std::array::from_fn(|b| {
        let mut wb = [0.0; K];
        let mut sum = 0.0;
        for n in 1..K {
            let mut acc = 0.0;
            for c in 0..D {
                acc += dm_inv[(n - 1, c)] * svd.v[(c, b)];
            }
            wb[n] = acc;
            sum += acc;
        }
        wb[0] = -sum;
        wb
    });
    let grad = gradient_vec::<D, K, N>(&u, &w, &s.grad, measure);
    let hess = if want_hessian {
        // Nodes 1…K−1 only (w restricted to them), node 0 from the zero node-sums.
        let wr: [[f64; D]; D] = std::array::from_fn(|b| std::array::from_fn(|n| w[b][n + 1]));
        let hr = modal_sum::<D, D, R>(&u, &wr, &Filtered::new(&s, filter), measure);
        SMatrix::from_array_storage(ArrayStorage(expand_nodes::<D, K, R, N>(&hr)))
    } else {
        SMatrix::zeros()
    };
    ElementEval {
        psi: measure * s.psi,
        grad: SVector::from(grad),
        hess,
    }
}
