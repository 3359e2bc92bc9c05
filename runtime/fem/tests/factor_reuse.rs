//! Fewer factorisations: reusing a stale Cholesky factor as the
//! preconditioner of CG (`linear::reuse`): fewer factorisations than Newton
//! steps where the Hessian changes slowly, the same minimiser, and a
//! factorisation whenever the stale factor is not good enough; the PCG
//! preconditioners (`linear::precond`) and `Auto`'s PCG attempts under a
//! work budget (`linear::adaptive`).

mod common;

use std::sync::Arc;

use common::grid;
use ecc_fem::linear::{AutoLimits, FactorReuse, Preconditioner};
use ecc_fem::{Elastic, LinearSolver, NewtonParams, NewtonResult, NewtonSolver, Term, Tri};
use ecc_runtime::energies::SymmetricDirichlet;

/// Symmetric Dirichlet on a 16×16 grid, boundary at rest, interior squeezed
/// and swirled (the barrier test's start): ~10–20 Newton steps whose last
/// ones barely change the Hessian. Returns the result and the distance of
/// the answer from the rest shape (the exact minimiser).
fn squeezed(reuse: FactorReuse, tol: f64) -> (NewtonResult, f64) {
    let params = NewtonParams {
        tol_abs: tol,
        linear_solver: LinearSolver::Cholesky,
        factor_reuse: reuse,
        ..Default::default()
    };
    let (r, err, _) = squeezed_with(params);
    (r, err)
}

/// [`squeezed`] with any Newton parameters; also returns the answer.
fn squeezed_with(params: NewtonParams) -> (NewtonResult, f64, Vec<[f64; 2]>) {
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
    let mut solver = NewtonSolver::new(rest.len(), terms, &boundary, params).unwrap();
    let r = solver.solve(&mut x).unwrap();
    let err = x
        .iter()
        .zip(&rest)
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0, f64::max);
    (r, err, x)
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

/// `max_age` = 1 (the default's limit): a factor serves at most the step
/// after the one that made it, so reused steps never follow each other and
/// each follows a factorisation; without the limit this problem reuses one
/// factor for consecutive steps, so the limit is what the test sees.
#[test]
fn one_stale_step_per_factor() {
    let consecutive = |r: &NewtonResult| {
        r.records
            .windows(2)
            .any(|w| w[0].reused_factor && w[1].reused_factor)
    };
    let (unlimited, _) = squeezed(any_cost(), 1e-8);
    assert!(
        consecutive(&unlimited),
        "the unlimited policy reuses twice in a row"
    );
    let once = FactorReuse {
        max_age: 1,
        ..any_cost()
    };
    let (r, err) = squeezed(once, 1e-8);
    assert!(r.converged(), "{:?}", r.status);
    assert!(err < 1e-6, "{err}");
    assert!(reused_steps(&r) > 0);
    assert!(r.numeric_factorizations < r.iterations);
    assert!(!consecutive(&r));
    for w in r.records.windows(2).filter(|w| w[1].reused_factor) {
        assert!(
            w[0].factorizations >= 1,
            "a reused step follows a factorisation"
        );
    }
    assert!(!r.records[0].reused_factor);
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
        max_age: usize::MAX,
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

/// `linear = "pcg"` with a solver's preconditioner, to 1e-8.
fn pcg_with(preconditioner: Preconditioner) -> NewtonResult {
    let params = NewtonParams {
        tol_abs: 1e-8,
        linear_solver: LinearSolver::Pcg,
        auto_limits: AutoLimits {
            preconditioner,
            ..AutoLimits::default()
        },
        ..Default::default()
    };
    let (r, err, _) = squeezed_with(params);
    assert!(
        r.converged() && err < 1e-6,
        "{preconditioner:?}: {:?}, {err}",
        r.status
    );
    r
}

fn cg_total(r: &NewtonResult) -> usize {
    r.records.iter().map(|s| s.cg_iterations).sum()
}

/// On the SD Hessians of the squeezed grid IC(0) needs less than half the
/// CG iterations of Jacobi and of block-Jacobi for the same minimiser
/// (block-Jacobi is not better than Jacobi on every mesh: 296 vs 259 here).
#[test]
fn ic0_needs_fewer_cg_iterations_than_jacobi_and_block_jacobi() {
    let jacobi = cg_total(&pcg_with(Preconditioner::Jacobi));
    let block = cg_total(&pcg_with(Preconditioner::BlockJacobi));
    let ic0 = cg_total(&pcg_with(Preconditioner::Ic0));
    println!("CG iterations: Jacobi {jacobi}, block-Jacobi {block}, IC(0) {ic0}");
    assert!(
        2 * ic0 < jacobi && 2 * ic0 < block,
        "{ic0} vs {jacobi}, {block}"
    );
    assert_eq!(Preconditioner::default(), Preconditioner::Ic0);
}

/// `Auto` with the adaptive backend forced (ρ = ∞) and the limits `limits`.
fn auto_with(limits: AutoLimits) -> (NewtonResult, Vec<[f64; 2]>) {
    auto_capped(limits, NewtonParams::default().pcg_max_iters)
}

/// [`auto_with`] with at most `max_cg` CG iterations per step.
fn auto_capped(limits: AutoLimits, max_cg: usize) -> (NewtonResult, Vec<[f64; 2]>) {
    let params = NewtonParams {
        tol_abs: 1e-8,
        linear_solver: LinearSolver::Auto,
        auto_limits: AutoLimits {
            pcg_trial_ratio: f64::INFINITY,
            ..limits
        },
        pcg_max_iters: max_cg,
        ..Default::default()
    };
    let (r, err, x) = squeezed_with(params);
    assert!(
        r.converged() && err < 1e-6,
        "{limits:?}: {:?}, {err}",
        r.status
    );
    (r, x)
}

/// A factorisation worth ∞ CG iterations (κ → 0) and no residual cap: every
/// PCG attempt is accepted, nothing is factorised, and the iterates are
/// exactly those of `linear = "pcg"` (same preconditioner, tolerance, start).
#[test]
fn auto_whose_pcg_attempts_all_succeed_is_pcg() {
    let (auto, x_auto) = auto_with(AutoLimits {
        factor_speedup: 1e-12,
        pcg_rel_tol: 1.0,
        ..AutoLimits::default()
    });
    let params = NewtonParams {
        tol_abs: 1e-8,
        linear_solver: LinearSolver::Pcg,
        ..Default::default()
    };
    let (pcg, _, x_pcg) = squeezed_with(params);
    assert_eq!(auto.numeric_factorizations, 0);
    assert_eq!(auto.symbolic_analyses, 1);
    assert_eq!(auto.linear_solver, LinearSolver::Pcg);
    assert_eq!(auto.iterations, pcg.iterations);
    assert_eq!(cg_total(&auto), cg_total(&pcg));
    assert_eq!(x_auto, x_pcg);
}

/// A residual cap no CG run can meet: every attempt that is made fails
/// (by its budget or the give-up rule; at most 60 iterations, so CG's
/// recursive residual cannot underflow to 0 as it can after hundreds of
/// iterations on this 450-unknown system), each failure is followed by one
/// factorisation of that step and a wait of 2^m steps, so there are at most ⌊log₂(N+1)⌋ failed attempts
/// (bound (2) of `linear::adaptive`), every step factorises once (no shift
/// retries on this SPD problem), and the iterates are Cholesky's.
#[test]
fn auto_whose_pcg_attempts_fail_falls_back_with_bounded_waste() {
    let (off, _) = squeezed(FactorReuse::OFF, 1e-8);
    let (auto, _) = auto_capped(
        AutoLimits {
            factor_speedup: 1e-3,
            pcg_rel_tol: 1e-300,
            ..AutoLimits::default()
        },
        60,
    );
    let n = auto.iterations;
    assert_eq!(n, off.iterations);
    assert_eq!(auto.numeric_factorizations, n);
    assert!(auto.records.iter().all(|s| s.factorizations == 1));
    assert_eq!(auto.linear_solver, LinearSolver::Cholesky);
    let attempts = auto.records.iter().filter(|s| s.cg_iterations > 0).count();
    assert!(attempts >= 1, "the first step tries PCG");
    assert!(
        attempts <= (n + 1).ilog2() as usize,
        "{attempts} failed attempts in {n} steps"
    );
    assert_eq!(auto.records[0].cg_iterations.min(1), 1);
}
