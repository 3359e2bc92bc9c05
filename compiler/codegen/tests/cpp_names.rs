//! Parameter names C++ cannot use as they are (keywords, names with `__`,
//! names of the generated locals and members) become valid, distinct members
//! (`int` → `int_`), the header compiles strictly, and the renamed
//! parameters still act: Ψ at F = 2I equals the formula's value.

mod cpp_common;

use ecc_codegen::{CppOptions, generate_cpp};

#[test]
fn awkward_parameter_names_compile_and_keep_their_values() {
    let names = [
        "int", "a__b", "sigma", "F", "out", "psi_s1", "name", "double",
    ];
    // Ψ = Σ_k (k+1)·p_k · I2 with every parameter defaulting to 1: at F = 2I in
    // 3D, I2 = 12 and Ψ = 12 · Σ (k+1) = 12 · 36 = 432.
    let mut src = String::new();
    let mut terms = Vec::new();
    for (k, n) in names.iter().enumerate() {
        src.push_str(&format!("param {n} = 1\n"));
        terms.push(format!("{}*{n}", k + 1));
    }
    src.push_str(&format!("psi = ({})*I2\n", terms.join(" + ")));
    let m = ecc_dsl::compile(&src, "names")
        .unwrap_or_else(|d| panic!("{}", d.render("names.psi", &src)));
    let h = generate_cpp(&m, &CppOptions::named("Names")).expect("emits");
    for member in [
        "double int_ = 1.0;",
        "double a_b = 1.0;",
        "double double_ = 1.0;",
    ] {
        assert!(h.contains(member), "no `{member}` in the header");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("names.hpp"), h).expect("write");
    let main = r#"#include "names.hpp"
#include <cstdio>
int main() {
    ecc::energies::Names e;
    const double F[3][3] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    std::printf("%.17g\n", e.eval(F).psi);
    e.int_ = 2.0;  // adds 1 · 12
    std::printf("%.17g\n", e.eval(F).psi);
}
"#;
    let path = dir.path().join("main.cpp");
    std::fs::write(&path, main).expect("write");
    let exe = cpp_common::compile("g++", &path, &[]);
    let out = std::process::Command::new(exe).output().expect("runs");
    let v: Vec<f64> = String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .map(|t| t.parse().expect("number"))
        .collect();
    assert_eq!(v, vec![432.0, 444.0]);
}
