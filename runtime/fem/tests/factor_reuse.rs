//! Reusing a stale Cholesky factor as the preconditioner of CG
//! (`linear::reuse`): fewer factorisations than Newton steps where the
//! Hessian changes slowly, the same minimiser, and a factorisation whenever
//! the stale factor is not good enough.

mod common;

use std::sync::Arc;

use common::grid;
use ecc_fem::linear::FactorReuse;
use ecc_fem::{Elastic, LinearSolver, NewtonParams, NewtonResult, NewtonSolver, Term, Tri};
use ecc_runtime::energies::SymmetricDirichlet;

/// Symmetric Dirichlet on a 16×16 grid, boundary at rest, interior squeezed
/// and swirled (the barrier test's start): ~10–20 Newton steps whose last
/// ones barely change the Hessian. Returns the result and the distance of
/// the answer from the rest shape (the exact minimiser).
fn squeezed(reuse: FactorReuse, tol: f64) -> (NewtonResult, f64) {
    let m = 16;
    let (rest, tris) = grid(m);
    let w = m + 1;
    let boundary: Vec<usize> = (0..w * w)
        .filter(|v| v % w == 0 || v % w == m || v / w == 0 || v / w == m)
        .collect();
    let mut x: Vec<[f64; 2]> = rest
        .iter()
        .enumerate()
        .map(|(v, p)| {
            if boundary.contains(&v) {
                return *p;
            }
            let (dx, dy) = (p[0] - 0.5, p[1] - 0.5);
            let a = 1.2 * (1.0 - 2.0 * dx.abs().max(dy.abs()));
            let (c, s) = (a.cos(), a.sin());
            [0.5 + 0.5 * (c * dx - s * dy), 0.5 + 0.5 * (s * dx + c * dy)]
        })
        .collect();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(
        Elastic::<_, Tri>::planar(Arc::new(SymmetricDirichlet), &rest, &tris).unwrap(),
    )];
    let params = NewtonParams {
        tol_abs: tol,
        linear_solver: LinearSolver::Cholesky,
        factor_reuse: reuse,
        ..Default::default()
    };
    let mut solver = NewtonSolver::new(rest.len(), terms, &boundary, params).unwrap();
    let r = solver.solve(&mut x).unwrap();
    let err = x
        .iter()
        .zip(&rest)
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0, f64::max);
    (r, err)
}

/// Reuse bounded by the iteration budget only (the cost bound of the
/// default would not reuse on a problem this small).
fn any_cost() -> FactorReuse {
    FactorReuse {
        max_work_fraction: f64::INFINITY,
        ..FactorReuse::STALE_CG
    }
}

fn reused_steps(r: &NewtonResult) -> usize {
    r.records.iter().filter(|s| s.reused_factor).count()
}

#[test]
fn the_stale_factor_saves_factorisations_and_finds_the_same_minimiser() {
    let (off, err_off) = squeezed(FactorReuse::OFF, 1e-8);
    let (on, err_on) = squeezed(any_cost(), 1e-8);
    println!(
        "off: {} iterations, {} factorisations; on: {} iterations, {} factorisations, {} reused",
        off.iterations,
        off.numeric_factorizations,
        on.iterations,
        on.numeric_factorizations,
        reused_steps(&on)
    );
    assert!(
        off.converged() && on.converged(),
        "{:?} {:?}",
        off.status,
        on.status
    );
    assert_eq!(reused_steps(&off), 0);
    assert!(off.numeric_factorizations >= off.iterations);
    assert!(reused_steps(&on) > 0, "some step reused the factor");
    assert!(
        on.numeric_factorizations < on.iterations,
        "{} factorisations for {} iterations",
        on.numeric_factorizations,
        on.iterations
    );
    // a reused step has no factorisation and its CG iterations are within the budget
    for s in on.records.iter().filter(|s| s.reused_factor) {
        assert_eq!(s.factorizations, 0);
        assert!(s.cg_iterations >= 1 && s.cg_iterations <= FactorReuse::STALE_CG.max_cg_iters);
    }
    // the same minimiser (the rest shape) to the same accuracy, with at most
    // a few more (inexact) Newton steps
    assert!(err_off < 1e-6 && err_on < 1e-6, "{err_off} {err_on}");
    assert!(
        on.iterations <= off.iterations + 3,
        "{} vs {}",
        on.iterations,
        off.iterations
    );
}

/// A budget the stale factor can never meet: every attempt falls back to a
/// factorisation of the same matrix, so the iterates are those without reuse.
#[test]
fn a_failed_reuse_attempt_refactorises() {
    let (off, _) = squeezed(FactorReuse::OFF, 1e-8);
    let hopeless = FactorReuse {
        max_cg_iters: ecc_fem::linear::reuse::MIN_BUDGET,
        rel_tol: f64::MIN_POSITIVE,
        max_work_fraction: f64::INFINITY,
    };
    let (forced, err) = squeezed(hopeless, 1e-8);
    assert!(forced.converged(), "{:?}", forced.status);
    assert!(err < 1e-6);
    assert_eq!(reused_steps(&forced), 0);
    assert_eq!(forced.iterations, off.iterations);
    assert_eq!(forced.numeric_factorizations, off.numeric_factorizations);
    // every step after the first tried (and gave up) the budget's CG iterations
    let budget = hopeless.max_cg_iters;
    assert!(
        forced.records[1..]
            .iter()
            .all(|s| s.cg_iterations >= 1 && s.cg_iterations <= budget)
    );
    assert!(forced.records[1..].iter().all(|s| s.factorizations >= 1));
    assert_eq!(forced.records[0].cg_iterations, 0);
}

/// On a system this small a factorisation costs less than a few triangular
/// solves, so the cost bound of the opt-in policy never spends CG
/// iterations on reuse; the default does not reuse at all.
#[test]
fn no_reuse_where_factorising_is_cheap_or_by_default() {
    let (off, _) = squeezed(FactorReuse::OFF, 1e-8);
    for policy in [FactorReuse::STALE_CG, FactorReuse::default()] {
        let (r, _) = squeezed(policy, 1e-8);
        assert_eq!(reused_steps(&r), 0);
        assert!(r.records.iter().all(|s| s.cg_iterations == 0));
        assert_eq!(r.iterations, off.iterations);
        assert_eq!(r.numeric_factorizations, off.numeric_factorizations);
    }
}
