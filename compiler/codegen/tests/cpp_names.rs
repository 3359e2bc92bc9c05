//! Parameter names C++ cannot use as they are (keywords, names with `__`,
//! names of the generated locals and members) become valid, distinct members
//! (`int` → `int_`), the header compiles strictly, and the renamed
//! parameters still act: Ψ at F = 2I equals the formula's value.
//! The same for the fibre part's names (`fibre_parameter_names_…`).

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

/// The fibre part's locals and members (`i4`, `i5`, `sign_i4`, the
/// direction argument `a`, the template parameter `D`, `fibre_uses`) as
/// parameter names: renamed, the header compiles, the values still act.
#[test]
fn fibre_parameter_names_do_not_shadow_the_fibre_locals() {
    let names = ["i4", "i5", "sign_i4", "a", "D", "fibre_uses"];
    // ψ = Σ_k (k+1)·p_k · (I5 − 1)² + I4 with every p_k = 1: at F = 2I with
    // the fibre e0, I5 = 4 and I4 = 2, so ψ = 21 · 9 + 2 = 191.
    let mut src = String::from("fiber n\n");
    let mut terms = Vec::new();
    for (k, n) in names.iter().enumerate() {
        src.push_str(&format!("param {n} = 1\n"));
        terms.push(format!("{}*{n}", k + 1));
    }
    src.push_str(&format!("psi = ({})*(I5 - 1)^2 + I4\n", terms.join(" + ")));
    let m = ecc_dsl::compile(&src, "names")
        .unwrap_or_else(|d| panic!("{}", d.render("names.psi", &src)));
    let h = generate_cpp(&m, &CppOptions::named("Names")).expect("emits");
    for member in ["double i4_ = 1.0;", "double a_ = 1.0;", "double D_ = 1.0;"] {
        assert!(h.contains(member), "no `{member}` in the header");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("names.hpp"), h).expect("write");
    let main = r#"#include "names.hpp"
#include <cstdio>
int main() {
    ecc::energies::Names e;
    const double F[3][3] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    const double a[3] = {1, 0, 0};
    std::printf("%.17g\n", e.fibre_eval(F, a).psi);
    e.i4_ = 2.0;  // adds 1 · 9
    std::printf("%.17g %.17g\n", e.fibre_eval(F, a).psi, e.fibre<3>(2.0, 4.0).psi);
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
    assert_eq!(v, vec![191.0, 200.0, 200.0]);
}
