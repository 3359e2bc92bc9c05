//! Exactly on the singular sets of the pair eigenvalues — σi = σj (flip)
//! and σi = −σj (twist) — every energy returns the limit of the divided
//! difference, checked against a double-double reference computed *off*
//! the set:
//!
//! * ∂Ψ/∂σ from fourth-order central differences of Ψ(σ) (the CAS graph of
//!   the `.psi` source, in double-double, step h = 2⁻³⁰·m);
//! * λ(t) = (Ψi ∓ Ψj)/(σi ∓ σj) at σi = m + t, σj = m − t (flip) or
//!   σi = a + t, σj = −a + t (twist, sign-symmetric energies), which is
//!   even in t;
//! * Richardson: λ₀ ≈ (4λ(t/2) − λ(t))/3 with t = 2⁻¹⁴·m, error O(t⁴) ≈ 1e-17.
//!
//! Where the limit does not exist — the twist of an energy that is not
//! sign-symmetric (ARAP, co-rotational) at σi + σj = 0 — the value must be
//! ±∞ (a genuine pole, dropped by the filters), never NaN, and the filtered
//! Hessians must stay finite.

// `!(err <= tol)` on purpose: a NaN error must fail.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod hard_ref;

use ecc_runtime::{Filter, Spectral, hessian_f, pair_indices};
use hard_ref::dd::Dd;
use hard_ref::energies::{Formula, formulas2, formulas3};
use hard_ref::graph::PsiGraph;
use nalgebra::{Matrix2, Matrix3};

/// |λ − λref| ≤ LIMIT_TOL · max(|λref|, |A_ii|, |A_jj|, 1e-300): the Richardson
/// error (≈ 1e-17) plus the f64 evaluation (worst seen ≈ 3e-13); a sign or
/// factor-2 error is O(1).
const LIMIT_TOL: f64 = 1e-11;

/// ∂Ψ/∂σ_i in double-double at σ (fourth-order central differences).
fn dpsi(g: &PsiGraph, s: &[Dd], i: usize, h: f64) -> Dd {
    let at = |t: f64| {
        let mut x = s.to_vec();
        x[i] = x[i] + Dd::from_f64(t);
        g.psi(&x)
    };
    ((at(h) - at(-h)).scale(8.0) - (at(2.0 * h) - at(-2.0 * h))) / Dd::from_f64(12.0 * h)
}

/// The reference limit of the flip (`plus = false`) or twist (`plus = true`)
/// of pair (i, j) at σ, where σ_i = ±σ_j exactly.
fn limit_reference(g: &PsiGraph, sigma: &[f64], i: usize, j: usize, plus: bool) -> f64 {
    let m = sigma[i].abs();
    let t = m * 2f64.powi(-14);
    let h = 2f64.powi((m * 2f64.powi(-30)).log2().floor() as i32);
    let lambda = |t: f64| {
        let mut s: Vec<Dd> = sigma.iter().map(|x| Dd::from_f64(*x)).collect();
        s[i] = s[i] + Dd::from_f64(t);
        s[j] = s[j] + Dd::from_f64(if plus { t } else { -t });
        let (gi, gj) = (dpsi(g, &s, i, h), dpsi(g, &s, j, h));
        if plus {
            (gi + gj) / (s[i] + s[j])
        } else {
            (gi - gj) / (s[i] - s[j])
        }
    };
    ((lambda(0.5 * t).scale(4.0) - lambda(t)) / Dd::from_f64(3.0)).to_f64()
}

fn check<const D: usize>(
    formula: &Formula<D>,
    sigma: [f64; D],
    k: usize,
    plus: bool,
    failures: &mut Vec<String>,
    worst: &mut f64,
) -> bool
where
    Spectral<D>: ClampFinite,
{
    let (i, j) = pair_indices::<D>(k);
    let what = if plus { "twist" } else { "flip" };
    assert_eq!(sigma[i], if plus { -sigma[j] } else { sigma[j] });
    let ir = formula.ir();
    let inside = formula.graph.psi(&sigma.map(Dd::from_f64)).is_finite();
    if !inside {
        return false;
    }
    let pole = plus && !ir.sign_symmetric;
    let want = (!pole).then(|| limit_reference(&formula.graph, &sigma, i, j, plus));
    for imp in &formula.impls {
        let s = imp.energy.spectral(&sigma);
        let got = if plus { s.twist[k] } else { s.flip[k] };
        let who = format!(
            "{} ({}) {D}D {what} slot {k} at σ = {sigma:?}",
            formula.name, imp.kind
        );
        match want {
            Some(want) => {
                let a = s.scale.to_dense();
                let scale = want.abs().max(a[i][i].abs()).max(a[j][j].abs()).max(1e-300);
                let err = (got - want).abs() / scale;
                *worst = worst.max(err);
                if !(err <= LIMIT_TOL) {
                    failures.push(format!(
                        "{who}: {got:e} vs limit {want:e} (relative {err:.1e})"
                    ));
                }
            }
            None => {
                if got.is_nan() {
                    failures.push(format!("{who}: NaN at the pole"));
                }
                if !s.clamp_finite(&sigma) {
                    failures.push(format!("{who}: filtered Hessian not finite at the pole"));
                }
            }
        }
    }
    true
}

/// The clamped Hessian at F = diag(σ) is finite.
trait ClampFinite {
    fn clamp_finite(&self, sigma: &[f64]) -> bool;
}

impl ClampFinite for Spectral<3> {
    fn clamp_finite(&self, sigma: &[f64]) -> bool {
        let f = Matrix3::from_diagonal(&nalgebra::Vector3::from_column_slice(sigma));
        let h = hessian_f(&ecc_runtime::signed_svd3(&f), self, Filter::Clamp);
        h.iter().all(|x| x.is_finite())
    }
}

impl ClampFinite for Spectral<2> {
    fn clamp_finite(&self, sigma: &[f64]) -> bool {
        let f = Matrix2::from_diagonal(&nalgebra::Vector2::from_column_slice(sigma));
        let h = hessian_f(&ecc_runtime::signed_svd2(&f), self, Filter::Clamp);
        h.iter().all(|x| x.is_finite())
    }
}

fn finish(failures: Vec<String>, checked: usize, min: usize, worst: f64) {
    println!(
        "{checked} limits checked, worst relative error {worst:.1e} (tolerance {LIMIT_TOL:e})"
    );
    assert!(
        failures.is_empty(),
        "{} wrong limits:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(checked >= min, "only {checked} points inside the domains");
}

#[test]
fn limits_on_the_singular_sets_3d() {
    let mut failures = Vec::new();
    let mut checked = 0;
    let mut worst = 0.0f64;
    for formula in formulas3() {
        let f = &formula;
        let mut go = |s: [f64; 3], k: usize, plus: bool| {
            checked += usize::from(check(f, s, k, plus, &mut failures, &mut worst));
        };
        // flips: every slot, moderate, tiny and huge repeated values
        go([1.3, 1.3, 0.7], 2, false);
        go([1.6, 0.9, 0.9], 0, false);
        go([1e3, 1e3, 0.5], 2, false);
        go([1.0, 1e-3, 1e-3], 0, false);
        go([0.8, 0.8, -0.4], 2, false);
        for k in 0..3 {
            go([1.2, 1.2, 1.2], k, false);
            go([0.6, 0.6, 0.6], k, false);
        }
        // twists: σ2 = −σ1 (slot 0), and σ2 = −σ0 = −σ1 (slots 0 and 1)
        go([1.3, 0.8, -0.8], 0, true);
        go([2.0, 0.4, -0.4], 0, true);
        go([0.8, 0.8, -0.8], 0, true);
        go([0.8, 0.8, -0.8], 1, true);
    }
    finish(failures, checked, 150, worst);
}

#[test]
fn limits_on_the_singular_sets_2d() {
    let mut failures = Vec::new();
    let mut checked = 0;
    let mut worst = 0.0f64;
    for formula in formulas2() {
        let f = &formula;
        let mut go = |s: [f64; 2], plus: bool| {
            checked += usize::from(check(f, s, 0, plus, &mut failures, &mut worst));
        };
        go([1.3, 1.3], false);
        go([0.6, 0.6], false);
        go([1e3, 1e3], false);
        go([1e-3, 1e-3], false);
        go([0.8, -0.8], true);
        go([1.7, -1.7], true);
    }
    finish(failures, checked, 50, worst);
}
