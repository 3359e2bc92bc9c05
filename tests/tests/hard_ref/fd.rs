//! The reference Ψ(F), ∇Ψ(F) and ∂²Ψ/∂f² at an f64 deformation gradient:
//! Ψ(F) = Ψ(σ(F)) in double-double ([`super::svd`], [`super::graph`]) and
//! fourth-order central differences of it, also in double-double:
//!
//! * gradient: [8(Ψ₊ₕ − Ψ₋ₕ) − (Ψ₊₂ₕ − Ψ₋₂ₕ)] / 12h,
//! * Hessian diagonal: [−Ψ₊₂ₕ + 16Ψ₊ₕ − 30Ψ₀ + 16Ψ₋ₕ − Ψ₋₂ₕ] / 12h²,
//! * off-diagonal: D(h) = [Ψ₊₊ − Ψ₊₋ − Ψ₋₊ + Ψ₋₋] / 4h², then (4D(h) − D(2h))/3.
//!
//! With the step h = 2⁻¹³·L (L: distance to the nearest set where Ψ(F) is
//! not smooth, see [`step_for`]) the truncation error is ≈ (h/L)⁴ ≈ 10⁻¹⁶
//! relative and rounding ≈ u·|Ψ|/h² with u ≈ 10⁻³², far below f64 for every
//! case here. The steps are exact powers of two, so F ± h·e_k is exact.

use super::dd::Dd;
use super::graph::PsiGraph;
use super::svd::signed_sigma;

/// Ψ, vec(∂Ψ/∂F) (column-major) and the d²×d² Hessian, rounded to f64.
#[derive(Clone, Debug)]
pub struct Reference {
    /// Ψ(F).
    pub psi: f64,
    /// vec(∂Ψ/∂F), column-major: index c·d + r is ∂Ψ/∂F_rc.
    pub grad: Vec<f64>,
    /// ∂²Ψ/∂f², row-major n×n with n = d².
    pub hess: Vec<f64>,
    /// The step used.
    pub h: f64,
}

/// Ψ(F) in double-double for F given column-major.
pub fn psi_f(g: &PsiGraph, f: &[Dd], d: usize) -> Dd {
    g.psi(&signed_sigma(f, d))
}

/// The largest power of two ≤ 2⁻¹³·L.
pub fn step_for(l: f64) -> f64 {
    let h = l * 2f64.powi(-13);
    2f64.powi(h.log2().floor() as i32)
}

/// The reference at F (column-major f64) with step `h`, or `None` if Ψ is
/// not finite at F or at any stencil point (outside the domain).
pub fn reference(g: &PsiGraph, f: &[f64], d: usize, h: f64) -> Option<Reference> {
    let n = d * d;
    let base: Vec<Dd> = f.iter().map(|x| Dd::from_f64(*x)).collect();
    let at = |moves: &[(usize, f64)]| {
        let mut x = base.clone();
        for &(k, t) in moves {
            x[k] = x[k] + Dd::from_f64(t);
        }
        psi_f(g, &x, d)
    };
    let p0 = at(&[]);
    let mut finite = p0.is_finite();
    let mut grad = vec![0.0; n];
    let mut hess = vec![0.0; n * n];
    let hd = Dd::from_f64(h);
    for i in 0..n {
        let (p1, m1, p2, m2) = (
            at(&[(i, h)]),
            at(&[(i, -h)]),
            at(&[(i, 2.0 * h)]),
            at(&[(i, -2.0 * h)]),
        );
        finite &= [p1, m1, p2, m2].iter().all(|v| v.is_finite());
        let g = ((p1 - m1).scale(8.0) - (p2 - m2)) / (hd * Dd::from_f64(12.0));
        grad[i] = g.to_f64();
        let dd = (-p2 + p1.scale(16.0) - p0 * Dd::from_f64(30.0) + m1.scale(16.0) - m2)
            / (hd * hd * Dd::from_f64(12.0));
        hess[i * n + i] = dd.to_f64();
        for j in 0..i {
            let mixed = |s: f64| {
                let v = at(&[(i, s), (j, s)]) - at(&[(i, s), (j, -s)]) - at(&[(i, -s), (j, s)])
                    + at(&[(i, -s), (j, -s)]);
                (v, v / (Dd::from_f64(s) * Dd::from_f64(s)).scale(4.0))
            };
            let (v1, d1) = mixed(h);
            let (v2, d2) = mixed(2.0 * h);
            finite &= v1.is_finite() && v2.is_finite();
            let m = (d1.scale(4.0) - d2) / Dd::from_f64(3.0);
            hess[i * n + j] = m.to_f64();
            hess[j * n + i] = m.to_f64();
        }
    }
    finite.then_some(Reference {
        psi: p0.to_f64(),
        grad,
        hess,
        h,
    })
}
