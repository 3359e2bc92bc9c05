//! Projected Newton at scale (issue #5).
//!
//! 1. **Scaling curve**: time per Newton iteration and its split (assembly /
//!    factorisation / solve / line search) against element count, on
//!    generated meshes, for the direct (faer Cholesky) and the PCG path:
//!    * triangles: unit-square grids, symmetric Dirichlet (a barrier, so the
//!      inversion-free bound is computed every step), left edge fixed, right
//!      edge pulled to x = 1.5, started from the affine stretch;
//!    * tets: unit cubes, stable Neo-Hookean (μ = 1, λ = 10), face x = 0
//!      fixed, face x = 1 twisted by 30° about the x axis, started from the
//!      linearly interpolated twist.
//!
//!    Each run takes `ECC_BENCH_ITERS` Newton steps (tolerance 0, so none stops
//!    early) and reports the mean over steps.
//! 2. **Parameterisation**: SD of hand_1_i_f5000.obj, camelhead.off and
//!    armadillo_cut_low.obj (unit area, mean energy, Tutte start, ‖∇‖∞ ≤ 1e-4),
//!    with the paper's fixed clamp filter and the trust-region Newton policy:
//!    iterations, wall time and its split.
//!
//! Environment (all optional):
//! `ECC_BENCH_TRIS` (default `10000,30000,100000,300000,1000000`),
//! `ECC_BENCH_TETS` (default `10000,30000,100000,300000`),
//! `ECC_BENCH_DIRECT_MAX_TETS` (largest tet mesh also run with Cholesky,
//! default 110000: the 300k-tet factor needs ≈2.9 GB and ≈1.6e12 flops,
//! minutes per step on 2 cores), `ECC_BENCH_ITERS` (default 3), `ECC_BENCH_PARAM=0` to
//! skip part 2, `ECC_BENCH_SCALING=0` to skip part 1.
//! Rows are also printed as `csv,…` lines for machine reading.
//!
//! Run: `cargo bench -p ecc-benches --bench newton`.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::param::{ParamOptions, parameterize};
use ecc_fem::{
    Elastic, FilterPolicy, LinearSolver, NewtonParams, NewtonResult, NewtonSolver, Term, Tet, Tri,
};
use ecc_mesh::{box_tet_with_at_least, grid_tri_with_at_least, read_tri_mesh};
use ecc_runtime::energies::{StableNeoHookean, SymmetricDirichlet};

fn env_list(name: &str, default: &[usize]) -> Vec<usize> {
    match std::env::var(name) {
        Ok(s) => s.split(',').filter_map(|t| t.trim().parse().ok()).collect(),
        Err(_) => default.to_vec(),
    }
}

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn bench_params(kind: LinearSolver, iters: usize) -> NewtonParams {
    NewtonParams {
        tol_abs: 0.0,
        max_iters: iters,
        linear_solver: kind,
        ..Default::default()
    }
}

struct Row {
    mesh: String,
    elements: usize,
    unknowns: usize,
    solver: LinearSolver,
    setup: f64,
    factor_mb: f64,
    r: NewtonResult,
}

fn print_header() {
    println!(
        "{:<6} {:>9} {:>9} {:<8} {:>8} {:>9} {:>5} {:>10} {:>9} {:>9} {:>9} {:>9} {:>7} {:>11}",
        "mesh",
        "elements",
        "unknowns",
        "solver",
        "setup_s",
        "L_MB",
        "its",
        "s/iter",
        "assembly",
        "factor",
        "solve",
        "lsearch",
        "cg/it",
        "status"
    );
}

fn print_row(row: &Row) {
    let r = &row.r;
    let n = r.iterations.max(1) as f64;
    let t = &r.times;
    let per = (t.assembly + t.factor + t.solve + t.line_search) / n;
    let cg = r.records.iter().map(|x| x.cg_iterations).sum::<usize>() as f64 / n;
    let status = format!("{:?}", r.status)
        .chars()
        .take(11)
        .collect::<String>();
    println!(
        "{:<6} {:>9} {:>9} {:<8} {:>8.3} {:>9.1} {:>5} {:>10.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>7.0} {:>11}",
        row.mesh,
        row.elements,
        row.unknowns,
        format!("{:?}", row.solver),
        row.setup,
        row.factor_mb,
        r.iterations,
        per,
        t.assembly / n,
        t.factor / n,
        t.solve / n,
        t.line_search / n,
        cg,
        status
    );
    println!(
        "csv,scaling,{},{},{},{:?},{:.6},{:.3},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.1},{:?}",
        row.mesh,
        row.elements,
        row.unknowns,
        row.solver,
        row.setup,
        row.factor_mb,
        r.iterations,
        per,
        t.assembly / n,
        t.factor / n,
        t.solve / n,
        t.line_search / n,
        cg,
        r.status
    );
}

fn run_tri(target: usize, kind: LinearSolver, iters: usize) -> Option<Row> {
    let mesh = grid_tri_with_at_least(target);
    let rest: Vec<[f64; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
    let t0 = Instant::now();
    let elastic =
        Elastic::<_, Tri>::planar(Arc::new(SymmetricDirichlet), &rest, &mesh.triangles).ok()?;
    let fixed: Vec<usize> = (0..rest.len())
        .filter(|&v| rest[v][0] < 1e-12 || rest[v][0] > 1.0 - 1e-12)
        .collect();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(elastic)];
    let mut solver = match NewtonSolver::new(rest.len(), terms, &fixed, bench_params(kind, iters)) {
        Ok(s) => s,
        Err(e) => {
            println!("tri {target}: {e}");
            return None;
        }
    };
    let setup = t0.elapsed().as_secs_f64();
    let mut x: Vec<[f64; 2]> = rest.iter().map(|p| [1.5 * p[0], p[1]]).collect();
    let r = solver.solve(&mut x).ok()?;
    let factor_mb = solver
        .linear_system()
        .factor_bytes()
        .map_or(0.0, |b| b as f64 / 1e6);
    Some(Row {
        mesh: "tri".into(),
        elements: mesh.triangles.len(),
        unknowns: r.unknowns,
        solver: solver.linear_solver(),
        setup,
        factor_mb,
        r,
    })
}

fn run_tet(target: usize, kind: LinearSolver, iters: usize) -> Option<Row> {
    let mesh = box_tet_with_at_least(target);
    let t0 = Instant::now();
    let elastic = Elastic::<_, Tet>::new(
        Arc::new(StableNeoHookean::new(1.0, 10.0)),
        &mesh.positions,
        &mesh.tets,
    )
    .ok()?;
    let p = &mesh.positions;
    let fixed: Vec<usize> = (0..p.len())
        .filter(|&v| p[v][0] < 1e-12 || p[v][0] > 1.0 - 1e-12)
        .collect();
    let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
    let mut solver = match NewtonSolver::new(p.len(), terms, &fixed, bench_params(kind, iters)) {
        Ok(s) => s,
        Err(e) => {
            println!("tet {target}: {e}");
            return None;
        }
    };
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
    let r = solver.solve(&mut x).ok()?;
    let factor_mb = solver
        .linear_system()
        .factor_bytes()
        .map_or(0.0, |b| b as f64 / 1e6);
    Some(Row {
        mesh: "tet".into(),
        elements: mesh.tets.len(),
        unknowns: r.unknowns,
        solver: solver.linear_solver(),
        setup,
        factor_mb,
        r,
    })
}

fn scaling(iters: usize) {
    let tris = env_list(
        "ECC_BENCH_TRIS",
        &[10_000, 30_000, 100_000, 300_000, 1_000_000],
    );
    let tets = env_list("ECC_BENCH_TETS", &[10_000, 30_000, 100_000, 300_000]);
    let direct_max_tets = env_usize("ECC_BENCH_DIRECT_MAX_TETS", 110_000);
    println!("\n== scaling: time per Newton iteration (mean of {iters} steps), seconds ==");
    print_header();
    for &t in &tris {
        for kind in [LinearSolver::Cholesky, LinearSolver::Pcg] {
            if let Some(row) = run_tri(t, kind, iters) {
                print_row(&row);
            }
        }
    }
    for &t in &tets {
        for kind in [LinearSolver::Cholesky, LinearSolver::Pcg] {
            if kind == LinearSolver::Cholesky && t > direct_max_tets {
                continue;
            }
            if let Some(row) = run_tet(t, kind, iters) {
                print_row(&row);
            }
        }
    }
}

fn param() {
    let data = ecc_mesh::data_dir();
    println!(
        "\n== SD parameterisation (unit area, mean energy, Tutte start, |grad|inf <= 1e-4, Cholesky) =="
    );
    println!(
        "{:<22} {:>7} {:<18} {:>5} {:>9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>7} {:<10}",
        "mesh",
        "tris",
        "policy",
        "its",
        "E_start",
        "E_final",
        "|g|inf",
        "wall_s",
        "assembly",
        "factor",
        "solve",
        "lsearch",
        "flipped",
        "status"
    );
    for name in [
        "hand_1_i_f5000.obj",
        "camelhead.off",
        "armadillo_cut_low.obj",
    ] {
        let mesh = match read_tri_mesh(data.join(name)) {
            Ok(m) => m,
            Err(e) => {
                println!("{name}: {e}");
                continue;
            }
        };
        for policy in [
            FilterPolicy::Fixed,
            FilterPolicy::TrustRegion,
            FilterPolicy::TrustRegionNewton,
        ] {
            let mut opts = ParamOptions::default();
            opts.newton.filter_policy = policy;
            opts.newton.linear_solver = LinearSolver::Cholesky;
            opts.newton.max_iters = 2000;
            let t0 = Instant::now();
            let p = match parameterize(&mesh, Arc::new(SymmetricDirichlet), &opts) {
                Ok(p) => p,
                Err(e) => {
                    println!("{name}: {e}");
                    continue;
                }
            };
            let wall = t0.elapsed().as_secs_f64();
            let t = &p.result.times;
            let status = format!("{:?}", p.result.status);
            println!(
                "{:<22} {:>7} {:<18} {:>5} {:>9.4} {:>9.6} {:>8.1e} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>7} {:<10}",
                name,
                mesh.triangles.len(),
                format!("{policy:?}"),
                p.result.iterations,
                p.result.initial_energy,
                p.result.energy,
                p.result.grad_inf,
                wall,
                t.assembly,
                t.factor,
                t.solve,
                t.line_search,
                p.flipped,
                status
            );
            println!(
                "csv,param,{name},{},{policy:?},{},{:.6e},{:.9},{:.3e},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{},{status}",
                mesh.triangles.len(),
                p.result.iterations,
                p.result.initial_energy,
                p.result.energy,
                p.result.grad_inf,
                wall,
                p.tutte_seconds,
                p.setup_seconds,
                t.assembly,
                t.factor,
                t.solve,
                t.line_search,
                p.flipped
            );
        }
    }
}

fn main() {
    let iters = env_usize("ECC_BENCH_ITERS", 3).max(1);
    println!("rayon threads: {}", rayon_threads());
    if env_usize("ECC_BENCH_SCALING", 1) != 0 {
        scaling(iters);
    }
    if env_usize("ECC_BENCH_PARAM", 1) != 0 {
        param();
    }
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
