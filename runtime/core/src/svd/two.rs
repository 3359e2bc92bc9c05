//! Closed-form signed SVD of a 2×2 matrix.
//!
//! Split F = [[a, b], [c, d]] into a similarity and an anti-similarity part:
//!
//! F = Q·rot(α₂) + R·refl(α₁),  E = (a+d)/2, H = (c−b)/2, P = (a−d)/2, G = (c+b)/2,
//! Q = |(E, H)|, α₂ = atan2(H, E), R = |(P, G)|, α₁ = atan2(G, P),
//!
//! with rot(α) = [[cos α, −sin α], [sin α, cos α]] and refl(α) = rot(α)·diag(1, −1).
//! Since rot(φ)·diag(Q+R, Q−R)·rot(ψ)ᵀ = Q·rot(φ−ψ) + R·refl(φ+ψ), the choice
//! φ = (α₁+α₂)/2, ψ = (α₁−α₂)/2 gives U = rot(φ), V = rot(ψ) ∈ SO(2) and
//! σ = (Q+R, Q−R). Then σ_0 ≥ |σ_1| and sign σ_1 = sign(Q² − R²) = sign det F.
//! Repeated (R = 0) and zero (Q = R) singular values need no special case:
//! atan2(0, 0) = 0 picks a valid rotation.

use super::{Svd, non_finite};
use nalgebra::{Matrix2, SMatrix};

/// (E, H, P, G) of the module docs for the leading 2×2 block of `m`: the
/// similarity part E·I + H·J and the anti-similarity part P·K + G·L
/// (also used to rotate a direction into the SVD's frame,
/// `element::curvature`).
#[inline]
pub(crate) fn conformal_parts<const D: usize>(m: &SMatrix<f64, D, D>) -> [f64; 4] {
    let (a, b, c, d) = (m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)]);
    [0.5 * (a + d), 0.5 * (c - b), 0.5 * (a - d), 0.5 * (c + b)]
}

/// Signed SVD of a 2×2 matrix: U, V ∈ SO(2), σ_0 ≥ |σ_1|, σ_1 < 0 iff det F < 0.
pub fn signed_svd2(f: &Matrix2<f64>) -> Svd<2> {
    if !f.iter().all(|x| x.is_finite()) {
        return non_finite();
    }
    let [e, h, p, g] = conformal_parts(f);
    let q = e.hypot(h);
    let r = p.hypot(g);
    let a2 = h.atan2(e);
    let a1 = g.atan2(p);
    let (sphi, cphi) = (0.5 * (a1 + a2)).sin_cos();
    let (spsi, cpsi) = (0.5 * (a1 - a2)).sin_cos();
    Svd {
        u: Matrix2::new(cphi, -sphi, sphi, cphi),
        sigma: [q + r, q - r],
        v: Matrix2::new(cpsi, -spsi, spsi, cpsi),
    }
}
