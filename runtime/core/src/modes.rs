//! The d² eigenmodes of the F-space Hessian in the SVD frame, and their
//! assembly into F-space or x-space (element) matrices.
//!
//! With F = U diag(σ) Vᵀ, every mode is a combination of the rank-one
//! matrices u_a v_bᵀ:
//!
//! * scaling mode m (eigenvector z_m of A): e = Σ_i z_m,i vec(u_i v_iᵀ);
//! * twist of pair (i, j): t = vec(u_j v_iᵀ − u_i v_jᵀ)/√2;
//! * flip of pair (i, j):  l = vec(u_j v_iᵀ + u_i v_jᵀ)/√2.
//!
//! They form an orthonormal basis of R^{d²}, so H = Σ λ e eᵀ.
//!
//! **Chain rule without dense products.** A linear element has
//! F = Ds Dm⁻¹ = Σ_n x_n β_nᵀ (β_n ∈ R^d the rows of the gradient operator:
//! β_n = row n−1 of Dm⁻¹ for n ≥ 1, β_0 = −Σ_n≥1 β_n), so with
//! f = vec(F) = B x we have Bᵀ vec(u vᵀ) = u ⊗ w (node-major) with w_n = β_n·v.
//! Hence the x-space mode is g = Σ c_ab u_a ⊗ w_b with w_b = β v_b (a K-vector
//! for K nodes) and H_x = Bᵀ H B = Σ λ g gᵀ: no 9×12 matrix is ever formed.
//! The F-space Hessian is the special case w_b = v_b.
//!
//! The Hessians themselves are assembled by [`crate::assemble`], which avoids
//! the eigensolve of the scaling block whenever filtering cannot change it.

use crate::spectral::{ScaleBlock, Spectral, pair_indices};
use crate::sym::{sym2_eigen, sym3_eigen};
use std::f64::consts::FRAC_1_SQRT_2;

/// Eigenvalues of the d² modes, in stretch-space form.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Modes<const D: usize> {
    /// Eigenvalues of the scaling block A.
    pub scale_vals: [f64; D],
    /// `scale_vecs[m]` = z_m, the unit eigenvector of A (coefficients on d_i).
    pub scale_vecs: [[f64; D]; D],
    /// Twist eigenvalue per pair slot.
    pub twist: [f64; 3],
    /// Flip eigenvalue per pair slot.
    pub flip: [f64; 3],
}

impl<const D: usize> Modes<D> {
    /// Decompose the scaling block of `s` (closed form in 2D, analytic 3×3).
    ///
    /// A block with a non-finite entry is replaced by its diagonal (its
    /// non-finite values are then handled by the filters).
    pub fn new(s: &Spectral<D>) -> Self {
        let mut scale_vecs = [[0.0; D]; D];
        for (i, z) in scale_vecs.iter_mut().enumerate() {
            z[i] = 1.0;
        }
        let scale_vals = match &s.scale {
            ScaleBlock::Diagonal(a) => *a,
            ScaleBlock::Full(a) => {
                if a.iter().flatten().all(|x| x.is_finite()) {
                    let (vals, vecs) = if D == 2 {
                        let (v, z) = sym2_eigen(a[0][0], 0.5 * (a[0][1] + a[1][0]), a[1][1]);
                        (
                            [v[0], v[1], 0.0],
                            [[z[0][0], z[0][1], 0.0], [z[1][0], z[1][1], 0.0], [0.0; 3]],
                        )
                    } else {
                        let mut m = [[0.0; 3]; 3];
                        for i in 0..3 {
                            for j in i..3 {
                                m[i][j] = 0.5 * (a[i][j] + a[j][i]);
                            }
                        }
                        sym3_eigen(&m)
                    };
                    for (m, z) in scale_vecs.iter_mut().enumerate() {
                        *z = std::array::from_fn(|i| vecs[m][i]);
                    }
                    std::array::from_fn(|m| vals[m])
                } else {
                    std::array::from_fn(|i| a[i][i])
                }
            }
        };
        Modes {
            scale_vals,
            scale_vecs,
            twist: s.twist,
            flip: s.flip,
        }
    }
}

/// u ⊗ w in node-major layout: index n·D + r holds u[r]·w[n].
#[inline(always)]
pub(crate) fn outer<const D: usize, const K: usize, const N: usize>(
    u: &[f64; D],
    w: &[f64; K],
) -> [f64; N] {
    let mut p = [0.0; N];
    for n in 0..K {
        for r in 0..D {
            p[n * D + r] = u[r] * w[n];
        }
    }
    p
}

/// The d² mode vectors g (x-space if `w` = β V, F-space if `w` = V) and their
/// eigenvalues (unsorted: scaling modes, then twist/flip per pair). Only the
/// first D² entries are meaningful.
#[inline(always)]
pub(crate) fn mode_vectors<const D: usize, const K: usize, const N: usize>(
    u: &[[f64; D]; D],
    w: &[[f64; K]; D],
    m: &Modes<D>,
) -> ([f64; 9], [[f64; N]; 9]) {
    debug_assert_eq!(N, D * K);
    let mut vals = [0.0; 9];
    let mut vecs = [[0.0; N]; 9];
    for (mi, z) in m.scale_vecs.iter().enumerate() {
        let mut g = [0.0; N];
        for i in 0..D {
            let p: [f64; N] = outer(&u[i], &w[i]);
            for (gx, px) in g.iter_mut().zip(p.iter()) {
                *gx += z[i] * px;
            }
        }
        vals[mi] = m.scale_vals[mi];
        vecs[mi] = g;
    }
    for k in 0..Spectral::<D>::PAIRS {
        let (i, j) = pair_indices::<D>(k);
        let pji: [f64; N] = outer(&u[j], &w[i]);
        let pij: [f64; N] = outer(&u[i], &w[j]);
        let t = D + 2 * k;
        for x in 0..N {
            vecs[t][x] = FRAC_1_SQRT_2 * (pji[x] - pij[x]);
            vecs[t + 1][x] = FRAC_1_SQRT_2 * (pji[x] + pij[x]);
        }
        vals[t] = m.twist[k];
        vals[t + 1] = m.flip[k];
    }
    (vals, vecs)
}

/// Σ_i grad_i · u_i ⊗ w_i, scaled by `weight`.
#[inline]
pub(crate) fn gradient_vec<const D: usize, const K: usize, const N: usize>(
    u: &[[f64; D]; D],
    w: &[[f64; K]; D],
    grad: &[f64; D],
    weight: f64,
) -> [f64; N] {
    let mut out = [0.0; N];
    for i in 0..D {
        let c = weight * grad[i];
        let p: [f64; N] = outer(&u[i], &w[i]);
        for (o, px) in out.iter_mut().zip(p.iter()) {
            *o += c * px;
        }
    }
    out
}
