//! Twist and flip eigenvalues as divided differences, with their removable
//! singularities resolved (Zhu 2020 §4; Smith et al. 2019 §4.3).
//!
//! For a pair (i, j) with Ψ_i = ∂Ψ/∂σ_i and A = ∂²Ψ/∂σ²:
//!
//! * flip  λ_l = (Ψ_i − Ψ_j)/(σ_i − σ_j),
//! * twist λ_t = (Ψ_i + Ψ_j)/(σ_i + σ_j).
//!
//! **Flip at σ_i ≈ σ_j.** Isotropy makes Ψ symmetric under σ_i ↔ σ_j, so along
//! (m + t, m − t) the numerator h(t) = Ψ_i − Ψ_j is odd in t and
//! h(t)/(2t) = h′(0)/2 + O(t²) with h′(0)/2 = (A_ii + A_jj)/2 − A_ij. Evaluating
//! that expression at the actual point (rather than at t = 0) differs from the
//! exact quotient by O((σ_i − σ_j)²) because h′ is even.
//!
//! **Twist at σ_i ≈ −σ_j.** If Ψ is *sign-symmetric*, i.e. unchanged by
//! (σ_i, σ_j) ↦ (−σ_j, −σ_i) (every function of I2 = ‖F‖² and I3 = det F, every
//! function of FᵀF), the same argument on g(s) = Ψ_i + Ψ_j along
//! (a + s/2, −a + s/2) gives the limit (A_ii + A_jj)/2 + A_ij with O((σ_i+σ_j)²)
//! error. Energies with I1 = tr S (ARAP, co-rotational, SARAP) are not
//! sign-symmetric: their twist has a genuine pole (ARAP: 2 − 4/(σ_i+σ_j)) and the
//! direct quotient is returned (±∞ or NaN exactly on the pole; the filters
//! drop such modes, see [`crate::filter`]).
//!
//! **Switch threshold.** The direct quotient of Ψ_i, Ψ_j (each with relative
//! rounding error ≈ ε) has relative error ≈ ε·|σ|/|δ| for a gap δ; the limit
//! form has relative error ≈ (δ/|σ|)². They balance at δ/|σ| = ε^{1/3} ≈ 6·10⁻⁶
//! ([`LIMIT_TOL`]), so either branch is accurate to ≈ ε^{2/3} ≈ 4·10⁻¹¹ relative
//! (times the energy's own derivative scale). The test is
//! |σ_i ∓ σ_j| ≤ τ·max(|σ_i|, |σ_j|), so exact equality (including σ = 0)
//! always takes the limit form and the runtime never divides by a vanishing
//! removable difference.

/// Relative switch threshold τ = ε^{1/3} between the direct divided difference
/// and its limit form.
pub const LIMIT_TOL: f64 = 6.055_454_452_393_343e-6;

/// λ_flip = (Ψ_i − Ψ_j)/(σ_i − σ_j), or (A_ii + A_jj)/2 − A_ij when
/// |σ_i − σ_j| ≤ [`LIMIT_TOL`]·max(|σ_i|, |σ_j|).
#[inline]
pub fn flip_value(si: f64, sj: f64, gi: f64, gj: f64, aii: f64, ajj: f64, aij: f64) -> f64 {
    let d = si - sj;
    if d.abs() <= LIMIT_TOL * si.abs().max(sj.abs()) {
        0.5 * (aii + ajj) - aij
    } else {
        (gi - gj) / d
    }
}

/// λ_twist = (Ψ_i + Ψ_j)/(σ_i + σ_j); for a sign-symmetric energy,
/// (A_ii + A_jj)/2 + A_ij when |σ_i + σ_j| ≤ [`LIMIT_TOL`]·max(|σ_i|, |σ_j|).
///
/// For energies that are not sign-symmetric the quotient is returned as is
/// (a genuine pole: ±∞ or NaN exactly at σ_i + σ_j = 0).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn twist_value(
    si: f64,
    sj: f64,
    gi: f64,
    gj: f64,
    aii: f64,
    ajj: f64,
    aij: f64,
    sign_symmetric: bool,
) -> f64 {
    let s = si + sj;
    if sign_symmetric && s.abs() <= LIMIT_TOL * si.abs().max(sj.abs()) {
        0.5 * (aii + ajj) + aij
    } else {
        (gi + gj) / s
    }
}

/// True when σ_i + σ_j is within the twist switch band (see [`twist_value`]).
#[inline]
pub fn near_antipodal(si: f64, sj: f64) -> bool {
    (si + sj).abs() <= LIMIT_TOL * si.abs().max(sj.abs())
}
