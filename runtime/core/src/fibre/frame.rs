//! The fibre invariants of one F and their F-space derivatives.
//!
//! With the signed SVD F = U Σ Vᵀ (U, V ∈ SO(d)), R = U Vᵀ, S = V Σ Vᵀ and
//! b = Vᵀ a (the fibre in the right singular frame):
//!
//! * I4 = aᵀ S a = Σ_i σ_i b_i²                                          (F1)
//! * I5 = ‖F a‖²                                                          (F2)
//!
//! Derivatives are taken in the singular frame, M = Uᵀ dF V, and rotated
//! back with vec(U M Vᵀ) = (V ⊗ U) vec(M) (column-major vec).
//!
//! **I5.** ∂I5/∂F = 2 F a aᵀ, ∂²I5/∂f² = 2 (a aᵀ ⊗ I_d)                (F3)
//! (Kim, de Goes & Iben 2019, §4.1 eqs. 6 and 7; HOBAK's `kronIdentity(A)`
//! is half of it): eigenvalue 2 on vec(q aᵀ) for every q (d modes; §4.1:
//! λ_{0,1,2} = 2‖a‖² on Q_i = e_i aᵀ), 0 on vec(q cᵀ) with c ⊥ a (§4.1's
//! rank-six null space in 3D).
//!
//! **I4.** S is the square root of C = FᵀF with eigenvalues σ_i (signed), so
//! S dS + dS S = dC and, in the singular frame, the first variation is
//! dS̃_pq = (σ_p M_pq + σ_q M_qp)/(σ_p + σ_q) =: G(M)_pq (G(M)_pp = M_pp) and
//!
//!   ∂I4/∂M_rc = 2 b_r b_c σ_r/(σ_r + σ_c)   (r ≠ c),   ∂I4/∂M_rr = b_r²   (F4)
//!
//! In the mode basis of the isotropic runtime this is b_i² on the scaling
//! mode d_i, √2 b_i b_j on the flip of (i, j) and −√2 b_i b_j (σ_i − σ_j)/(σ_i + σ_j)
//! on its twist: R A (the derivative with R held fixed, dI4 = aᵀRᵀdF a)
//! plus a twist term from dR that vanishes only for σ_i = σ_j. The second variation
//! (S d²S + d²S S = 2 dCdC-terms) gives the bilinear form
//!
//!   B(M, N) = Σ_{p≠q} b_p b_q X_pq/(σ_p + σ_q) + Σ_p b_p² D_p(M, N),     (F5)
//!   X = MᵀN + NᵀM − G(M) G(N) − G(N) G(M),
//!   D_p = Σ_{k≠p} [2 m₂n₂ − m₂n₁ − n₂m₁ − σ_p (m₂ − m₁)(n₂ − n₁)/s]/s,
//!
//! with m₁ = M_pk, m₂ = M_kp (n likewise) and s = σ_p + σ_k: the diagonal
//! p = q terms X_pp/(2σ_p) are a removable 0/0 at σ_p = 0 (the fibre along
//! the compressed axis of an element being inverted) and D_p is their
//! cancellation-free form. The remaining denominators σ_p + σ_q vanish only
//! on the genuine kink of S (σ_i + σ_j = 0, an inverted element's twist
//! pole, as for I1); there the raw values are ±∞ and every filter drops them.
//!
//! The I4 Hessian couples scaling and twist modes
//! (B(d_i, t_ij) = −2√2 b_i b_j σ_j/(σ_i + σ_j)² ≠ 0 in general), so it is
//! *not* diagonal in the isotropic mode basis; `fibre/reduced.rs` gives the
//! same Hessian in polar coordinates (eq. R3) and the smallest eigensolve
//! for energies using I4.

use nalgebra::{SMatrix, SVector};

use crate::svd::{Svd, signed_svd};

/// x · y with 0 · (±∞) = 0: a zero factor is exact (e.g. F a = 0), so
/// an infinite coefficient in front of it contributes nothing.
#[inline]
pub(crate) fn mul0(c: f64, x: f64) -> f64 {
    if x == 0.0 { 0.0 } else { c * x }
}

/// Singular frame, fibre and I4 of one F.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame<const D: usize> {
    pub svd: Svd<D>,
    /// b = Vᵀ a.
    pub b: [f64; D],
    pub i4: f64,
}

/// F a and I5 = ‖F a‖² (no SVD).
#[inline]
pub(crate) fn fa_i5<const D: usize>(
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
) -> ([f64; D], f64) {
    let fa: [f64; D] = std::array::from_fn(|r| (0..D).map(|c| f[(r, c)] * a[c]).sum());
    (fa, fa.iter().map(|x| x * x).sum())
}

/// I4 = aᵀ S a with the signed SVD's S = V Σ Vᵀ (eq. F1).
pub fn invariant4<const D: usize>(f: &SMatrix<f64, D, D>, a: &SVector<f64, D>) -> f64 {
    Frame::new(f, a).i4
}

/// I5 = ‖F a‖² (eq. F2).
pub fn invariant5<const D: usize>(f: &SMatrix<f64, D, D>, a: &SVector<f64, D>) -> f64 {
    fa_i5(f, a).1
}

impl<const D: usize> Frame<D> {
    pub fn new(f: &SMatrix<f64, D, D>, a: &SVector<f64, D>) -> Self {
        let svd = signed_svd(f);
        let b: [f64; D] = std::array::from_fn(|i| (0..D).map(|c| svd.v[(c, i)] * a[c]).sum());
        let i4 = (0..D).map(|i| svd.sigma[i] * b[i] * b[i]).sum();
        Frame { svd, b, i4 }
    }

    /// ∂I4/∂M (singular frame), eq. F4.
    pub(crate) fn grad4_m(&self) -> SMatrix<f64, D, D> {
        let (s, b) = (&self.svd.sigma, &self.b);
        SMatrix::from_fn(|r, c| {
            if r == c {
                b[r] * b[r]
            } else {
                let num = 2.0 * b[r] * b[c] * s[r];
                if num == 0.0 { 0.0 } else { num / (s[r] + s[c]) }
            }
        })
    }

    /// vec(∂I4/∂F) = vec(U (∂I4/∂M) Vᵀ).
    pub fn grad4<const N: usize>(&self) -> SVector<f64, N> {
        let g = self.svd.u * self.grad4_m() * self.svd.v.transpose();
        SVector::from_fn(|k, _| g[(k % D, k / D)])
    }

    /// G(M) of eq. F5 (first variation of S in the singular frame).
    fn g(&self, m: &SMatrix<f64, D, D>) -> SMatrix<f64, D, D> {
        let s = &self.svd.sigma;
        SMatrix::from_fn(|p, q| {
            if p == q {
                m[(p, p)]
            } else {
                let num = s[p] * m[(p, q)] + s[q] * m[(q, p)];
                if num == 0.0 { 0.0 } else { num / (s[p] + s[q]) }
            }
        })
    }

    /// B(M, N) of eq. F5.
    fn bilinear(&self, m: &SMatrix<f64, D, D>, n: &SMatrix<f64, D, D>) -> f64 {
        let (s, b) = (&self.svd.sigma, &self.b);
        let mut acc = 0.0;
        // Off-diagonal p ≠ q (only needed where b_p b_q ≠ 0).
        let (gm, gn) = (self.g(m), self.g(n));
        let x = m.transpose() * n + n.transpose() * m - gm * gn - gn * gm;
        for p in 0..D {
            for q in 0..D {
                if p != q && b[p] * b[q] != 0.0 {
                    acc += b[p] * b[q] * mul0(1.0 / (s[p] + s[q]), x[(p, q)]);
                }
            }
        }
        // Diagonal p = q, cancellation-free.
        for p in 0..D {
            if b[p] == 0.0 {
                continue;
            }
            let mut dp = 0.0;
            for k in (0..D).filter(|&k| k != p) {
                let (m1, m2, n1, n2) = (m[(p, k)], m[(k, p)], n[(p, k)], n[(k, p)]);
                let sum = s[p] + s[k];
                let (dm, dn) = (m2 - m1, n2 - n1);
                let t = 2.0 * m2 * n2 - m2 * n1 - n2 * m1 - mul0(s[p] / sum, dm * dn);
                dp += mul0(1.0 / sum, t);
            }
            acc += b[p] * b[p] * dp;
        }
        acc
    }

    /// ∂²I4/∂f² (d² × d², column-major vec), eq. F5 rotated to F-space.
    pub fn hess4<const N: usize>(&self) -> SMatrix<f64, N, N> {
        let unit = |k: usize| {
            let mut e = SMatrix::<f64, D, D>::zeros();
            e[(k % D, k / D)] = 1.0;
            e
        };
        let mut hm = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            for j in i..N {
                let v = self.bilinear(&unit(i), &unit(j));
                hm[(i, j)] = v;
                hm[(j, i)] = v;
            }
        }
        // K = V ⊗ U: K[(c, r), (c', r')] = V[c, c'] U[r, r'].
        let (u, v) = (&self.svd.u, &self.svd.v);
        let k = SMatrix::<f64, N, N>::from_fn(|i, j| v[(i / D, j / D)] * u[(i % D, j % D)]);
        k * hm * k.transpose()
    }

    /// ∂²I5/∂f² = 2 (a aᵀ ⊗ I_d) (eq. F3).
    pub fn hess5<const N: usize>(a: &SVector<f64, D>) -> SMatrix<f64, N, N> {
        SMatrix::from_fn(|i, j| {
            if i % D == j % D {
                2.0 * a[i / D] * a[j / D]
            } else {
                0.0
            }
        })
    }
}
