//! Replays the committed cargo-fuzz corpus of the `.psi` front end
//! (`fuzz/corpus/psi`, minimised: every input reached new code while
//! fuzzing) and the seeds through exactly the code the fuzz target runs
//! (`fuzz/fuzz_targets/psi_common.rs`: compile, render diagnostics, build
//! the interpreted energy and evaluate Ψ, the eigen data and the clamped
//! Hessian at hard σ, asserting no NaN where Ψ is finite). Any panic fails
//! the test. See `fuzz/README.md`.

#[path = "../../fuzz/fuzz_targets/psi_common.rs"]
mod psi_common;

use std::path::PathBuf;

#[test]
fn psi_corpus() {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../fuzz"));
    let mut n = 0;
    for dir in ["corpus/psi", "seeds/psi"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
        paths.sort();
        for p in paths {
            let bytes = std::fs::read(&p).unwrap();
            let r = std::panic::catch_unwind(|| psi_common::run(&bytes));
            assert!(r.is_ok(), "{} panics", p.display());
            n += 1;
        }
    }
    assert!(n >= 20, "only {n} inputs found");
    println!("{n} .psi inputs replayed");
}
