//! Factor reuse (issue #11 items 3–4, docs/benchmarks/reuse.md): SD
//! parameterisation to ‖∇Ē‖∞ ≤ 1e-4 (uniform Tutte start, clamp filter)
//! with one linear-solver setting, printing one JSON line: Newton
//! iterations, numeric factorisations, reused steps, CG iterations, times.
//!
//! `cargo run --release -p ecc-fem --example reuse -- MESH|disk:RINGS SOLVER [REUSE]`
//!
//! SOLVER: `cholesky`, `pcg` or `auto`, optionally `:jacobi`,
//! `:block_jacobi` or `:ic0` (the PCG preconditioner, default IC(0)) and
//! for `auto` `:CAP` (`AutoLimits::pcg_rel_tol`); REUSE: `off` or `ITERS:TOL[:THETA[:AGE]]`
//! (the `FactorReuse` budget, residual cap, work fraction and `max_age`,
//! no age limit when omitted; without REUSE: `FactorReuse::default()`).
//! `disk:RINGS` is the generated bumpy disk of `ecc-mesh`'s `setup_timing`
//! example (6·RINGS² triangles; 409 rings ≈ 1M). `tet:FILE:arap|snh` is a
//! 3D handle problem instead: the lowest 15 % (in y) of the tet mesh fixed,
//! the highest 30 % turned by −50° about the x axis, ARAP or SNH (μ = 1,
//! λ = 10), objective divided by the rest volume, one solve to 1e-4.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::linear::{FactorReuse, LinearSystem, Preconditioner};
use ecc_fem::param::{ParamOptions, prepare};
use ecc_fem::{Elastic, LinearSolver, NewtonResult, NewtonSolver, Pattern, Term, Tet};
use ecc_mesh::{TriMesh, disk_tri, read_tet_mesh, read_tri_mesh};
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};

fn mesh(spec: &str) -> Result<TriMesh, String> {
    if let Some(rings) = spec.strip_prefix("disk:") {
        let rings: usize = rings.parse().map_err(|e| format!("{spec}: {e}"))?;
        let mut m = disk_tri(rings, 1.0);
        let k = 8.0 * std::f64::consts::PI;
        for p in &mut m.positions {
            p[2] = 0.05 * (k * p[0]).sin() * (k * p[1]).sin();
        }
        return Ok(m);
    }
    read_tri_mesh(spec).map_err(|e| e.to_string())
}

fn reuse(spec: &str) -> Result<FactorReuse, String> {
    if spec == "off" {
        return Ok(FactorReuse::OFF);
    }
    let bad = || format!("bad reuse `{spec}` (off or ITERS:TOL[:THETA[:AGE]])");
    let parts: Vec<&str> = spec.split(':').collect();
    let num = |i: usize| parts.get(i).map(|p| p.parse::<f64>().map_err(|_| bad()));
    let default = FactorReuse::default();
    Ok(FactorReuse {
        max_cg_iters: num(0).ok_or_else(bad)?? as usize,
        rel_tol: num(1).ok_or_else(bad)??,
        max_work_fraction: num(2).unwrap_or(Ok(default.max_work_fraction))?,
        max_age: num(3).map_or(Ok(usize::MAX), |a| a.map(|a| a as usize))?,
    })
}

fn tet_problem(
    spec: &str,
    opts: &ParamOptions,
) -> Result<(usize, NewtonSolver<3>, Vec<[f64; 3]>), String> {
    let (file, energy) = spec.rsplit_once(':').ok_or("tet:FILE:arap|snh")?;
    let mesh = read_tet_mesh(file).map_err(|e| e.to_string())?;
    let p = &mesh.positions;
    let (lo, hi) = p
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), q| (l.min(q[1]), h.max(q[1])));
    let fixed: Vec<usize> = (0..p.len())
        .filter(|&v| p[v][1] < lo + 0.15 * (hi - lo) || p[v][1] > hi - 0.3 * (hi - lo))
        .collect();
    let (c, s) = ((-50f64).to_radians().cos(), (-50f64).to_radians().sin());
    let top = hi - 0.3 * (hi - lo);
    let x: Vec<[f64; 3]> = p
        .iter()
        .map(|q| {
            if q[1] <= top {
                return *q;
            }
            let (y, z) = (q[1] - top, q[2]);
            [q[0], top + c * y - s * z, s * y + c * z]
        })
        .collect();
    let volume: f64 = mesh
        .tets
        .iter()
        .map(|t| {
            let e = |i: usize| std::array::from_fn::<f64, 3, _>(|k| p[t[i]][k] - p[t[0]][k]);
            let (a, b, d) = (e(1), e(2), e(3));
            (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                + a[2] * (b[0] * d[1] - b[1] * d[0]))
                .abs()
                / 6.0
        })
        .sum();
    let term: Box<dyn Term<3>> = match energy {
        "arap" => Box::new(
            Elastic::<_, Tet>::new(Arc::new(Arap), p, &mesh.tets).map_err(|e| e.to_string())?,
        ),
        "snh" => Box::new(
            Elastic::<_, Tet>::new(Arc::new(StableNeoHookean::new(1.0, 10.0)), p, &mesh.tets)
                .map_err(|e| e.to_string())?,
        ),
        e => return Err(format!("unknown energy `{e}`")),
    };
    let mut params = opts.newton.clone();
    params.energy_scale = 1.0 / volume;
    let solver =
        NewtonSolver::new(p.len(), vec![term], &fixed, params).map_err(|e| e.to_string())?;
    Ok((mesh.tets.len(), solver, x))
}

fn run(args: &[String]) -> Result<String, String> {
    let [m, solver, rest @ ..] = args else {
        return Err(
            "usage: reuse MESH|disk:RINGS cholesky|pcg|auto [off|ITERS:TOL[:THETA[:AGE]]]".into(),
        );
    };
    let mut opts = ParamOptions::default();
    // the fixed clamp of docs/benchmarks/reuse.md's runs (trust-region
    // Newton, the parameterisation default, never reuses on raw steps)
    opts.newton.filter_policy = ecc_fem::FilterPolicy::Fixed;
    let mut parts = solver.split(':');
    let solver = parts.next().unwrap_or_default();
    let precond = parts.next().unwrap_or("ic0");
    if let Some(cap) = parts.next() {
        let cap = cap
            .parse()
            .map_err(|_| format!("bad residual cap `{cap}`"))?;
        opts.newton.auto_limits.pcg_rel_tol = cap;
    }
    opts.newton.auto_limits.preconditioner = match precond {
        "jacobi" => Preconditioner::Jacobi,
        "block_jacobi" => Preconditioner::BlockJacobi,
        "ic0" => Preconditioner::Ic0,
        s => return Err(format!("unknown preconditioner `{s}`")),
    };
    opts.newton.linear_solver = match solver {
        "cholesky" => LinearSolver::Cholesky,
        "pcg" => LinearSolver::Pcg,
        "auto" => LinearSolver::Auto,
        s => return Err(format!("unknown solver `{s}`")),
    };
    if let Some(r) = rest.first() {
        opts.newton.factor_reuse = reuse(r)?;
    }
    if let Some(spec) = m.strip_prefix("tet:") {
        let (tets, mut solver, mut x) = tet_problem(spec, &opts)?;
        let t0 = Instant::now();
        let r = solver.solve(&mut x).map_err(|e| e.to_string())?;
        let wall = t0.elapsed().as_secs_f64();
        return Ok(line(
            m,
            tets,
            solver.linear_system(),
            solver.pattern(),
            &r,
            solver_name(args),
            wall,
            0.0,
        ));
    }
    let mesh = mesh(m)?;
    let t0 = Instant::now();
    let mut problem =
        prepare(&mesh, Arc::new(SymmetricDirichlet), &opts).map_err(|e| e.to_string())?;
    let p = problem
        .solve_with(|_, _| std::ops::ControlFlow::Continue(()))
        .map_err(|e| e.to_string())?;
    let wall = t0.elapsed().as_secs_f64();
    let sys = problem.solver.linear_system();
    let pattern = problem.solver.pattern();
    Ok(line(
        m,
        mesh.triangles.len(),
        sys,
        pattern,
        &p.result,
        solver_name(args),
        wall,
        p.setup_seconds,
    ))
}

fn solver_name(args: &[String]) -> String {
    format!(
        "{} {}",
        args[1],
        args.get(2).map_or("default", |s| s.as_str())
    )
}

#[allow(clippy::too_many_arguments)]
fn line(
    m: &str,
    elements: usize,
    sys: &LinearSystem,
    pattern: &Pattern,
    r: &NewtonResult,
    solver: String,
    wall: f64,
    setup: f64,
) -> String {
    let reused = r.records.iter().filter(|s| s.reused_factor).count();
    let cg: usize = r.records.iter().map(|s| s.cg_iterations).sum();
    let t = &r.times;
    let ad = sys.adaptive();
    let adaptive = format!(
        "\"budget\":{},\"pcg_steps\":{},\"failed_attempts\":{},\"symbolic\":{}",
        ad.map_or(0, |a| a.budget()),
        ad.map_or(0, |a| a.pcg_steps()),
        ad.map_or(0, |a| a.failed_attempts()),
        r.symbolic_analyses,
    );
    format!(
        "{{\"mesh\":\"{m}\",\"elements\":{elements},\"solver\":\"{solver}\",\"used\":\"{:?}\",\"status\":\"{:?}\",\"iterations\":{},\"factorizations\":{},\"reused_steps\":{reused},\"cg_iterations\":{cg},\"newton_s\":{:.3},\"assembly_s\":{:.3},\"factor_s\":{:.3},\"solve_s\":{:.3},\"line_search_s\":{:.3},\"setup_s\":{setup:.3},\"wall_s\":{wall:.3},\"unknowns\":{},\"nnz\":{},\"factor_mb\":{:.1},\"factor_gflop\":{:.3},{adaptive}}}",
        r.linear_solver,
        r.status,
        r.iterations,
        r.numeric_factorizations,
        t.total,
        t.assembly,
        t.factor,
        t.solve,
        t.line_search,
        pattern.n(),
        pattern.nnz(),
        sys.factor_bytes().map_or(0.0, |b| b as f64 / 1e6),
        sys.factor_flops().map_or(0.0, |f| f / 1e9),
    )
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(line) => println!("{line}"),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    }
}
