//! Newton iterations of the SD parameterisation under changed solver rules
//! (issue #11: why TinyAD needs fewer iterations on hand_1_i_f5000).
//!
//! `cargo run --release -p ecc-benches --example iterations MESH SPEC…`
//!
//! MESH is a triangle mesh of the data folder (e.g. `hand_1_i_f5000.obj`),
//! parameterised, or `hand.mesh:arap` / `hand.mesh:snh`, the report's
//! twist-and-pull deformation of a tet mesh (fixed handles; `disk`/`raw`
//! do not apply; tol 1e-4 as everywhere here). Each SPEC
//! is a base method followed by `+`-separated changes:
//! * bases: `fspace`, `element`, `hybrid` (analytic clamp with that
//!   projection), `numeric` (raw element Hessian, nalgebra eigensolve of the
//!   6×6), `autodiff` (dual numbers + numeric projection), `defaults` /
//!   `defaults1` (what `ecc sim` runs, on two threads / one);
//! * changes: `one` (every line search starts at α = 1, the barrier's +∞
//!   rejects steps past α_max), `s<x>` (barrier_safety x), `b<x>`
//!   (backtracking factor), `c<x>` (Armijo c₁), `eps<x>` (clamp eigenvalues
//!   to x), `tinyad` (TinyAD's rule: `one+b0.8+c1e-4+eps1e-9`), `disk`
//!   (Tutte start left on the unit circle), `raw` (mesh at its own scale,
//!   objective Σ A (‖J‖² + ‖J⁻¹‖²): TinyAD-Examples' units; `disk+raw` is
//!   their `parametrization_*.cc` setup), `trn` (filter policy
//!   `TrustRegionNewton`), `ord=<name>` (fill-reducing ordering, e.g.
//!   `ord=block-amd`, instead of `auto`).
//!
//! Same start, scaling and stopping rule as the report (unit area, mean
//! energy, uniform Tutte start, ‖∇E‖∞ ≤ 1e-4; here the solve stops there).
//! Prints one line per SPEC: iterations to 1e-4, seconds to 1e-4 (solver
//! records: assembly + factorisation + solve + line search), status; with
//! `ECC_TRACE` set, also every iterate's index, ‖∇E‖∞ and energy.

use std::sync::Arc;

use ecc_benches::solve::{self, SolveError, SolveLimits, SolveMethod, Trace, Variant};
use ecc_fem::elastic::{HYBRID_MIN_COND, Projection};
use ecc_fem::linear::ordering::FillOrdering;
use ecc_fem::{Filter, FilterPolicy};
use ecc_runtime::Energy;

fn parse(spec: &str) -> Result<(SolveMethod, Variant), String> {
    let mut parts = spec.split('+');
    let mut v = Variant {
        tol_abs: 1e-4,
        ..Default::default()
    };
    let method = match parts.next().unwrap_or("") {
        "fspace" => SolveMethod::Clamp,
        "element" => {
            v.projection = Projection::Element;
            SolveMethod::Clamp
        }
        "hybrid" => {
            v.projection = Projection::Hybrid {
                min_cond: HYBRID_MIN_COND,
            };
            SolveMethod::Clamp
        }
        "numeric" => SolveMethod::NumericProjection,
        "autodiff" => SolveMethod::Autodiff,
        "defaults" => SolveMethod::Defaults,
        "defaults1" => SolveMethod::DefaultsOneThread,
        other => return Err(format!("{spec}: unknown base `{other}`")),
    };
    for change in parts {
        let num = |prefix: &str| -> Result<f64, String> {
            change[prefix.len()..]
                .parse()
                .map_err(|e| format!("{spec}: `{change}`: {e}"))
        };
        match change {
            "one" => v.barrier_safety = f64::INFINITY,
            "disk" => v.unit_disk_start = true,
            "trn" => v.filter_policy = Some(FilterPolicy::TrustRegionNewton),
            "raw" => v.raw_units = true,
            "tinyad" => {
                let t = Variant::tinyad();
                v.filter = t.filter;
                v.barrier_safety = t.barrier_safety;
                v.backtrack = t.backtrack;
                v.armijo_c1 = t.armijo_c1;
            }
            c if c.starts_with("ord=") => {
                let name = &c["ord=".len()..];
                v.ordering = Some(
                    FillOrdering::from_name(name)
                        .ok_or_else(|| format!("{spec}: unknown ordering `{name}`"))?,
                );
            }
            c if c.starts_with("eps") => v.filter = Some(Filter::ClampEps(num("eps")?)),
            c if c.starts_with('s') => v.barrier_safety = num("s")?,
            c if c.starts_with('b') => v.backtrack = num("b")?,
            c if c.starts_with('c') => v.armijo_c1 = num("c")?,
            _ => return Err(format!("{spec}: unknown change `{change}`")),
        }
    }
    Ok((method, v))
}

type Solve = Box<dyn Fn(SolveMethod, &SolveLimits, &Variant) -> Result<Trace, SolveError>>;

/// The problem named by MESH: `NAME.mesh:arap` / `NAME.mesh:snh` is the
/// report's twist-and-pull deformation of that tet mesh, anything else the SD
/// parameterisation of a triangle mesh.
fn problem(file: &str) -> Result<Solve, Box<dyn std::error::Error>> {
    let data = ecc_mesh::data_dir();
    if let Some((name, energy)) = file.split_once(':') {
        let mesh = ecc_mesh::read_tet_mesh(data.join(name))?;
        let energy: Arc<dyn Energy<3>> = match energy {
            "arap" => Arc::new(ecc_energies::Arap::new()),
            "snh" => Arc::new(ecc_energies::StableNeoHookean::new()),
            other => return Err(format!("{file}: unknown energy `{other}`").into()),
        };
        let file = file.to_string();
        return Ok(Box::new(move |m, l, v| {
            solve::deformation_with(&file, &mesh, energy.clone(), m, l, v)
        }));
    }
    let mesh = ecc_mesh::read_tri_mesh(data.join(file))?;
    let file = file.to_string();
    Ok(Box::new(move |m, l, v| {
        let e = Arc::new(ecc_energies::SymmetricDirichlet2::new());
        solve::parameterization_with(&file, &mesh, e, m, l, v)
    }))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let file = args.next().ok_or("usage: iterations MESH SPEC…")?;
    let limits = SolveLimits {
        seconds: 600.0,
        newton_iters: 1000,
        proxy_iters: 0,
    };
    let solve = problem(&file)?;
    for spec in args {
        let (method, variant) = parse(&spec)?;
        let tr = solve(method, &limits, &variant)?;
        let its = tr.iters_to(1e-4).map_or("-".into(), |i| i.to_string());
        let secs = tr.time_to(1e-4).map_or("-".into(), |t| format!("{t:.3}"));
        println!(
            "{file} {spec}: iterations {its}, seconds {secs}, {}",
            tr.status
        );
        if std::env::var_os("ECC_TRACE").is_some() {
            for p in &tr.points {
                println!("  {} {:.6e} {:.12e}", p.iter, p.grad_inf, p.energy);
            }
        }
    }
    Ok(())
}
