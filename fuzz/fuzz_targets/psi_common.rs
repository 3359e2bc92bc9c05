//! What the `.psi` fuzz target does with its input (shared with the corpus
//! replay test `tests/tests/bad_input_fuzz_psi.rs`, which includes this
//! file): compile the text as the CLI does (`ecc_dsl::compile`), render any
//! diagnostics (codespan), and for every dimension that compiles, build the
//! interpreted energy (`ecc-interp`) and evaluate it — Ψ, the stretch-space
//! eigen data and the filtered F-space Hessian — at hard singular values
//! (rest, repeated, inverted, zero, antipodal, huge).
//!
//! Beyond "no panic" this checks one invariant: wherever Ψ is finite, the
//! clamped Hessian the solver would use has no NaN.

use ecc_runtime::{Energy, Filter, hessian_f, signed_svd2, signed_svd3};

const SIGMA3: [[f64; 3]; 8] = [
    [1.0, 1.0, 1.0],
    [1.3, 0.9, 0.6],
    [1.2, 1.2, 0.7],
    [1.3, 0.8, -0.6],
    [1.1, 0.9, -0.9],
    [1.0, 0.5, 0.0],
    [1e3, 1.0, 1e-6],
    [0.0, 0.0, 0.0],
];
const SIGMA2: [[f64; 2]; 7] = [
    [1.0, 1.0],
    [1.3, 0.6],
    [0.9, -0.9],
    [1.3, -0.6],
    [1.0, 0.0],
    [1e3, 1e-6],
    [0.0, 0.0],
];

fn mat3(s: [f64; 3]) -> ecc_runtime::Svd<3> {
    signed_svd3(&nalgebra::Matrix3::from_diagonal(&s.into()))
}

fn mat2(s: [f64; 2]) -> ecc_runtime::Svd<2> {
    signed_svd2(&nalgebra::Matrix2::from_diagonal(&s.into()))
}

/// Run one input (any bytes; non-UTF-8 is skipped like the CLI refuses it).
pub fn run(data: &[u8]) {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let module = match ecc_dsl::compile(src, "fuzz") {
        Ok(m) => m,
        Err(d) => {
            let _ = d.render("fuzz.psi", src);
            return;
        }
    };
    if let Ok(e) = ecc_interp::energy_from_module::<3>(&module, "fuzz.psi", &[]) {
        for s in SIGMA3 {
            let sp = e.spectral(&s);
            let _ = e.psi(&s);
            if sp.psi.is_finite() {
                let h = hessian_f(&mat3(s), &sp, Filter::Clamp);
                assert!(
                    !h.iter().any(|x| x.is_nan()),
                    "NaN in the clamped Hessian at {s:?}: {src:?}"
                );
            }
        }
    }
    if let Ok(e) = ecc_interp::energy_from_module::<2>(&module, "fuzz.psi", &[]) {
        for s in SIGMA2 {
            let sp = e.spectral(&s);
            let _ = e.psi(&s);
            if sp.psi.is_finite() {
                let h = hessian_f(&mat2(s), &sp, Filter::Clamp);
                assert!(
                    !h.iter().any(|x| x.is_nan()),
                    "NaN in the clamped Hessian at {s:?}: {src:?}"
                );
            }
        }
    }
}
