//! Part 3 of the report: time per Newton iteration against element count,
//! direct (faer sparse Cholesky) vs iterative (Jacobi PCG).
//!
//! * triangles: unit-square grids (`grid_tri_with_at_least`), symmetric
//!   Dirichlet, left and right edges fixed, right edge pulled to x = 1.5,
//!   started from the affine stretch (a barrier energy: the inversion-free
//!   step bound is computed every iteration);
//! * tets: unit cubes (`box_tet_with_at_least`), stable Neo-Hookean (μ = 1,
//!   λ = 10), faces x = 0 and x = 1 fixed, x = 1 twisted by 30° about the x
//!   axis, started from the linearly interpolated twist.
//!
//! Each run takes a fixed number of projected Newton steps (tolerance 0, so
//! none stops early; the analytic clamp) and reports the mean time per step
//! and its split. Setup (pattern, colouring, symbolic analysis) is reported
//! separately.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::{Elastic, LinearSolver, NewtonParams, NewtonSolver, Term, Tet, Tri};
use ecc_mesh::{box_tet_with_at_least, grid_tri_with_at_least};
use serde::Serialize;

/// One (mesh, size, solver) measurement.
#[derive(Clone, Debug, Serialize)]
pub struct ScalingRow {
    pub mesh: String,
    pub elements: usize,
    pub unknowns: usize,
    pub solver: String,
    pub setup_s: f64,
    pub iterations: usize,
    pub per_iter_s: f64,
    pub assembly_s: f64,
    pub factor_s: f64,
    pub solve_s: f64,
    pub line_search_s: f64,
    pub cg_per_iter: f64,
    pub factor_mb: f64,
    pub status: String,
}

fn params(kind: LinearSolver, iters: usize) -> NewtonParams {
    let mut p = NewtonParams {
        tol_abs: 0.0,
        max_iters: iters,
        linear_solver: kind,
        ..Default::default()
    };
    p.auto_limits.max_factor_bytes = usize::MAX;
    p.auto_limits.max_factor_flops = f64::INFINITY;
    p
}

fn row<const D: usize>(
    mesh: &str,
    elements: usize,
    mut solver: NewtonSolver<D>,
    setup: f64,
    x: &mut [[f64; D]],
) -> Option<ScalingRow> {
    let r = solver.solve(x).ok()?;
    let n = r.iterations.max(1) as f64;
    let t = &r.times;
    Some(ScalingRow {
        mesh: mesh.into(),
        elements,
        unknowns: r.unknowns,
        solver: format!("{:?}", solver.linear_solver()),
        setup_s: setup,
        iterations: r.iterations,
        per_iter_s: (t.assembly + t.factor + t.solve + t.line_search) / n,
        assembly_s: t.assembly / n,
        factor_s: t.factor / n,
        solve_s: t.solve / n,
        line_search_s: t.line_search / n,
        cg_per_iter: r.records.iter().map(|x| x.cg_iterations).sum::<usize>() as f64 / n,
        factor_mb: solver
            .linear_system()
            .factor_bytes()
            .map_or(0.0, |b| b as f64 / 1e6),
        status: format!("{:?}", r.status)
            .split(['(', ' ', '{'])
            .next()
            .unwrap_or("")
            .to_string(),
    })
}

/// Triangle grid with at least `target` triangles.
pub fn tri(target: usize, kind: LinearSolver, iters: usize) -> Option<ScalingRow> {
    let mesh = grid_tri_with_at_least(target);
    let rest: Vec<[f64; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
    let t0 = Instant::now();
    let e = Arc::new(ecc_energies::SymmetricDirichlet2::new());
    let elastic = Elastic::<_, Tri>::planar(e, &rest, &mesh.triangles).ok()?;
    let fixed: Vec<usize> = (0..rest.len())
        .filter(|&v| rest[v][0] < 1e-12 || rest[v][0] > 1.0 - 1e-12)
        .collect();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(elastic)];
    let solver = NewtonSolver::new(rest.len(), terms, &fixed, params(kind, iters)).ok()?;
    let setup = t0.elapsed().as_secs_f64();
    let mut x: Vec<[f64; 2]> = rest.iter().map(|p| [1.5 * p[0], p[1]]).collect();
    row("tri (SD)", mesh.triangles.len(), solver, setup, &mut x)
}

/// Tet box with at least `target` tets.
pub fn tet(target: usize, kind: LinearSolver, iters: usize) -> Option<ScalingRow> {
    let mesh = box_tet_with_at_least(target);
    let t0 = Instant::now();
    let e = Arc::new(ecc_energies::StableNeoHookean::new());
    let elastic = Elastic::<_, Tet>::new(e, &mesh.positions, &mesh.tets).ok()?;
    let p = &mesh.positions;
    let fixed: Vec<usize> = (0..p.len())
        .filter(|&v| p[v][0] < 1e-12 || p[v][0] > 1.0 - 1e-12)
        .collect();
    let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
    let solver = NewtonSolver::new(p.len(), terms, &fixed, params(kind, iters)).ok()?;
    let setup = t0.elapsed().as_secs_f64();
    let twist = 30f64.to_radians();
    let mut x: Vec<[f64; 3]> = p
        .iter()
        .map(|q| {
            let a = twist * q[0];
            let (y, z) = (q[1] - 0.5, q[2] - 0.5);
            [
                q[0],
                0.5 + a.cos() * y - a.sin() * z,
                0.5 + a.sin() * y + a.cos() * z,
            ]
        })
        .collect();
    row("tet (SNH)", mesh.tets.len(), solver, setup, &mut x)
}

/// Sizes and solvers to run.
#[derive(Clone, Debug)]
pub struct ScalingPlan {
    pub tris: Vec<usize>,
    pub tets: Vec<usize>,
    /// Largest tet count also run with Cholesky.
    pub direct_max_tets: usize,
    pub iters: usize,
}

/// Run the plan; `progress` is called with each finished row.
pub fn run(plan: &ScalingPlan, mut progress: impl FnMut(&ScalingRow)) -> Vec<ScalingRow> {
    let mut rows = Vec::new();
    for &t in &plan.tris {
        for kind in [LinearSolver::Cholesky, LinearSolver::Pcg] {
            if let Some(r) = tri(t, kind, plan.iters) {
                progress(&r);
                rows.push(r);
            }
        }
    }
    for &t in &plan.tets {
        for kind in [LinearSolver::Cholesky, LinearSolver::Pcg] {
            if kind == LinearSolver::Cholesky && t > plan.direct_max_tets {
                continue;
            }
            if let Some(r) = tet(t, kind, plan.iters) {
                progress(&r);
                rows.push(r);
            }
        }
    }
    rows
}
