//! The parameterisation default filter policy is trust-region Newton
//! (`ParamOptions::default`): its raw-Hessian steps are safe with every
//! linear solver — Cholesky with the growing shift search, PCG (truncated
//! at non-positive curvature, which still gives a descent direction) and
//! `Auto`'s PCG attempts (falling back to a shifted factorisation) — and
//! reach the fixed clamp's minimiser.

use std::sync::Arc;

use ecc_fem::param::{ParamOptions, Parameterization, parameterize};
use ecc_fem::{FilterPolicy, LinearSolver};
use ecc_runtime::energies::SymmetricDirichlet;

/// A curved disk (not developable: the SD minimiser is not an isometry).
fn solve(linear: LinearSolver, policy: Option<FilterPolicy>) -> Parameterization {
    let mut mesh = ecc_mesh::disk_tri(8, 1.0);
    for p in &mut mesh.positions {
        p[2] = 0.6 * (p[0] * p[0] - 0.5 * p[1] * p[1]) + 0.3 * p[0] * p[1];
    }
    let mut opts = ParamOptions::default();
    opts.newton.linear_solver = linear;
    opts.newton.tol_abs = 1e-8;
    if let Some(policy) = policy {
        opts.newton.filter_policy = policy;
    }
    let p = parameterize(&mesh, Arc::new(SymmetricDirichlet), &opts).unwrap();
    assert!(p.result.converged(), "{linear:?}: {:?}", p.result.status);
    assert!(p.result.grad_inf <= 1e-8, "{linear:?}");
    assert_eq!(p.flipped, 0, "{linear:?}: flipped triangles");
    p
}

#[test]
fn the_default_policy_is_trust_region_newton() {
    let opts = ParamOptions::default();
    assert_eq!(opts.newton.filter_policy, FilterPolicy::TrustRegionNewton);
    // the untrusted filter stays the library default (clamp)
    assert_eq!(opts.newton.filter, ecc_fem::Filter::Clamp);
}

#[test]
fn raw_newton_steps_are_safe_with_every_linear_solver() {
    let fixed = solve(LinearSolver::Cholesky, Some(FilterPolicy::Fixed));
    for linear in [
        LinearSolver::Cholesky,
        LinearSolver::Pcg,
        LinearSolver::Auto,
    ] {
        let p = solve(linear, None);
        assert!(
            p.result.records.iter().any(|r| r.filter == "None"),
            "{linear:?}: raw Newton steps were used"
        );
        let (e, e0) = (p.result.energy, fixed.result.energy);
        assert!((e - e0).abs() <= 1e-9 * e0, "{linear:?}: {e} vs fixed {e0}");
        assert!(
            p.result.iterations <= fixed.result.iterations,
            "{linear:?}: {} Newton steps, fixed clamp {}",
            p.result.iterations,
            fixed.result.iterations
        );
    }
}

/// With the default (trust-region Newton) policy, the default projection
/// `Auto` is the F-space projection on triangles (`Projection::resolve_for`):
/// the same iterates, bit for bit, as an explicit `FSpace`, and not those of
/// the exact element projection; under the fixed policy `Auto` stays the
/// element projection.
#[test]
fn the_default_parameterisation_projects_in_f_space() {
    use ecc_fem::elastic::Projection;
    let run = |projection: Projection, policy: FilterPolicy| {
        let mut mesh = ecc_mesh::disk_tri(8, 1.0);
        for p in &mut mesh.positions {
            p[2] = 0.6 * (p[0] * p[0] - 0.5 * p[1] * p[1]) + 0.3 * p[0] * p[1];
        }
        let mut opts = ParamOptions {
            projection,
            ..Default::default()
        };
        opts.newton.filter_policy = policy;
        opts.newton.tol_abs = 1e-8;
        let p = parameterize(&mesh, Arc::new(SymmetricDirichlet), &opts).unwrap();
        assert!(p.result.converged(), "{projection:?}, {policy:?}");
        let uv: Vec<u64> = p.uv.iter().flatten().map(|c| c.to_bits()).collect();
        (p.result.iterations, uv)
    };
    let trn = FilterPolicy::TrustRegionNewton;
    assert_eq!(ParamOptions::default().projection, Projection::Auto);
    let auto = run(Projection::Auto, trn);
    assert_eq!(auto, run(Projection::FSpace, trn));
    assert_ne!(auto, run(Projection::Element, trn));
    let fixed = FilterPolicy::Fixed;
    assert_eq!(
        run(Projection::Auto, fixed),
        run(Projection::Element, fixed)
    );
}
