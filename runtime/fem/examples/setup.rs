//! Wall and CPU time of a parameterisation's setup (`param::prepare`: rest
//! frames, pattern, ordering, symbolic analysis and storage of the
//! factor, beside the Tutte solve on its own thread), without the Newton
//! solve: the phase the 1M-triangle benchmark calls setup after the read.
//!
//! `cargo run --release -p ecc-fem --example setup -- MESH [REPEATS]`
//!
//! Reads MESH once, then runs the SD parameterisation's `prepare` REPEATS
//! times (default 5) with the default options and prints one line per run:
//! wall seconds and the process's CPU seconds (user + system, all threads,
//! from `/proc/self/stat`) and the Newton factor's size and flops (which
//! the shared vertex dissection must not worsen), then the best of each.
//! CPU time is what a busy machine cannot hide: on two cores setup's wall
//! time is at least half of it.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::param::{ParamOptions, prepare};
use ecc_mesh::read_tri_mesh;
use ecc_runtime::energies::SymmetricDirichlet;

/// CPU seconds (user + system) of this process so far, or NaN off Linux.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // fields after the parenthesised command: state is field 3, utime 14, stime 15
    let Some(rest) = stat.rsplit_once(')').map(|(_, r)| r) else {
        return f64::NAN;
    };
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i - 3).and_then(|v| v.parse::<f64>().ok());
    match (ticks(14), ticks(15)) {
        // the kernel's USER_HZ is 100 on every Linux this runs on
        (Some(u), Some(s)) => (u + s) / 100.0,
        _ => f64::NAN,
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: setup MESH [REPEATS]");
        std::process::exit(2);
    };
    let repeats: usize = args.get(1).and_then(|r| r.parse().ok()).unwrap_or(5);
    let mesh = match read_tri_mesh(path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(1);
        }
    };
    let opts = ParamOptions::default();
    let energy = Arc::new(SymmetricDirichlet);
    let (mut best_wall, mut best_cpu) = (f64::INFINITY, f64::INFINITY);
    for r in 0..repeats {
        let (t, c) = (Instant::now(), cpu_seconds());
        let problem = match prepare(&mesh, energy.clone(), &opts) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{path}: {e}");
                std::process::exit(1);
            }
        };
        let (wall, cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
        let linear = problem.solver.linear_system();
        let (bytes, flops) = (linear.factor_bytes(), linear.factor_flops());
        drop(problem);
        println!(
            "run {r}: wall {wall:.3} s, cpu {cpu:.2} s, factor {:.1} MB, {:.3e} flops",
            bytes.unwrap_or(0) as f64 / 1e6,
            flops.unwrap_or(f64::NAN)
        );
        best_wall = best_wall.min(wall);
        best_cpu = best_cpu.min(cpu);
    }
    println!(
        "{path}: {} vertices, {} triangles: best wall {best_wall:.3} s, best cpu {best_cpu:.2} s",
        mesh.positions.len(),
        mesh.triangles.len()
    );
}
