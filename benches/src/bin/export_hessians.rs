//! Write the projected Newton Hessians ecc factorises at the start of a
//! solve as Matrix Market files (benches/cholmod: CHOLMOD as the reference
//! for the factorisation, issue #11).
//!
//! ```text
//! cargo run --release -p ecc-benches --bin export_hessians -- --out DIR [--data DIR] [--rings N] [NAME…]
//! ```
//!
//! NAME (default: all): `camelhead`, `armadillo_cut_low`, `hand_1_i_f5000`
//! (symmetric Dirichlet parameterisation as `scenes/camelhead_sd.toml`:
//! unit area, mean energy, uniform Tutte start, clamp filter, F-space
//! projection, no vertex fixed); `disk` (the same on the generated bumpy
//! disk of the scaling benchmark, `disk_tri(N, 1)` with z = 0.05 sin(8πx)
//! sin(8πy), N = 409 rings ≈ 1.0M triangles by default); `hand_arap`,
//! `hand_snh` (hand.mesh as the report's per-solve table: lowest 8 % fixed,
//! highest 8 % twisted 60° and pulled, energy / volume, clamp filter);
//! `disk_tutte` (not a Hessian: the interior matrix `L_II` of the uniform
//! Tutte system the parameterisation solves for its start on the same disk,
//! one scalar unknown per interior vertex, `w_ij = 1/2` per triangle edge,
//! the reference for the Tutte solve of setup).
//!
//! The matrix is exactly what faer factorises in the first Newton step:
//! the solver's own pattern (unknown numbering included) and filtered
//! Hessian at the start, plus the diagonal shift `LinearSystem::prepare`
//! applies (δ = `null_space_shift`·mean diag when nothing is fixed, raised
//! on a failed factorisation as in the solver). Each file is written
//! atomically as DIR/NAME.mtx; one JSON line per matrix goes to stdout.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use ecc_benches::mtx::{self, UpperCsc};
use ecc_benches::solve::handle_setup;
use ecc_fem::linear::LinearSystem;
use ecc_fem::linear::cholesky::CholeskyParams;
use ecc_fem::param::{ParamOptions, prepare};
use ecc_fem::{Elastic, Filter, LinearSolver, NewtonParams, NewtonSolver, Term, Tet};
use ecc_mesh::{TriMesh, disk_tri, read_tet_mesh, read_tri_mesh};
use ecc_runtime::Energy;

const ALL: [&str; 7] = [
    "camelhead",
    "armadillo_cut_low",
    "hand_1_i_f5000",
    "disk",
    "hand_arap",
    "hand_snh",
    "disk_tutte",
];

struct Args {
    out: PathBuf,
    data: PathBuf,
    rings: usize,
    names: Vec<String>,
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        out: PathBuf::new(),
        data: std::env::var_os("ECC_DATA_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../data")),
        rings: 409,
        names: Vec::new(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(x) = it.next() {
        let mut value = |flag: &str| it.next().ok_or(format!("{flag} needs a value"));
        match x.as_str() {
            "--out" => a.out = value("--out")?.into(),
            "--data" => a.data = value("--data")?.into(),
            "--rings" => {
                a.rings = value("--rings")?
                    .parse()
                    .map_err(|e| format!("--rings: {e}"))?
            }
            n if ALL.contains(&n) => a.names.push(n.into()),
            n => {
                return Err(format!(
                    "unknown argument `{n}` (matrices: {})",
                    ALL.join(", ")
                ));
            }
        }
    }
    if a.out.as_os_str().is_empty() {
        return Err("usage: export_hessians --out DIR [--data DIR] [--rings N] [NAME…]".into());
    }
    if a.names.is_empty() {
        a.names = ALL.map(String::from).to_vec();
    }
    Ok(a)
}

/// The first Newton step's factorised matrix and how it was made.
struct Exported {
    matrix: UpperCsc,
    elements: usize,
    shift: f64,
    relative_shift: f64,
    attempts: usize,
}

/// Assemble at `x` with the solver's first filter and shift it as
/// `LinearSystem::prepare` does in the first Newton step.
fn first_matrix<const D: usize>(
    solver: &mut NewtonSolver<D>,
    x: &[[f64; D]],
    elements: usize,
) -> Result<Exported, String> {
    let p = solver.params.clone();
    let filter = p.filter_policy.first(p.filter);
    if filter == Filter::None {
        return Err("a raw first step (Filter::None) starts from another shift".into());
    }
    let ev = solver
        .evaluate(x, Some(filter))
        .map_err(|e| e.to_string())?
        .map_err(|b| format!("non-finite {} at stencil {}", b.quantity, b.stencil))?;
    let mut values = ev.hessian.ok_or("no Hessian assembled")?;
    let pattern = solver.pattern().clone();
    let null_shift = if solver.dofs().n_fixed() == 0 {
        p.null_space_shift
    } else {
        0.0
    };
    let params = CholeskyParams::default();
    let mut sys = LinearSystem::with_cholesky_params(
        &pattern,
        LinearSolver::Cholesky,
        p.auto_limits,
        D,
        params,
    )
    .map_err(|e| e.to_string())?;
    let prep = sys
        .prepare(&pattern, &mut values, null_shift, p.shift_attempts)
        .map_err(|f| format!("not factorisable even with shift {}", f.shift))?;
    Ok(Exported {
        matrix: UpperCsc {
            n: pattern.n(),
            col_ptr: pattern.col_ptr().to_vec(),
            row_idx: pattern.row_idx().to_vec(),
            values,
        },
        elements,
        shift: prep.shift,
        relative_shift: prep.relative_shift,
        attempts: prep.factorizations,
    })
}

/// The bumpy disk of the scaling benchmark (`ecc-mesh`'s `setup_timing`).
fn bumpy_disk(rings: usize) -> TriMesh {
    let mut m = disk_tri(rings, 1.0);
    let k = 8.0 * std::f64::consts::PI;
    for p in &mut m.positions {
        p[2] = 0.05 * (k * p[0]).sin() * (k * p[1]).sin();
    }
    m
}

/// SD parameterisation as `scenes/camelhead_sd.toml` (linear = cholesky).
fn parameterisation(mesh: &TriMesh) -> Result<Exported, String> {
    let energy: Arc<dyn Energy<2>> = ecc_energies::by_name::<2>("sd")
        .ok_or("no energy `sd`")?
        .into();
    let opts = ParamOptions {
        newton: NewtonParams {
            tol_abs: 1e-4,
            linear_solver: LinearSolver::Cholesky,
            ..NewtonParams::default()
        },
        ..ParamOptions::default()
    };
    let mut problem = prepare(mesh, energy, &opts).map_err(|e| e.to_string())?;
    let start = problem.start.clone();
    first_matrix(&mut problem.solver, &start, mesh.triangles.len())
}

/// hand.mesh as the report's per-solve table (`ecc_benches::solve::deformation`).
fn hand(data: &Path, energy: &str) -> Result<Exported, String> {
    let mesh = read_tet_mesh(data.join("hand.mesh")).map_err(|e| e.to_string())?;
    let e: Arc<dyn Energy<3>> = ecc_energies::by_name::<3>(energy)
        .ok_or(format!("no energy `{energy}`"))?
        .into();
    let elastic = Elastic::<dyn Energy<3>, Tet>::new(e, &mesh.positions, &mesh.tets)
        .map_err(|e| e.to_string())?;
    let params = NewtonParams {
        linear_solver: LinearSolver::Cholesky,
        energy_scale: 1.0 / elastic.total_measure(),
        ..NewtonParams::default()
    };
    let (handles, x) = handle_setup(&mesh);
    let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
    let mut solver = NewtonSolver::new(mesh.positions.len(), terms, &handles, params)
        .map_err(|e| e.to_string())?;
    first_matrix(&mut solver, &x, mesh.tets.len())
}

/// `L_II` of the uniform Tutte system (`ecc_mesh::tutte_embedding`):
/// each triangle adds `1/2` to the weight of each of its edges; row `i` of
/// an interior vertex has `Σ_j w_ij` on its diagonal and `−w_ij` at each
/// interior neighbour `j` (the boundary is fixed, so its columns go to the
/// right-hand side). Upper triangle, the interior vertices in mesh order.
fn tutte_matrix(mesh: &TriMesh) -> Exported {
    let mut edges: Vec<(usize, usize)> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |c| (t[c].min(t[(c + 1) % 3]), t[c].max(t[(c + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    let mut weighted: Vec<(usize, usize, f64)> = Vec::with_capacity(edges.len() / 2);
    for e in edges {
        match weighted.last_mut() {
            Some(last) if (last.0, last.1) == e => last.2 += 0.5,
            _ => weighted.push((e.0, e.1, 0.5)),
        }
    }
    let n = mesh.positions.len();
    let mut interior = vec![true; n];
    for &(i, j, w) in &weighted {
        if w < 1.0 {
            (interior[i], interior[j]) = (false, false);
        }
    }
    let mut index = vec![usize::MAX; n];
    let mut m = 0;
    for v in (0..n).filter(|&v| interior[v]) {
        index[v] = m;
        m += 1;
    }
    let mut diagonal = vec![0.0; m];
    let mut entries = Vec::with_capacity(weighted.len() + m);
    for &(i, j, w) in &weighted {
        for (a, b) in [(i, j), (j, i)] {
            if index[a] != usize::MAX {
                diagonal[index[a]] += w;
                if index[b] != usize::MAX && index[a] < index[b] {
                    entries.push((index[a], index[b], -w));
                }
            }
        }
    }
    entries.extend(diagonal.iter().enumerate().map(|(c, &d)| (c, c, d)));
    Exported {
        matrix: UpperCsc::from_entries(m, entries),
        elements: mesh.triangles.len(),
        shift: 0.0,
        relative_shift: 0.0,
        attempts: 0,
    }
}

fn build(name: &str, a: &Args) -> Result<Exported, String> {
    let tri = |file: &str| read_tri_mesh(a.data.join(file)).map_err(|e| format!("{file}: {e}"));
    match name {
        "camelhead" => parameterisation(&tri("camelhead.off")?),
        "armadillo_cut_low" => parameterisation(&tri("armadillo_cut_low.obj")?),
        "hand_1_i_f5000" => parameterisation(&tri("hand_1_i_f5000.obj")?),
        "disk" => parameterisation(&bumpy_disk(a.rings)),
        "hand_arap" => hand(&a.data, "arap"),
        "hand_snh" => hand(&a.data, "snh"),
        "disk_tutte" => Ok(tutte_matrix(&bumpy_disk(a.rings))),
        n => Err(format!("unknown matrix `{n}`")),
    }
}

fn commit() -> String {
    std::process::Command::new("git")
        .args([
            "-C",
            env!("CARGO_MANIFEST_DIR"),
            "rev-parse",
            "--short",
            "HEAD",
        ])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map_or("unknown".into(), |o| {
            String::from_utf8_lossy(&o.stdout).trim().to_string()
        })
}

/// Write DIR/NAME.mtx through a temporary file and a rename.
fn write(dir: &Path, name: &str, e: &Exported, comments: &[String]) -> Result<PathBuf, String> {
    let path = dir.join(format!("{name}.mtx"));
    let tmp = dir.join(format!(".{name}.mtx.tmp"));
    let file = std::fs::File::create(&tmp).map_err(|err| format!("{}: {err}", tmp.display()))?;
    let mut out = BufWriter::new(file);
    mtx::write(&mut out, &e.matrix, comments)
        .and_then(|_| out.flush())
        .map_err(|err| format!("{}: {err}", tmp.display()))?;
    drop(out);
    std::fs::rename(&tmp, &path).map_err(|err| format!("{}: {err}", path.display()))?;
    Ok(path)
}

fn run() -> Result<(), String> {
    let a = args()?;
    std::fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    let commit = commit();
    for name in &a.names {
        let e = build(name, &a).map_err(|err| format!("{name}: {err}"))?;
        let m = &e.matrix;
        let what = if name == "disk_tutte" {
            "uniform Tutte system L_II"
        } else {
            "first projected Newton matrix"
        };
        let comments = [
            format!("ecc {what} `{name}` (benches/src/bin/export_hessians.rs), commit {commit}"),
            format!(
                "elements {} unknowns {} shift {:e} (relative {:e}, {} attempt(s))",
                e.elements, m.n, e.shift, e.relative_shift, e.attempts
            ),
        ];
        let path = write(&a.out, name, &e, &comments)?;
        let line = serde_json::json!({
            "matrix": name,
            "file": path.display().to_string(),
            "elements": e.elements,
            "n": m.n,
            "nnz_upper": m.row_idx.len(),
            "shift": e.shift,
            "relative_shift": e.relative_shift,
            "attempts": e.attempts,
            "commit": commit,
        });
        println!("{line}");
    }
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("export_hessians: {e}");
        std::process::exit(1);
    }
}
