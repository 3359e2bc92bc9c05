//! The autodiff baseline's two report sections on small inputs (minutes, not
//! the whole report): per-element timing, then one SD parameterisation per
//! method (analytic clamp, numeric projection, autodiff).
//!
//! `cargo run --release -p ecc-benches --example autodiff [BATCH] [ROUNDS] [MESH]`
//! (defaults 128, 11, hand_1_i_f5000.obj from the data folder).

use std::sync::Arc;

use ecc_benches::element::autodiff;
use ecc_benches::solve::{self, SolveLimits, SolveMethod};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let batch: usize = args.next().map_or(Ok(128), |a| a.parse())?;
    let rounds: usize = args.next().map_or(Ok(11), |a| a.parse())?;
    let mesh = args.next().unwrap_or_else(|| "hand_1_i_f5000.obj".into());
    let t = autodiff::run(batch, rounds)?;
    println!("dim energy analytic_ns numeric_ns autodiff_ns autodiff_raw_ns ratio max_rel_diff");
    for r in &t.rows {
        println!(
            "{}D {} {:.0} {:.0} {:.0} {:.0} {:.2} {:.1e}",
            r.dim,
            r.energy,
            r.analytic_ns,
            r.numeric_ns,
            r.autodiff_ns,
            r.autodiff_raw_ns,
            r.ratio,
            r.max_rel_diff
        );
    }
    let m = ecc_mesh::read_tri_mesh(ecc_mesh::data_dir().join(&mesh))?;
    let limits = SolveLimits {
        seconds: 60.0,
        newton_iters: 300,
        proxy_iters: 0,
    };
    for method in [
        SolveMethod::Clamp,
        SolveMethod::NumericProjection,
        SolveMethod::Autodiff,
    ] {
        let e = Arc::new(ecc_energies::SymmetricDirichlet2::new());
        let tr = solve::parameterization(&mesh, &m, e, method, &limits)?;
        println!(
            "{mesh} {}: {} iterations, time to 1e-4 {:?} s ({:?} its), total {:.2} s, {}",
            method.label(),
            tr.points.len() - 1,
            tr.time_to(1e-4),
            tr.iters_to(1e-4),
            tr.seconds_measured,
            tr.status
        );
    }
    Ok(())
}
