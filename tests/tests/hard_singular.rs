//! Where an energy is itself singular — det F = 0, inverted elements for
//! barrier energies (log J, SD's 1/σ², Ogden's σ^1.5, Hencky's log σ), and
//! Ψ overflowing or underflowing f64 — every energy returns +∞ or a finite
//! value, never NaN, and the runtime turns +∞ into zero derivatives and
//! finite filtered Hessians. Element rest shapes that are degenerate or
//! inverted are refused with an error that says which.
//!
//! Checked for every implementation of every built-in and example energy
//! (`hard_ref::energies`), in 2D and 3D:
//!
//! * Ψ is never NaN or −∞; `psi` and `spectral.psi` agree; Ψ = +∞ comes
//!   with `Spectral::infinite()` (zero derivatives, no NaN);
//! * wherever Ψ is finite the clamped F-space Hessian is finite;
//! * for σ of moderate size (|σ| in [1e-3, 10] or exactly 0) the spectral
//!   data has no NaN — except a twist/flip at a genuine pole (σi + σj = 0
//!   exactly for an energy that is not sign-symmetric, where no limit
//!   exists); barrier energies (the compiler's `barrier` flag) give
//!   Ψ = +∞ at det F = 0 and wherever the reference (the CAS graph in
//!   double-double) is undefined; other energies give the reference value
//!   at det F = 0. At extreme σ (1e-160, 1e200, f64::MAX) derivatives may
//!   overflow f64; then only Ψ and the filtered Hessian are checked;
//! * the element kernels (`element_eval` in 3D and 2D) on a collapsed or
//!   inverted current element give Ψ = +∞ with zero gradient and Hessian,
//!   or finite values — never NaN — for every filter but `None`.

// `!(err <= tol)` on purpose: a NaN error must fail.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod hard_ref;

use ecc_runtime::{
    Energy, Filter, Rest, RestError, ScaleBlock, Spectral, element_eval, hessian_f, signed_svd2,
    signed_svd3,
};
use hard_ref::dd::Dd;
use hard_ref::energies::{Formula, formulas2, formulas3};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

const FILTERS: [Filter; 3] = [Filter::Clamp, Filter::Abs, Filter::ClampEps(1e-3)];

/// σ on or beyond the singular sets, in the runtime's order.
fn sigmas3() -> Vec<[f64; 3]> {
    vec![
        [1.0, 1.0, 0.0],
        [1.3, 0.7, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.2, 0.8, -0.0],
        [1.3, 0.7, -0.4],
        [1.0, 1.0, -1.0],
        [2.0, 1.0, -5e-324],
        [1.0, 1e-160, 1e-160],
        [1e-200, 1e-200, 1e-200],
        [1e200, 1e200, 1e200],
        [1e155, 1.0, 1.0],
        [f64::MAX, 1.0, 0.5],
    ]
}

fn sigmas2() -> Vec<[f64; 2]> {
    vec![
        [1.0, 0.0],
        [0.0, 0.0],
        [1.2, -0.0],
        [1.3, -0.4],
        [1.0, -1.0],
        [2.0, -5e-324],
        [1e-200, 1e-200],
        [1e200, 1e200],
        [1e155, 1.0],
        [f64::MAX, 0.5],
    ]
}

/// Whether a pair eigenvalue slot is a genuine pole: σi + σj = 0 exactly
/// for an energy that is not sign-symmetric (no limit exists; ±∞ or NaN
/// are the honest raw values there, and every filter drops the mode).
fn pole<const D: usize>(sigma: &[f64; D], k: usize, sign_symmetric: bool) -> bool {
    let (i, j) = ecc_runtime::pair_indices::<D>(k);
    !sign_symmetric && sigma[i] + sigma[j] == 0.0
}

/// The first NaN in the spectral data, if any (poles excepted).
fn nan_in<const D: usize>(s: &Spectral<D>, sigma: &[f64; D], sign_symmetric: bool) -> bool {
    let scale: Vec<f64> = match s.scale {
        ScaleBlock::Diagonal(a) => a.to_vec(),
        ScaleBlock::Full(a) => a.iter().flatten().copied().collect(),
    };
    let pairs_nan = (0..Spectral::<D>::PAIRS)
        .any(|k| (s.twist[k].is_nan() || s.flip[k].is_nan()) && !pole(sigma, k, sign_symmetric));
    s.psi.is_nan()
        || s.grad.iter().any(|x| x.is_nan())
        || scale.iter().any(|x| x.is_nan())
        || pairs_nan
}

/// σ in the range where f64 represents Ψ and its derivatives (|σ| in
/// [1e-3, 10], or exactly 0). Beyond it (σ = 1e-160, 1e200, …) a derivative
/// may overflow: only Ψ itself and the filtered Hessian are then checked.
fn moderate(sigma: &[f64]) -> bool {
    sigma
        .iter()
        .all(|x| x.abs() <= 10.0 && (*x == 0.0 || x.abs() >= 1e-3))
}

fn check_sigma<const D: usize>(formula: &Formula<D>, sigma: [f64; D], failures: &mut Vec<String>)
where
    Spectral<D>: Lift,
{
    let ir = formula.ir();
    let reference = formula.graph.psi(&sigma.map(Dd::from_f64)).to_f64();
    let det_zero = sigma.contains(&0.0);
    let moderate = moderate(&sigma);
    for imp in &formula.impls {
        let who = format!("{} ({}) {D}D at σ = {sigma:?}", formula.name, imp.kind);
        let e = imp.energy.as_ref();
        let psi = e.psi(&sigma);
        let s = e.spectral(&sigma);
        if psi.is_nan() || psi == f64::NEG_INFINITY {
            failures.push(format!("{who}: Ψ = {psi}"));
            continue;
        }
        // 1e-14: the two routes may round differently by an ulp or two
        if !(psi == s.psi || (psi - s.psi).abs() <= 1e-14 * psi.abs()) {
            failures.push(format!("{who}: psi {psi} vs spectral.psi {}", s.psi));
        }
        if psi == f64::INFINITY {
            if s != Spectral::infinite() {
                failures.push(format!("{who}: Ψ = +∞ but derivatives {s:?}"));
            }
            if !moderate || ir.barrier {
                continue;
            }
        }
        if !s.clamped_finite(&sigma) {
            failures.push(format!("{who}: the clamped Hessian is not finite ({s:?})"));
        }
        if !moderate {
            continue;
        }
        if nan_in(&s, &sigma, ir.sign_symmetric) {
            failures.push(format!("{who}: NaN in {s:?}"));
        }
        if ir.barrier && (det_zero || !reference.is_finite()) && psi != f64::INFINITY {
            failures.push(format!(
                "{who}: barrier energy gives Ψ = {psi} (reference {reference})"
            ));
        }
        if !ir.barrier && det_zero {
            // a non-barrier energy is defined at det F = 0: the formula value
            let tol = 1e-12 * reference.abs().max(1.0);
            if !((psi - reference).abs() <= tol) {
                failures.push(format!("{who}: Ψ = {psi}, reference {reference}"));
            }
        }
    }
}

/// The clamped F-space Hessian at F = diag(σ) has no NaN or ∞.
trait Lift {
    fn clamped_finite(&self, sigma: &[f64]) -> bool;
}

impl Lift for Spectral<3> {
    fn clamped_finite(&self, sigma: &[f64]) -> bool {
        let f = Matrix3::from_diagonal(&Vector3::from_column_slice(sigma));
        hessian_f(&signed_svd3(&f), self, Filter::Clamp)
            .iter()
            .all(|x| x.is_finite())
    }
}

impl Lift for Spectral<2> {
    fn clamped_finite(&self, sigma: &[f64]) -> bool {
        let f = Matrix2::from_diagonal(&Vector2::from_column_slice(sigma));
        hessian_f(&signed_svd2(&f), self, Filter::Clamp)
            .iter()
            .all(|x| x.is_finite())
    }
}

/// A collapsed / inverted current tetrahedron for every filter.
fn check_tets(formula: &Formula<3>, failures: &mut Vec<String>) {
    let rest =
        Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap();
    let shapes: [(&str, [[f64; 3]; 4]); 4] = [
        (
            "flat",
            [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.3, 0.3, 0.0]],
        ),
        (
            "inverted",
            [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]],
        ),
        ("point", [[0.5; 3]; 4]),
        (
            "needle",
            [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]],
        ),
    ];
    for imp in &formula.impls {
        for (name, x) in &shapes {
            for fl in FILTERS {
                let ev = element_eval(imp.energy.as_ref(), &rest, x, fl, true);
                let who = format!("{} ({}) {name} tet, {fl:?}", formula.name, imp.kind);
                element_ok(
                    &who,
                    ev.psi,
                    ev.grad.as_slice(),
                    ev.hess.as_slice(),
                    failures,
                );
            }
        }
    }
}

fn check_tris(formula: &Formula<2>, failures: &mut Vec<String>) {
    let rest = Rest::<2>::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).unwrap();
    let shapes: [(&str, [[f64; 2]; 3]); 3] = [
        ("flat", [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]),
        ("inverted", [[0.0, 0.0], [1.0, 0.0], [0.0, -1.0]]),
        ("point", [[0.5, 0.5]; 3]),
    ];
    for imp in &formula.impls {
        for (name, x) in &shapes {
            for fl in FILTERS {
                let ev = element_eval(imp.energy.as_ref(), &rest, x, fl, true);
                let who = format!("{} ({}) {name} triangle, {fl:?}", formula.name, imp.kind);
                element_ok(
                    &who,
                    ev.psi,
                    ev.grad.as_slice(),
                    ev.hess.as_slice(),
                    failures,
                );
            }
        }
    }
}

fn element_ok(who: &str, psi: f64, grad: &[f64], hess: &[f64], failures: &mut Vec<String>) {
    if psi.is_nan() || psi == f64::NEG_INFINITY {
        failures.push(format!("{who}: Ψ = {psi}"));
    } else if psi == f64::INFINITY {
        if grad.iter().chain(hess).any(|x| *x != 0.0) {
            failures.push(format!("{who}: Ψ = +∞ but non-zero derivatives"));
        }
    } else if !grad.iter().chain(hess).all(|x| x.is_finite()) {
        failures.push(format!("{who}: Ψ = {psi} but non-finite derivatives"));
    }
}

fn finish(failures: Vec<String>) {
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn singular_sigma_give_infinity_or_finite_values_never_nan_3d() {
    let mut failures = Vec::new();
    for formula in formulas3() {
        for s in sigmas3() {
            check_sigma(&formula, s, &mut failures);
        }
        check_tets(&formula, &mut failures);
    }
    finish(failures);
}

#[test]
fn singular_sigma_give_infinity_or_finite_values_never_nan_2d() {
    let mut failures = Vec::new();
    for formula in formulas2() {
        for s in sigmas2() {
            check_sigma(&formula, s, &mut failures);
        }
        check_tris(&formula, &mut failures);
    }
    finish(failures);
}

#[test]
fn degenerate_and_inverted_rest_shapes_are_refused_with_their_reason() {
    let flat = Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]);
    assert!(
        matches!(flat, Err(RestError::Degenerate { .. })),
        "{flat:?}"
    );
    let e = flat.unwrap_err().to_string();
    assert!(e.contains("degenerate rest element"), "{e}");
    let inverted = Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]);
    assert!(matches!(inverted, Err(RestError::Inverted { measure }) if measure < 0.0));
    assert!(
        inverted
            .unwrap_err()
            .to_string()
            .contains("inverted rest element")
    );
    let nan = Rest::<3>::new([
        [0.0; 3],
        [f64::NAN, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]);
    assert!(matches!(nan, Err(RestError::Degenerate { measure }) if measure.is_nan()));
    let sliver = Rest::<3>::new([
        [0.0; 3],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.2, 0.2, 1e-17],
    ]);
    assert!(
        matches!(sliver, Err(RestError::Degenerate { .. })),
        "{sliver:?}"
    );
    let t = Rest::<2>::new([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
    assert!(matches!(t, Err(RestError::Degenerate { .. })), "{t:?}");
    let t = Rest::<2>::new([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]);
    assert!(matches!(t, Err(RestError::Inverted { .. })), "{t:?}");
    let t = Rest::<2>::from_3d([[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]);
    assert!(matches!(t, Err(RestError::Degenerate { .. })), "{t:?}");
    let t = Rest::<2>::new([[0.0, 0.0], [f64::INFINITY, 0.0], [0.0, 1.0]]);
    assert!(matches!(t, Err(RestError::Degenerate { .. })), "{t:?}");
}

/// Every formula is exercised (the loops above would pass vacuously on an
/// empty list).
#[test]
fn the_energy_lists_are_complete() {
    let (f3, f2) = (formulas3(), formulas2());
    assert!(
        f3.len() >= 14 && f2.len() >= 15,
        "{} / {}",
        f3.len(),
        f2.len()
    );
    assert!(
        f3.iter().filter(|f| f.impls.len() == 3).count() >= 3,
        "hand-written ones"
    );
    let barriers = f3.iter().filter(|f| f.ir().barrier).count();
    assert!(barriers >= 5, "{barriers} barrier energies in 3D");
    let _: &dyn Energy<3> = f3[0].impls[0].energy.as_ref();
}
