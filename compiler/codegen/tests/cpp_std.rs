//! The emitted C++ of every standard-library energy (`energies/psi/*.psi`)
//! compiles with `-std=c++17 -O2 -Wall -Wextra -Werror` (g++, and clang++
//! when installed) and agrees with the Rust side — the generated Rust
//! energies of ecc-energies lifted by ecc-runtime — to 10⁻¹² relative on the
//! hard cases: rest, uniform scale, repeated σ, σi + σj ≈ 0 (exactly and
//! within the switch band), tiny σ, inversion, huge stretch, each also under
//! random rotations: Ψ, vec(∂Ψ/∂F), the 4 filtered d²×d² Hessians and the
//! element (triangle/tetrahedron) energy, gradient and Hessians.
//!
//! All headers go into one driver program (so including several emitted
//! headers together is checked too), compiled once per compiler.

mod cpp_common;

use cpp_common::{
    Case, blocks, compare, compile, compilers, rotation, run, rust_line, write_driver,
};
use ecc_codegen::type_name_from_stem;
use ecc_runtime::Energy;
use nalgebra::SMatrix;

/// Agreement required between C++ and Rust (relative to each block's scale).
const TOL: f64 = 1e-12;

fn library() -> Vec<(ecc_dsl::Module, String)> {
    let dir = format!("{}/../../energies/psi", env!("CARGO_MANIFEST_DIR"));
    let mut stems: Vec<String> = std::fs::read_dir(&dir)
        .expect("energies/psi")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "psi"))
        .filter_map(|p| p.file_stem().and_then(|s| s.to_str()).map(String::from))
        .collect();
    stems.sort();
    assert!(
        stems.len() >= 18,
        "the standard library has {} files",
        stems.len()
    );
    stems
        .iter()
        .map(|stem| {
            let path = format!("{dir}/{stem}.psi");
            let src = std::fs::read_to_string(&path).expect("read");
            let m = ecc_dsl::compile(&src, stem)
                .unwrap_or_else(|d| panic!("{}", d.render(&path, &src)));
            (m, type_name_from_stem(stem))
        })
        // Fibre energies (whose Rust counterparts come from `fibre_by_name`, not
        // `by_name`) are tested by cpp_fibre.rs.
        .filter(|(m, _)| m.dims.iter().all(|d| d.fibre.is_none()))
        .collect()
}

/// The hard cases' singular values (see the module docs).
fn hard_sigmas(d: usize) -> Vec<Vec<f64>> {
    let band = 1e-9; // inside the ε^(1/3) switch band
    let out = 1e-4; // outside it, still close
    let v: Vec<Vec<f64>> = if d == 2 {
        vec![
            vec![1.0, 1.0],
            vec![1.7, 1.7],
            vec![1.3, 0.8],
            vec![1.2, 1.2 * (1.0 + band)],
            vec![1.2, -1.2],
            vec![1.2, -1.2 * (1.0 + band)],
            vec![1.2, -1.2 * (1.0 + out)],
            vec![1.0, 1e-7],
            vec![1.5, -0.4],
            vec![1e3, 1e-3],
            vec![40.0, 0.9],
        ]
    } else {
        vec![
            vec![1.0, 1.0, 1.0],
            vec![1.7, 1.7, 1.7],
            vec![1.3, 1.3, 0.8],
            vec![1.2, 1.2 * (1.0 + band), 0.9],
            vec![1.3, 0.9, -0.9],
            vec![1.3, 0.9, -0.9 * (1.0 + band)],
            vec![1.3, 0.9, -0.9 * (1.0 + out)],
            vec![1.0, 1e-4, 1e-7],
            vec![1.4, 0.8, -0.5],
            vec![1e3, 1.0, 1e-3],
            vec![0.6, 0.6, -0.6],
            vec![1.1, 0.95, 0.9],
        ]
    };
    v
}

fn cases<const D: usize>() -> Vec<Case<D>> {
    let mut st = 0x5eed_u64 + D as u64;
    let rest_nodes: Vec<[f64; D]> = if D == 2 {
        vec![
            [0.0; D],
            std::array::from_fn(|i| [1.0, 0.1][i]),
            std::array::from_fn(|i| [0.2, 1.1][i]),
        ]
    } else {
        vec![
            [0.0; D],
            std::array::from_fn(|i| [1.0, 0.1, 0.0][i]),
            std::array::from_fn(|i| [0.2, 1.1, 0.0][i]),
            std::array::from_fn(|i| [0.1, 0.2, 0.9][i]),
        ]
    };
    let mut out = Vec::new();
    for s in hard_sigmas(D) {
        let diag = SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { s[i] } else { 0.0 });
        let mut fs = vec![diag];
        for _ in 0..2 {
            let (r1, r2) = (rotation::<D>(&mut st), rotation::<D>(&mut st));
            fs.push(r1 * diag * r2.transpose());
        }
        for f in fs {
            let x = rest_nodes
                .iter()
                .map(|p| {
                    let v = f * nalgebra::SVector::<f64, D>::from_fn(|i, _| p[i]);
                    std::array::from_fn(|i| v[i])
                })
                .collect();
            out.push(Case {
                f,
                rest_nodes: rest_nodes.clone(),
                x,
            });
        }
    }
    out
}

fn energy2(stem: &str) -> Box<dyn Energy<2>> {
    ecc_energies::by_name::<2>(stem).unwrap_or_else(|| panic!("no 2D energy {stem}"))
}

fn energy3(stem: &str) -> Box<dyn Energy<3>> {
    ecc_energies::by_name::<3>(stem).unwrap_or_else(|| panic!("no 3D energy {stem}"))
}

#[test]
fn every_library_energy_compiles_and_agrees_with_rust() {
    let lib = library();
    let dir = tempfile::tempdir().expect("tempdir");
    let (src, energies) = write_driver(dir.path(), &lib);
    let mut input = String::new();
    let mut expected: Vec<(String, usize, Vec<f64>)> = Vec::new();
    for (idx, ((module, _), de)) in lib.iter().zip(&energies).enumerate() {
        for &d in &de.dims {
            if d == 2 {
                let e = energy2(&module.name);
                for (k, c) in cases::<2>().iter().enumerate() {
                    let (line, want) = rust_line::<2>(e.as_ref(), idx, c);
                    input.push_str(&line);
                    expected.push((format!("{} 2D case {k}", module.name), 2, want));
                }
            } else {
                let e = energy3(&module.name);
                for (k, c) in cases::<3>().iter().enumerate() {
                    let (line, want) = rust_line::<3>(e.as_ref(), idx, c);
                    input.push_str(&line);
                    expected.push((format!("{} 3D case {k}", module.name), 3, want));
                }
            }
        }
    }
    for cc in compilers() {
        let exe = compile(&cc, &src, &[]);
        let got = run(&exe, &input);
        assert_eq!(got.len(), expected.len(), "{cc}: one line per case");
        let mut worst = 0.0f64;
        let mut failures = Vec::new();
        for (g, (what, d, want)) in got.iter().zip(&expected) {
            match compare(g, want, &blocks(*d), TOL) {
                Ok(w) => worst = worst.max(w),
                Err(msg) => failures.push(format!("{what}: {msg}")),
            }
        }
        assert!(
            failures.is_empty(),
            "{cc}: {} of {} cases disagree:\n{}",
            failures.len(),
            expected.len(),
            failures.join("\n")
        );
        eprintln!(
            "{cc}: {} cases agree, worst relative difference {worst:e}",
            expected.len()
        );
    }
}
