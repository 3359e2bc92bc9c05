//! Symmetric Dirichlet parameterisation of a disk-topology mesh, printing the
//! per-iteration records and a JSON summary (default filter policy: trust-region
//! Newton, `ParamOptions::default`; `fixed` gives the paper's fixed clamp).
//!
//! `cargo run --release -p ecc-fem --example parameterize -- MESH [uniform|mean-value] [cholesky|pcg|auto] [fixed|adaptive|newton|raw|abs]`

use std::sync::Arc;

use ecc_fem::LinearSolver;
use ecc_fem::param::{ParamOptions, parameterize};
use ecc_mesh::{TutteWeights, read_tri_mesh};
use ecc_runtime::energies::SymmetricDirichlet;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!(
            "usage: parameterize MESH [uniform|mean-value] [cholesky|pcg|auto] [fixed|adaptive|newton|raw|abs]"
        );
        std::process::exit(2);
    };
    let mut opts = ParamOptions::default();
    for a in &args[1..] {
        match a.as_str() {
            "uniform" => opts.tutte = TutteWeights::Uniform,
            "mean-value" => opts.tutte = TutteWeights::MeanValue,
            "cholesky" => opts.newton.linear_solver = LinearSolver::Cholesky,
            "pcg" => opts.newton.linear_solver = LinearSolver::Pcg,
            "auto" => opts.newton.linear_solver = LinearSolver::Auto,
            "fixed" => opts.newton.filter_policy = ecc_fem::FilterPolicy::Fixed,
            "adaptive" => opts.newton.filter_policy = ecc_fem::FilterPolicy::TrustRegion,
            "newton" => opts.newton.filter_policy = ecc_fem::FilterPolicy::TrustRegionNewton,
            "raw" => opts.newton.filter = ecc_fem::Filter::None,
            "abs" => opts.newton.filter = ecc_fem::Filter::Abs,
            other => {
                eprintln!("unknown option `{other}`");
                std::process::exit(2);
            }
        }
    }
    let mesh = match read_tri_mesh(path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let p = match parameterize(&mesh, Arc::new(SymmetricDirichlet), &opts) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    println!(
        "iter       energy     |grad|inf     alpha     alpha_max  shift      filter  t_asm    t_fac    t_sol    t_ls"
    );
    for r in &p.result.records {
        println!(
            "{:4} {:14.8e} {:10.3e} {:10.3e} {:10} {:10.2e} {:6} {:8.4} {:8.4} {:8.4} {:8.4}",
            r.iter,
            r.energy,
            r.grad_inf,
            r.step,
            r.max_step.map_or("-".to_string(), |a| format!("{a:.3e}")),
            r.shift,
            r.filter,
            r.t_assembly,
            r.t_factor,
            r.t_solve,
            r.t_line_search
        );
        if let Some(rho) = r.rho {
            println!("      rho {rho:.6}");
        }
    }
    let name = std::path::Path::new(path)
        .file_name()
        .map_or(path.clone(), |n| n.to_string_lossy().into_owned());
    match serde_json::to_string(&p.summary(&name, "symmetric_dirichlet", mesh.triangles.len())) {
        Ok(s) => println!("{s}"),
        Err(e) => eprintln!("{e}"),
    }
}
