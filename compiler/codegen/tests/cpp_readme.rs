//! The C++ snippet of README.md ("C++ (and GPU-style code)"), compiled with
//! the strict flags and run: the three lines work as written, the projected
//! Hessians are symmetric with non-negative diagonals, the snippet in the
//! README is still the one checked here, and the header also compiles with
//! `ECC_HOST_DEVICE` defined to an attribute (where `__host__ __device__` goes).

mod cpp_common;

use ecc_codegen::{CppOptions, generate_cpp};

const SNIPPET: &str = r#"#include "snh.hpp"
ecc::energies::Snh snh;                                    // parameters: snh.mu, snh.lambda
auto p = snh.eval(F, ecc::Filter::clamp());                // Ψ, vec(∂Ψ/∂F), PSD 9×9 Hessian
auto t = snh.eval_tet(x, dm_inv, volume, ecc::Filter::abs()); // element: 12-vector, 12×12"#;

#[test]
fn readme_cpp_snippet_compiles_and_runs() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md"))
        .expect("README.md");
    assert!(
        readme.contains(SNIPPET),
        "README's C++ snippet changed: update this test"
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../energies/psi/snh.psi"
    ))
    .expect("snh.psi");
    let m = ecc_dsl::compile(&src, "snh").expect("compiles");
    let h = generate_cpp(&m, &CppOptions::named("Snh")).expect("emits");
    std::fs::write(dir.path().join("snh.hpp"), h).expect("write");
    let (include, body) = SNIPPET.split_once('\n').expect("two parts");
    let main = format!(
        r#"{include}
#include <cstdio>
int main() {{
    const double F[3][3] = {{{{1.1, 0.1, 0.0}}, {{0.0, 0.9, 0.2}}, {{0.1, 0.0, 1.2}}}};
    const double x[4][3] = {{{{0, 0, 0}}, {{1.1, 0, 0.1}}, {{0, 0.9, 0}}, {{0.1, 0, 1.2}}}};
    const double dm_inv[3][3] = {{{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}};
    const double volume = 1.0 / 6.0;
{body}
    int bad = 0;
    for (int i = 0; i < 9; ++i) for (int j = 0; j < 9; ++j) bad += p.hess[i][j] != p.hess[j][i];
    for (int i = 0; i < 12; ++i) bad += t.hess[i][i] < 0.0;
    std::printf("%d %.17g %.17g\n", bad, p.psi, t.psi);
    return bad;
}}
"#
    );
    let path = dir.path().join("readme.cpp");
    std::fs::write(&path, main).expect("write");
    // The device hook sits where a `__host__ __device__` would: every
    // function of the header and runtime still compiles with an attribute there.
    cpp_common::compile("g++", &path, &["-DECC_HOST_DEVICE=__attribute__((cold))"]);
    let exe = cpp_common::compile("g++", &path, &[]);
    let out = std::process::Command::new(exe).output().expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse().expect("number"))
        .collect();
    assert!(
        v[0] == 0.0 && v[1].is_finite() && v[2].is_finite(),
        "{text}"
    );
}
