//! Time `compile` (parse → full DimIr for every dimension that applies) for
//! every energy of the standard library.
//!
//! `cargo run --release -p ecc-dsl --example compile_times`
//!
//! Each energy is compiled once to warm up, then `REPS` times; the median and
//! the maximum wall-clock time per compile are printed.

use std::time::Instant;

const REPS: usize = 15;

fn main() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "psi"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    println!(
        "{:<14} {:>6} {:>10} {:>10}",
        "energy", "dims", "median ms", "max ms"
    );
    let mut worst: f64 = 0.0;
    for f in files {
        let name = f
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let src = std::fs::read_to_string(&f).unwrap_or_default();
        let dims = match ecc_dsl::compile(&src, &name) {
            Ok(m) if std::env::var_os("ECC_BUDGET").is_some() => {
                let used = ecc_dsl::poly::WORK_BUDGET - ecc_dsl::poly::budget_left();
                eprintln!("{name}: polynomial work of the last dimension {used}");
                m.dims
                    .iter()
                    .map(|d| d.dim.to_string())
                    .collect::<Vec<_>>()
                    .join("+")
            }
            Ok(m) => m
                .dims
                .iter()
                .map(|d| d.dim.to_string())
                .collect::<Vec<_>>()
                .join("+"),
            Err(d) => {
                eprint!("{}", d.render(&name, &src));
                continue;
            }
        };
        let mut times: Vec<f64> = (0..REPS)
            .map(|_| {
                let t = Instant::now();
                let m = ecc_dsl::compile(&src, &name);
                std::hint::black_box(&m);
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let max = times[REPS - 1];
        worst = worst.max(max);
        println!("{name:<14} {dims:>6} {:>10.2} {max:>10.2}", times[REPS / 2]);
    }
    println!("worst single compile: {worst:.2} ms");
}
