//! Time the interpreter against the generated energies (ecc-energies):
//! `spectral(σ)` and `psi(σ)` per call, 3D and 2D, on 100 000 random σ.
//!
//! Run with `cargo run --release -p ecc-interp --example speed`.

use std::hint::black_box;
use std::time::Instant;

use ecc_runtime::Energy;
use rand::{Rng, SeedableRng};

/// Best-of-5 nanoseconds per call of `f` over `points`.
fn time<const D: usize>(points: &[[f64; D]], f: impl Fn(&[f64; D]) -> f64) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t = Instant::now();
        let mut acc = 0.0;
        for p in points {
            acc += f(black_box(p));
        }
        black_box(acc);
        best = best.min(t.elapsed().as_secs_f64() * 1e9 / points.len() as f64);
    }
    best
}

fn row<const D: usize>(
    name: &str,
    it: &dyn Energy<D>,
    generated: &dyn Energy<D>,
    points: &[[f64; D]],
) {
    let si = time(points, |s| it.spectral(s).twist[0]);
    let sg = time(points, |s| generated.spectral(s).twist[0]);
    let pi = time(points, |s| it.psi(s));
    let pg = time(points, |s| generated.psi(s));
    println!(
        "{name:<14}{D}D  spectral {si:7.1} ns vs {sg:6.1} ns ({:4.1}x)   psi {pi:6.1} ns vs {pg:5.1} ns ({:4.1}x)",
        si / sg,
        pi / pg
    );
}

fn points<const D: usize>(n: usize) -> Vec<[f64; D]> {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    (0..n)
        .map(|_| {
            let mut s: [f64; D] = std::array::from_fn(|_| r.gen_range(0.5..1.5));
            s.sort_by(|a, b| b.total_cmp(a));
            s
        })
        .collect()
}

fn main() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi");
    let p3 = points::<3>(100_000);
    let p2 = points::<2>(100_000);
    println!("interpreter (ecc-interp) vs generated (ecc-energies), per call, best of 5:");
    for (file, reg) in [
        ("arap", "arap"),
        ("sd3", "sd"),
        ("snh", "snh"),
        ("neohookean", "neohookean"),
        ("stvk", "stvk"),
        ("ogden", "ogden"),
        ("hencky", "hencky"),
    ] {
        let it =
            ecc_interp::load_psi::<3>(format!("{dir}/{file}.psi"), &[]).expect("library energy");
        let generated = ecc_energies::by_name::<3>(reg).expect("generated energy");
        row::<3>(file, it.as_ref(), generated.as_ref(), &p3);
    }
    for (file, reg) in [
        ("arap", "arap"),
        ("sd2", "sd"),
        ("mips2", "mips"),
        ("snh", "snh"),
        ("ogden2", "ogden2"),
    ] {
        let it =
            ecc_interp::load_psi::<2>(format!("{dir}/{file}.psi"), &[]).expect("library energy");
        let generated = ecc_energies::by_name::<2>(reg).expect("generated energy");
        row::<2>(file, it.as_ref(), generated.as_ref(), &p2);
    }
}
