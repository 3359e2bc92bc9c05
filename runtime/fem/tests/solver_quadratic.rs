//! The solver infrastructure on quadratic objectives (no elasticity needed):
//! one Newton step solves them exactly, constraints are met, Cholesky and PCG
//! agree, the symbolic factorisation is reused, bad stencils are reported.

mod common;

use common::{OffsetSprings, edges, grid};
use ecc_fem::{Filter, LinearSolver, NewtonParams, NewtonSolver, NewtonStatus, SoftAnchors, Term};

fn springs_problem(m: usize) -> (Vec<[f64; 2]>, Vec<Box<dyn Term<2>>>) {
    let (rest, tris) = grid(m);
    let springs = OffsetSprings::from_rest(&rest, edges(&tris), 3.0);
    (rest, vec![Box::new(springs)])
}

#[test]
fn constrained_quadratic_reaches_the_constraints_in_one_step() {
    let m = 12;
    let (rest, terms) = springs_problem(m);
    // fix the left column, move the right column (Dirichlet handles)
    let left: Vec<usize> = (0..=m).map(|i| i * (m + 1)).collect();
    let right: Vec<usize> = (0..=m).map(|i| i * (m + 1) + m).collect();
    let fixed: Vec<usize> = left.iter().chain(&right).copied().collect();
    let mut solver = NewtonSolver::new(rest.len(), terms, &fixed, NewtonParams::default()).unwrap();
    let mut x = rest.clone();
    for &v in &right {
        x[v][0] += 0.5;
        x[v][1] -= 0.25;
    }
    let targets: Vec<[f64; 2]> = fixed.iter().map(|&v| x[v]).collect();
    let r = solver.solve(&mut x).unwrap();
    assert_eq!(r.status, NewtonStatus::Converged, "{r:?}");
    assert_eq!(r.iterations, 1, "a quadratic needs exactly one Newton step");
    assert!(r.grad_inf <= 1e-9);
    for (&v, t) in fixed.iter().zip(&targets) {
        assert_eq!(x[v], *t, "fixed vertex {v} moved");
    }
    // a minimiser: perturbing free vertices only increases the energy
    let e = solver.energy(&x).unwrap();
    for v in (0..x.len()).filter(|v| !fixed.contains(v)).step_by(7) {
        for c in 0..2 {
            let mut y = x.clone();
            y[v][c] += 1e-3;
            assert!(solver.energy(&y).unwrap() > e);
        }
    }
    // a second solve with moved handles reuses the symbolic analysis
    for &v in &right {
        x[v][1] += 0.1;
    }
    let r2 = solver.solve(&mut x).unwrap();
    assert!(r2.converged());
    assert_eq!(r2.symbolic_analyses, 1);
    assert_eq!(
        solver
            .linear_system()
            .cholesky()
            .unwrap()
            .symbolic_analyses(),
        1
    );
    assert!(r2.numeric_factorizations >= 2);
}

#[test]
fn no_fixed_vertices_uses_the_shift_and_converges() {
    // springs + one soft anchor: the Hessian is nonsingular only through the anchor;
    // without the anchor the translation null space must be handled by the shift
    for anchored in [true, false] {
        let (rest, mut terms) = springs_problem(8);
        if anchored {
            terms.push(Box::new(
                SoftAnchors::new(vec![0], vec![[0.3, 0.1]], vec![1.0]).unwrap(),
            ));
        }
        let params = NewtonParams {
            tol_abs: 1e-10,
            ..Default::default()
        };
        let mut solver = NewtonSolver::new(rest.len(), terms, &[], params).unwrap();
        let mut x: Vec<[f64; 2]> = rest
            .iter()
            .map(|p| [1.5 * p[0] + 0.2 * p[1], p[1] - 0.3 * p[0] * p[0]])
            .collect();
        let r = solver.solve(&mut x).unwrap();
        assert!(r.converged(), "anchored={anchored}: {r:?}");
        assert!(r.iterations <= 3, "{} iterations", r.iterations);
        assert!(
            r.records[0].shift > 0.0,
            "nothing fixed: the null space shift is on"
        );
        if anchored {
            assert!((x[0][0] - 0.3).abs() < 1e-9 && (x[0][1] - 0.1).abs() < 1e-9);
        }
        // converged shape is a translate of the rest shape
        let t = [x[0][0] - rest[0][0], x[0][1] - rest[0][1]];
        for (p, q) in x.iter().zip(&rest) {
            assert!((p[0] - q[0] - t[0]).abs() < 1e-7 && (p[1] - q[1] - t[1]).abs() < 1e-7);
        }
    }
}

#[test]
fn pcg_and_cholesky_give_the_same_newton_step() {
    let m = 10;
    let (rest, tris) = grid(m);
    let make = || -> Vec<Box<dyn Term<2>>> {
        vec![
            Box::new(OffsetSprings::from_rest(&rest, edges(&tris), 2.0)),
            Box::new(
                SoftAnchors::new(vec![0, m], vec![[0.0, 0.0], [1.2, 0.0]], vec![10.0, 10.0])
                    .unwrap(),
            ),
        ]
    };
    let x0: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| [p[0] + 0.1 * (7.0 * p[1]).sin(), p[1] * 0.8])
        .collect();
    let mut steps = Vec::new();
    for kind in [LinearSolver::Cholesky, LinearSolver::Pcg] {
        let params = NewtonParams {
            linear_solver: kind,
            max_iters: 1,
            pcg_rel_max: 1e-12,
            pcg_rel_min: 1e-12,
            ..Default::default()
        };
        let mut solver = NewtonSolver::new(rest.len(), make(), &[], params).unwrap();
        assert_eq!(solver.linear_solver(), kind);
        let mut x = x0.clone();
        let r = solver.solve(&mut x).unwrap();
        assert_eq!(r.iterations, 1);
        if kind == LinearSolver::Pcg {
            assert!(r.records[0].cg_iterations > 0);
        }
        steps.push(x);
    }
    let diff = steps[0]
        .iter()
        .zip(&steps[1])
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0, f64::max);
    assert!(diff < 1e-8, "Cholesky and PCG steps differ by {diff}");
}

/// A term that produces NaN on one stencil.
struct Poisoned;
impl Term<2> for Poisoned {
    fn name(&self) -> &str {
        "poisoned"
    }
    fn arity(&self) -> usize {
        1
    }
    fn stencils(&self) -> &[usize] {
        &[0, 1, 2]
    }
    fn value(&self, s: usize, x: &[[f64; 2]]) -> f64 {
        x[s][0] * x[s][0]
    }
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; 2]],
        _f: Filter,
        g: &mut [f64],
        h: Option<&mut [f64]>,
    ) -> f64 {
        g[0] = if s == 2 { f64::NAN } else { 2.0 * x[s][0] };
        g[1] = 0.0;
        if let Some(h) = h {
            h.copy_from_slice(&[2.0, 0.0, 0.0, 1.0]);
        }
        self.value(s, x)
    }
}

#[test]
fn non_finite_gradient_stops_with_the_stencil_named() {
    let mut solver = NewtonSolver::new(
        3,
        vec![Box::new(Poisoned) as Box<dyn Term<2>>],
        &[],
        NewtonParams::default(),
    )
    .unwrap();
    let mut x = vec![[1.0, 0.0]; 3];
    let r = solver.solve(&mut x).unwrap();
    match r.status {
        NewtonStatus::NonFinite(b) => {
            assert_eq!(b.term, "poisoned");
            assert_eq!(b.stencil, 2);
            assert_eq!(b.quantity, "gradient");
        }
        s => panic!("unexpected status {s:?}"),
    }
    assert!(x.iter().all(|p| p.iter().all(|c| c.is_finite())));
    // bad input is an error, not a panic
    let mut short = vec![[0.0, 0.0]; 2];
    assert!(solver.solve(&mut short).is_err());
    let mut nan = vec![[f64::NAN, 0.0]; 3];
    assert!(solver.solve(&mut nan).is_err());
}

#[test]
fn result_serialises_to_json() {
    let (rest, terms) = springs_problem(4);
    let mut solver = NewtonSolver::new(rest.len(), terms, &[0], NewtonParams::default()).unwrap();
    let mut x: Vec<[f64; 2]> = rest.iter().map(|p| [p[0] * 1.1, p[1]]).collect();
    let r = solver.solve(&mut x).unwrap();
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"kind\":\"Converged\""));
    assert!(json.contains("t_assembly"));
    let back: ecc_fem::NewtonResult = serde_json::from_str(&json).unwrap();
    assert_eq!(back.iterations, r.iterations);
    assert_eq!(back.terms[0].name, "springs");
    assert!(back.terms[0].assembly_passes >= 1);
}

#[test]
fn a_failed_start_still_serialises() {
    let mut solver = NewtonSolver::new(
        3,
        vec![Box::new(Poisoned) as Box<dyn Term<2>>],
        &[],
        NewtonParams::default(),
    )
    .unwrap();
    let mut x = vec![[1.0, 0.0]; 3];
    let r = solver.solve(&mut x).unwrap();
    // the energy is finite (only a gradient entry is NaN); the gradient norm is unknown
    assert_eq!(r.energy, 3.0);
    assert_eq!(r.grad_inf, f64::INFINITY);
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"grad_inf\":null"));
    let back: ecc_fem::NewtonResult = serde_json::from_str(&json).unwrap();
    assert!(back.grad_inf.is_nan(), "null reads back as NaN");
    assert_eq!(back.energy, 3.0);
    assert_eq!(back.status, r.status);
}
