//! The C++ snippet of README.md ("C++ (and GPU-style code)"), compiled with
//! the strict flags and run: the three lines work as written, the projected
//! Hessians are symmetric with non-negative diagonals, the snippet in the
//! README is still the one checked here, and the header also compiles with
//! `ECC_HOST_DEVICE` defined to an attribute (where `__host__ __device__` goes).
//! The fibre snippet likewise: it compiles, runs, and its projected Hessians
//! are symmetric and PSD on the diagonal.

mod cpp_common;

use ecc_codegen::{CppOptions, generate_cpp};

const SNIPPET: &str = r#"#include "snh.hpp"
ecc::energies::Snh snh;                                    // parameters: snh.mu, snh.lambda
auto p = snh.eval(F, ecc::Filter::clamp());                // Ψ, vec(∂Ψ/∂F), PSD 9×9 Hessian
auto t = snh.eval_tet(x, dm_inv, volume, ecc::Filter::abs()); // element: 12-vector, 12×12"#;

const FIBRE_SNIPPET: &str = r#"#include "fibre_stvk.hpp"
ecc::energies::FibreStvk fib;                              // ψ = μ/2 (I5 − 1)², fib.mu
auto q = fib.fibre_eval(F, a, ecc::Filter::clamp());       // ψ, I4, I5, vec(∂ψ/∂F), PSD 9×9; a: unit fibre
auto r = fib.fibre_eval_tet(x, dm_inv, volume, a);         // element: 12-vector, 12×12"#;

#[test]
fn readme_fibre_snippet_compiles_and_runs() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md"))
        .expect("README.md");
    assert!(
        readme.contains(FIBRE_SNIPPET),
        "README's fibre C++ snippet changed: update this test"
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../energies/psi/fibre_stvk.psi"
    ))
    .expect("fibre_stvk.psi");
    let m = ecc_dsl::compile(&src, "fibre_stvk").expect("compiles");
    let h = generate_cpp(&m, &CppOptions::named("FibreStvk")).expect("emits");
    std::fs::write(dir.path().join("fibre_stvk.hpp"), h).expect("write");
    let (include, body) = FIBRE_SNIPPET.split_once('\n').expect("two parts");
    let main = format!(
        r#"{include}
#include <cstdio>
int main() {{
    // Compressed along the fibre (I5 < 1): λ_across = 2μ(I5 − 1) < 0 is clamped.
    const double F[3][3] = {{{{0.7, 0.1, 0.0}}, {{0.0, 0.9, 0.2}}, {{0.1, 0.0, 1.2}}}};
    const double x[4][3] = {{{{0, 0, 0}}, {{0.7, 0, 0.1}}, {{0.1, 0.9, 0}}, {{0, 0.2, 1.2}}}};
    const double dm_inv[3][3] = {{{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}};
    const double volume = 1.0 / 6.0;
    const double a[3] = {{1.0, 0.0, 0.0}};
{body}
    int bad = q.path != ecc::FibrePath::ClosedI5;
    for (int i = 0; i < 9; ++i) for (int j = 0; j < 9; ++j) bad += q.hess[i][j] != q.hess[j][i];
    for (int i = 0; i < 12; ++i) bad += r.hess[i][i] < 0.0;
    std::printf("%d %.17g %.17g %.17g\n", bad, q.psi, q.i5, r.psi);
    return bad;
}}
"#
    );
    let path = dir.path().join("readme_fibre.cpp");
    std::fs::write(&path, main).expect("write");
    let exe = cpp_common::compile("g++", &path, &[]);
    let out = std::process::Command::new(exe).output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse().expect("number"))
        .collect();
    // I5 = ‖F e0‖² = 0.7² + 0.1², ψ = (I5 − 1)²/2, the element's ψ × volume.
    let i5 = 0.7f64 * 0.7 + 0.1 * 0.1;
    let psi = 0.5 * (i5 - 1.0) * (i5 - 1.0);
    assert!(v[0] == 0.0, "{text}");
    assert!(
        (v[1] - psi).abs() < 1e-15 && (v[2] - i5).abs() < 1e-15,
        "{text}"
    );
    assert!((v[3] - psi / 6.0).abs() < 1e-15, "{text}");
}

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
