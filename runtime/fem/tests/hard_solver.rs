//! The solver never outputs NaN, and a solve that cannot succeed ends with
//! a report — why (the status), where (the stencil, the step), and the best
//! iterate kept in the positions — not garbage. Each test builds a hostile
//! problem a user can produce by mistake:
//!
//! * an energy unbounded below (a sign typo: Ψ = −‖F‖²): diverges;
//! * an energy that returns NaN in part of its domain (a buggy formula);
//! * an energy whose gradient has the wrong sign (inconsistent derivatives);
//! * a barrier energy started from an inverted element;
//! * an iteration cap far too small (stalled);
//! * non-finite or wrongly sized positions and out-of-range handles.
//!
//! Common assertions ([`check_report`]): the returned positions are finite,
//! the reported energy is the energy of the returned positions and is not
//! above the initial one, no record holds a NaN, and the result serialises
//! to JSON (non-finite numbers become `null`).

mod common;

use std::sync::Arc;

use common::grid;
use ecc_fem::{
    Elastic, FemError, NewtonParams, NewtonResult, NewtonSolver, NewtonStatus, Term, Tri,
};
use ecc_runtime::energies::{Arap, SymmetricDirichlet};
use ecc_runtime::{Energy, EnergyInfo, Spectral, spectral_from_invariants};

/// Ψ = −‖F‖²: unbounded below.
struct Unbounded;

impl Energy<2> for Unbounded {
    fn name(&self) -> &str {
        "unbounded"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        -(s[0] * s[0] + s[1] * s[1])
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        spectral_from_invariants(s, self.psi(s), [0.0, -1.0, 0.0], [0.0; 6], true, true)
    }
}

/// ARAP, except Ψ = NaN (and NaN derivatives) wherever σ0 > 1.3.
struct NanAbove;

impl Energy<2> for NanAbove {
    fn name(&self) -> &str {
        "nan-above-1.3"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        if s[0] > 1.3 { f64::NAN } else { Arap.psi(s) }
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        let mut sp = Arap.spectral(s);
        if s[0] > 1.3 {
            sp.psi = f64::NAN;
            sp.grad = [f64::NAN; 2];
        }
        sp
    }
}

/// ARAP with the gradient negated (the Hessian is right).
struct WrongGradient;

impl Energy<2> for WrongGradient {
    fn name(&self) -> &str {
        "wrong-gradient"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        Arap.psi(s)
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        let mut sp = Arap.spectral(s);
        sp.grad = sp.grad.map(|g| -g);
        sp
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo::default()
    }
}

/// The grid's left column (fixed handles).
fn left(m: usize) -> Vec<usize> {
    (0..=m).map(|i| i * (m + 1)).collect()
}

fn solver<E: Energy<2> + 'static>(
    e: E,
    m: usize,
    params: NewtonParams,
) -> (NewtonSolver<2>, Vec<[f64; 2]>) {
    let (rest, tris) = grid(m);
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(
        Elastic::<_, Tri>::planar(Arc::new(e), &rest, &tris).unwrap(),
    )];
    let s = NewtonSolver::new(rest.len(), terms, &left(m), params).unwrap();
    (s, rest)
}

/// The assertions every hostile solve must pass (see the module docs).
fn check_report(s: &mut NewtonSolver<2>, x: &[[f64; 2]], r: &NewtonResult) {
    assert!(
        x.iter().flatten().all(|c| c.is_finite()),
        "non-finite positions returned ({:?})",
        r.status
    );
    assert!(!r.energy.is_nan() && !r.initial_energy.is_nan(), "{r:?}");
    assert!(!r.grad_inf.is_nan(), "{r:?}");
    for rec in &r.records {
        for v in [
            rec.energy,
            rec.grad_inf,
            rec.step,
            rec.decrement,
            rec.dx_inf,
        ] {
            assert!(!v.is_nan(), "NaN in record {rec:?}");
        }
    }
    if r.energy.is_finite() {
        // the returned positions are the reported (best) iterate
        let e = s.energy(x).unwrap();
        assert_eq!(
            e, r.energy,
            "reported energy is not that of the returned positions"
        );
        // 1e-12 relative: the line search may accept a rounding-level increase
        assert!(
            r.energy <= r.initial_energy + 1e-12 * r.initial_energy.abs().max(1.0),
            "energy went up: {} → {}",
            r.initial_energy,
            r.energy
        );
    }
    // JSON has no NaN/∞: non-finite numbers are written as null, so the
    // result always serialises to valid JSON and reads back.
    let json = serde_json::to_string(r).expect("the result serialises");
    let back: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    assert!(back["status"]["kind"].is_string(), "{json}");
}

/// Pull the right column of the grid away from the fixed left column.
fn stretched(rest: &[[f64; 2]], m: usize, by: f64) -> Vec<[f64; 2]> {
    assert_eq!(rest.len(), (m + 1) * (m + 1));
    rest.iter()
        .map(|p| [p[0] * (1.0 + by * p[0]), p[1]])
        .collect()
}

#[test]
fn an_energy_unbounded_below_ends_with_a_report_not_garbage() {
    let params = NewtonParams {
        max_iters: 200,
        ..Default::default()
    };
    let (mut s, rest) = solver(Unbounded, 4, params);
    let mut x = rest.clone();
    let r = s.solve(&mut x).unwrap();
    assert!(
        !r.converged(),
        "an unbounded energy cannot converge: {:?}",
        r.status
    );
    check_report(&mut s, &x, &r);
    assert!(
        r.energy < r.initial_energy,
        "the energy decreased while diverging"
    );
}

#[test]
fn an_energy_that_returns_nan_is_reported_with_its_element() {
    // Started inside the NaN region (σ0 up to ≈ 3 near the right side):
    // the first assembly names the stencil and nothing moves.
    let (mut s, rest) = solver(NanAbove, 4, NewtonParams::default());
    let mut x = stretched(&rest, 4, 1.0);
    let x0 = x.clone();
    let r = s.solve(&mut x).unwrap();
    match &r.status {
        NewtonStatus::NonFinite(b) => {
            assert_eq!(b.term, "elastic", "{b:?}");
            assert!(b.stencil < 32, "{b:?}");
            assert!(["energy", "gradient", "hessian"].contains(&b.quantity.as_str()));
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert_eq!(x, x0, "positions must be left at the start");
    assert_eq!(r.iterations, 0);
    let json = serde_json::to_string(&r).unwrap();
    assert!(
        json.contains("\"NonFinite\"") && json.contains("\"stencil\""),
        "{json}"
    );
}

#[test]
fn a_wrong_gradient_ends_with_a_line_search_report_and_the_start_kept() {
    let (mut s, rest) = solver(WrongGradient, 4, NewtonParams::default());
    let mut x = stretched(&rest, 4, 0.3);
    let x0 = x.clone();
    let r = s.solve(&mut x).unwrap();
    match r.status {
        NewtonStatus::LineSearchFailed { last_step, .. } => {
            assert!(last_step > 0.0 && last_step < 1e-10, "{last_step}");
        }
        ref other => panic!("expected a line-search failure, got {other:?}"),
    }
    check_report(&mut s, &x, &r);
    assert_eq!(x, x0, "no step may be taken along an ascent direction");
}

#[test]
fn a_barrier_energy_started_inverted_names_the_element_and_keeps_the_start() {
    let (rest, tris) = grid(3);
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(
        Elastic::<_, Tri>::planar(Arc::new(SymmetricDirichlet), &rest, &tris).unwrap(),
    )];
    let mut s = NewtonSolver::new(rest.len(), terms, &left(3), NewtonParams::default()).unwrap();
    let mut x = rest.clone();
    // fold vertex 5 (interior) across its neighbours: its triangles invert
    x[5] = [x[5][0] + 0.6, x[5][1] + 0.6];
    let x0 = x.clone();
    let r = s.solve(&mut x).unwrap();
    match &r.status {
        NewtonStatus::NonFinite(b) => {
            assert_eq!(b.quantity, "energy", "{b:?}");
            let t = tris[b.stencil];
            assert!(
                t.contains(&5),
                "stencil {} = {t:?} does not touch vertex 5",
                b.stencil
            );
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert_eq!(x, x0);
    assert_eq!(r.energy, f64::INFINITY);
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"energy\":null"), "{json}");
}

#[test]
fn a_stalled_solve_reports_max_iterations_and_keeps_its_best_iterate() {
    let params = NewtonParams {
        max_iters: 2,
        tol_abs: 1e-14,
        ..Default::default()
    };
    let (mut s, rest) = solver(SymmetricDirichlet, 6, params);
    let mut x = stretched(&rest, 6, 1.5);
    let r = s.solve(&mut x).unwrap();
    assert_eq!(r.status, NewtonStatus::MaxIterations);
    assert_eq!(r.iterations, 2);
    assert!(r.energy < r.initial_energy);
    check_report(&mut s, &x, &r);
}

#[test]
fn bad_positions_and_handles_are_errors_naming_the_vertex() {
    let (mut s, rest) = solver(Arap, 2, NewtonParams::default());
    let mut x = rest.clone();
    x[4][1] = f64::NAN;
    let e = s.solve(&mut x).unwrap_err();
    assert_eq!(
        e,
        FemError::NonFinitePosition {
            what: "positions",
            vertex: 4
        }
    );
    assert!(e.to_string().contains("vertex 4"), "{e}");
    let mut short = rest[..3].to_vec();
    let e = s.solve(&mut short).unwrap_err();
    assert!(e.to_string().contains("expected length 9, got 3"), "{e}");
    x[4][1] = f64::INFINITY;
    assert!(s.energy(&x).is_err());

    let (rest, tris) = grid(2);
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(
        Elastic::<_, Tri>::planar(Arc::new(Arap), &rest, &tris).unwrap(),
    )];
    let e = NewtonSolver::new(rest.len(), terms, &[99], NewtonParams::default())
        .err()
        .expect("out-of-range handle");
    assert!(
        e.to_string().contains("fixed vertex 99 out of range"),
        "{e}"
    );
}
