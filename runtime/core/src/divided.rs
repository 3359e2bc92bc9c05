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

/// How a twist (Ψ_i + Ψ_j)/(σ_i + σ_j) behaves on σ_i + σ_j = 0, as the
/// compiler decided it (see `ecc_dsl::PairKind`).
///
/// **Removable without sign symmetry.** When Ψ_i + Ψ_j vanishes on the plane
/// but is not odd about it, the plain limit (A_ii + A_jj)/2 + A_ij evaluated
/// off the plane is only first-order accurate. With N(t) = Ψ_i + Ψ_j along
/// σ_i, σ_j ↦ σ_i + t/2, σ_j + t/2 (so the gap grows by t, d/dt = (∂_i + ∂_j)/2),
/// N(t)/t = N′(0) + N″(0)t/2 + O(t²) while N′(t) = N′(0) + N″(0)t + O(t²), so
///
/// λ_t ≈ N′(t) − N″(t)·t/2 = (A_ii + A_jj)/2 + A_ij − (∂_i + ∂_j)(A_ii + 2A_ij + A_jj)·(σ_i + σ_j)/8
///
/// is second-order accurate and keeps the ε^{1/3} switch's ε^{2/3} error. The
/// compiler builds that expression; [`TwistRule::Removable`] carries its value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TwistRule {
    /// No division to resolve (invariant path with Ψ1 ≡ 0), or undeclared:
    /// the quotient as written (0/0 on the plane is taken as its finite part
    /// on the invariant path, +∞ on the stretch path).
    Regular,
    /// Ψ sign-symmetric: removable, limit (A_ii + A_jj)/2 + A_ij (error O(δ²)).
    SignSymmetric,
    /// Removable without sign symmetry: the compiler's corrected limit at this
    /// point, used within the switch band.
    Removable(f64),
    /// A genuine pole of the energy (or not decided): the direct quotient,
    /// and +∞ exactly on σ_i + σ_j = 0 (never NaN).
    Pole,
}

/// λ_twist under `rule` (see [`TwistRule`]); `direct` computes the quotient
/// away from the plane (only called when it is used).
#[inline]
pub fn twist_by_rule(
    si: f64,
    sj: f64,
    sym_limit: impl FnOnce() -> f64,
    direct: impl FnOnce() -> f64,
    rule: TwistRule,
) -> f64 {
    let near = near_antipodal(si, sj);
    match rule {
        TwistRule::SignSymmetric if near => sym_limit(),
        TwistRule::Removable(l) if near => l,
        TwistRule::Pole if si + sj == 0.0 => f64::INFINITY,
        _ => direct(),
    }
}

/// True when σ_i + σ_j is within the twist switch band (see [`twist_value`]).
#[inline]
pub fn near_antipodal(si: f64, sj: f64) -> bool {
    (si + sj).abs() <= LIMIT_TOL * si.abs().max(sj.abs())
}
