//! Compile time against the size of the energy: generated polynomial energies
//! of n terms, compiled by the same path as `ecc FILE --emit rs` (parse →
//! CAS → derivatives → IR for every dimension that applies).
//!
//! `cargo run --release -p ecc-dsl --example compile_scaling -- [family] [n…] [--reps R]`
//!
//! Families (default: inv, sig, trans):
//! * `inv`  — Σ c_k I1^a I2^b I3^c (distinct monomials, graded order);
//! * `sig`  — Σ c_k (s1^a s2^b s3^c + its 5 permutations), an isotropic
//!   polynomial in the stretches (3D only);
//! * `trans` — the `inv` polynomial plus, every 8th term, an exp or log
//!   subterm (c·exp(I1/k), c·log(I3)^a, c·I2^a·exp(-I3/k));
//! * `exps` — Σ_k c_k exp(I1/k), k = 1…n: n distinct exponentials;
//! * `logs` — Σ_k c_k log(I2 + k): n distinct logarithms;
//! * `exppoly` — Σ_k c_k (I2 − k)² exp(I3/k).
//!
//! Default sizes: 250 500 1000 2000 5000 10000 20000. Each compile is run
//! `R` times (default 1) and the minimum is printed: the machine is shared,
//! so the minimum is the least noisy estimate. `work` is the deterministic
//! CAS operation count of one compile ([`ecc_dsl::cas::work_count`]);
//! `max bits` the size of the largest constant the compile built
//! ([`ecc_dsl::cas::largest_number_bits`]).

use std::time::Instant;

#[path = "common/scaling_gen.rs"]
mod scaling_gen;

use scaling_gen::{Family, energy};

fn main() {
    let mut families: Vec<Family> = Vec::new();
    let mut sizes: Vec<usize> = Vec::new();
    let mut reps = 1usize;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--reps" => reps = args.next().and_then(|r| r.parse().ok()).unwrap_or(1),
            _ => match (Family::parse(&a), a.parse::<usize>()) {
                (Some(f), _) => families.push(f),
                (None, Ok(n)) => sizes.push(n),
                _ => {
                    eprintln!(
                        "unknown argument {a:?} (families: inv, sig, trans, exps, logs, exppoly; sizes: numbers)"
                    );
                    std::process::exit(2);
                }
            },
        }
    }
    if families.is_empty() {
        families = vec![Family::Inv, Family::Sig, Family::Trans];
    }
    if sizes.is_empty() {
        sizes = vec![250, 500, 1000, 2000, 5000, 10000, 20000];
    }
    println!(
        "{:<7} {:>7} {:>9} {:>10} {:>9} {:>12} {:>8}",
        "family", "n", "bytes", "min s", "nodes", "work", "max bits"
    );
    for f in &families {
        for &n in &sizes {
            let src = energy(*f, n);
            let mut best = f64::INFINITY;
            let mut nodes = 0;
            let mut work = 0;
            for _ in 0..reps.max(1) {
                ecc_dsl::cas::reset_largest_number_bits();
                let w0 = ecc_dsl::cas::work_count();
                let t = Instant::now();
                let m = ecc_dsl::compile(&src, "scaling");
                best = best.min(t.elapsed().as_secs_f64());
                work = ecc_dsl::cas::work_count() - w0;
                match m {
                    Ok(m) => nodes = m.dims.iter().map(|d| d.graph.len()).sum(),
                    Err(d) => {
                        eprint!("{}", d.render("scaling", &src));
                        std::process::exit(1);
                    }
                }
            }
            println!(
                "{:<7} {n:>7} {:>9} {best:>10.3} {nodes:>9} {work:>12} {:>8}",
                f.name(),
                src.len(),
                ecc_dsl::cas::largest_number_bits()
            );
        }
    }
}
