//! Line-search extrapolation (`NewtonParams::extrapolate`, on by default
//! for parameterisations): after an accepted full step with no
//! inversion-free bound the solver tries once the minimiser of the
//! parabola through E(0), ∇Eᵀd and E(1). On a curved disk's symmetric
//! Dirichlet parameterisation the projected Newton step is short, so it
//! takes longer steps, needs fewer iterations and reaches the same
//! minimiser; a step is never extrapolated towards a barrier.

use std::sync::Arc;

use ecc_fem::param::{ParamOptions, Parameterization, parameterize};
use ecc_runtime::energies::SymmetricDirichlet;

/// A bumpy disk (not developable: the SD minimiser is not an isometry and
/// the uniform Tutte start compresses the bumps' triangles).
fn solve(extrapolate: bool) -> Parameterization {
    let mut mesh = ecc_mesh::disk_tri(16, 1.0);
    for p in &mut mesh.positions {
        let (x, y) = (p[0], p[1]);
        p[2] = 0.25 * (6.0 * x).sin() * (5.0 * y).cos() + 0.5 * (x * x - 0.5 * y * y);
    }
    let mut opts = ParamOptions::default();
    assert!(
        opts.newton.extrapolate,
        "on by default for parameterisations"
    );
    opts.newton.extrapolate = extrapolate;
    opts.newton.tol_abs = 1e-8;
    let p = parameterize(&mesh, Arc::new(SymmetricDirichlet), &opts).unwrap();
    assert!(p.result.converged(), "{:?}", p.result.status);
    assert_eq!(p.flipped, 0, "flipped triangles");
    p
}

#[test]
fn extrapolation_takes_longer_steps_and_fewer_iterations_to_the_same_minimiser() {
    let (on, off) = (solve(true), solve(false));
    let longer = on.result.records.iter().filter(|r| r.step > 1.0).count();
    assert!(longer > 0, "no extrapolated step");
    assert!(off.result.records.iter().all(|r| r.step <= 1.0));
    for r in &on.result.records {
        assert!(r.step <= 2.0, "step {} beyond the cap", r.step);
        if r.max_step.is_some() {
            assert!(r.step <= 1.0, "extrapolated towards a barrier: {r:?}");
        }
    }
    assert!(
        on.result.iterations < off.result.iterations,
        "{} iterations with extrapolation, {} without",
        on.result.iterations,
        off.result.iterations
    );
    let (a, b) = (on.result.energy, off.result.energy);
    assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
}

#[test]
fn deformation_solves_keep_the_plain_line_search() {
    assert!(!ecc_fem::NewtonParams::default().extrapolate);
}
