//! The optional Eigen adapter (`compiler/codegen/cpp/ecc_eigen.hpp`, Debian
//! `libeigen3-dev`, installed by `.ci/run`) compiles strictly with an emitted
//! header and returns exactly what the array entry points return (F-space
//! and element versions, 2D and 3D; the isotropic and the fibre part).

mod cpp_common;

use ecc_codegen::cpp::CPP_EIGEN_ADAPTER;
use ecc_codegen::{CppOptions, generate_cpp};

const EIGEN: &str = "/usr/include/eigen3";

const MAIN: &str = r#"#include "snh.hpp"
#include "ecc_eigen.hpp"
#include <cstdio>
int main() {
    ecc::energies::Snh e;
    int bad = 0;
    Eigen::Matrix3d F;
    F << 1.1, 0.1, 0.0, 0.0, 0.9, 0.2, 0.1, 0.0, -1.2;
    double Fa[3][3];
    ecc::eigen::to_array<3>(F, Fa);
    auto a = e.eval(Fa, ecc::Filter::abs());
    auto b = ecc::eigen::eval<3>(e, F, ecc::Filter::abs());
    bad += a.psi != b.psi;
    for (int i = 0; i < 9; ++i) {
        bad += a.grad[i] != b.grad(i);
        for (int j = 0; j < 9; ++j) bad += a.hess[i][j] != b.hess(i, j);
    }
    Eigen::Matrix<double, 2, 3> x;
    x << 0.0, 1.1, 0.2, 0.0, 0.1, 0.8;
    Eigen::Matrix2d dm_inv;
    dm_inv << 1.0, -0.1, 0.0, 1.0;
    double xa[3][2] = {{0.0, 0.0}, {1.1, 0.1}, {0.2, 0.8}}, da[2][2] = {{1.0, -0.1}, {0.0, 1.0}};
    auto c = e.eval_tri(xa, da, 0.5);
    auto d = ecc::eigen::eval_element<2>(e, x, dm_inv, 0.5);
    bad += c.psi != d.psi;
    for (int i = 0; i < 6; ++i) {
        bad += c.grad[i] != d.grad(i);
        for (int j = 0; j < 6; ++j) bad += c.hess[i][j] != d.hess(i, j);
    }
    std::printf("%d %g %g\n", bad, a.psi, c.psi);
    return bad;
}
"#;

/// The fibre adapters against the array entry points (a ψ with I4 terms,
/// so the numeric block, and an inverted F).
const FIBRE_MAIN: &str = r#"#include "mixed.hpp"
#include "ecc_eigen.hpp"
#include <cstdio>
int main() {
    ecc::energies::Mixed e;
    int bad = 0;
    Eigen::Matrix3d F;
    F << 1.1, 0.1, 0.0, 0.0, 0.9, 0.2, 0.1, 0.0, -1.2;
    Eigen::Vector3d a(0.48, 0.6, 0.64);
    double Fa[3][3], av[3] = {0.48, 0.6, 0.64};
    ecc::eigen::to_array<3>(F, Fa);
    auto p = e.fibre_eval(Fa, av, ecc::Filter::abs());
    auto q = ecc::eigen::fibre_eval<3>(e, F, a, ecc::Filter::abs());
    bad += p.psi != q.psi || p.i4 != q.i4 || p.i5 != q.i5 || p.path != q.path;
    bad += p.path != ecc::FibrePath::Numeric;
    for (int i = 0; i < 9; ++i) {
        bad += p.grad[i] != q.grad(i);
        for (int j = 0; j < 9; ++j) bad += p.hess[i][j] != q.hess(i, j);
    }
    Eigen::Matrix<double, 2, 3> x;
    x << 0.0, 1.1, 0.2, 0.0, 0.1, 0.8;
    Eigen::Matrix2d dm_inv;
    dm_inv << 1.0, -0.1, 0.0, 1.0;
    Eigen::Vector2d a2(0.8, 0.6);
    double xa[3][2] = {{0.0, 0.0}, {1.1, 0.1}, {0.2, 0.8}}, da[2][2] = {{1.0, -0.1}, {0.0, 1.0}};
    double a2v[2] = {0.8, 0.6};
    auto c = e.fibre_eval_tri(xa, da, 0.5, a2v);
    auto d = ecc::eigen::fibre_eval_element<2>(e, x, dm_inv, 0.5, a2);
    bad += c.psi != d.psi;
    for (int i = 0; i < 6; ++i) {
        bad += c.grad[i] != d.grad(i);
        for (int j = 0; j < 6; ++j) bad += c.hess[i][j] != d.hess(i, j);
    }
    std::printf("%d %g %g\n", bad, p.psi, c.psi);
    return bad;
}
"#;

#[test]
fn eigen_adapter_matches_the_array_entry_points() {
    assert!(
        std::path::Path::new(EIGEN).join("Eigen/Core").exists(),
        "Eigen 3 is needed at {EIGEN} (apt-get install libeigen3-dev; .ci/run does it)"
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
    std::fs::write(dir.path().join("ecc_eigen.hpp"), CPP_EIGEN_ADAPTER).expect("write");
    let path = dir.path().join("eigen.cpp");
    std::fs::write(&path, MAIN).expect("write");
    let exe = cpp_common::compile("g++", &path, &["-isystem", EIGEN]);
    let out = std::process::Command::new(exe).output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "adapter and arrays differ: {text}");
    assert!(text.starts_with("0 "), "{text}");
}

#[test]
fn eigen_fibre_adapter_matches_the_array_entry_points() {
    let dir = tempfile::tempdir().expect("tempdir");
    let src = "fiber a\npsi = (I4 - 1)^2 + 0.3*(I5 - 1)^2 - 0.2*I4*I5\n";
    let m = ecc_dsl::compile(src, "mixed").expect("compiles");
    let h = generate_cpp(&m, &CppOptions::named("Mixed")).expect("emits");
    std::fs::write(dir.path().join("mixed.hpp"), h).expect("write");
    std::fs::write(dir.path().join("ecc_eigen.hpp"), CPP_EIGEN_ADAPTER).expect("write");
    let path = dir.path().join("eigen_fibre.cpp");
    std::fs::write(&path, FIBRE_MAIN).expect("write");
    let exe = cpp_common::compile("g++", &path, &["-isystem", EIGEN]);
    let out = std::process::Command::new(exe).output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "adapter and arrays differ: {text}");
    assert!(text.starts_with("0 "), "{text}");
}
