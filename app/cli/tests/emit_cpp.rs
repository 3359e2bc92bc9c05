//! `ecc FILE.psi --emit cpp [-o out.hpp] [--name T]`: a self-contained C++17
//! header. Standard output and `-o` give the same text; `--name` names the
//! struct; a name C++ cannot use is refused (exit 1, nothing written); and a
//! program built on the emitted header (g++ -Wall -Wextra -Werror) prints the
//! same Ψ, gradient and raw/projected Hessian as `ecc eval --json` (and, for a
//! `.psi` with `fiber a`, the same fibre part as `ecc eval --fiber --json`).

mod common;

use std::process::Command;

use common::{fails, lib, ok};

#[test]
fn stdout_and_output_file_agree_and_name_the_struct() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("my_snh.hpp");
    let text = ok(&[&lib("snh"), "--emit", "cpp", "--name", "MySnh"]);
    assert!(text.contains("struct MySnh {"), "{text}");
    assert!(text.contains("#ifndef ECC_RUNTIME_HPP"), "runtime inlined");
    let quiet = ok(&[
        &lib("snh"),
        "--emit",
        "cpp",
        "--name",
        "MySnh",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(quiet.is_empty());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), text);
    // Default name from the file stem.
    assert!(ok(&[&lib("sd2"), "--emit", "cpp"]).contains("struct Sd2 {"));
}

#[test]
fn a_type_name_cpp_cannot_use_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.hpp");
    let err = fails(&[
        &lib("arap"),
        "--emit",
        "cpp",
        "--name",
        "int",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(err.contains("`int` is not a valid C++ type name"), "{err}");
    assert!(!out.exists(), "nothing written");
}

/// Ψ, gradient, raw and clamped Hessian of the energy at F from the emitted header.
fn cpp_numbers(stem: &str, dim: usize, f: &[f64]) -> Vec<f64> {
    let vals: Vec<String> = f.iter().map(|v| format!("{v:e}")).collect();
    let main = format!(
        r#"#include "energy.hpp"
#include <cstdio>
int main() {{
    const double v[] = {{{vals}}};
    double F[{dim}][{dim}];
    for (int i = 0; i < {dim}; ++i) for (int j = 0; j < {dim}; ++j) F[i][j] = v[i * {dim} + j];
    ecc::energies::E e;
    auto raw = e.eval(F, ecc::Filter::none());
    auto pro = e.eval(F, ecc::Filter::clamp());
    std::printf("%.17g\n", raw.psi);
    for (double g : raw.grad) std::printf("%.17g\n", g);
    for (auto& r : raw.hess) for (double h : r) std::printf("%.17g\n", h);
    for (auto& r : pro.hess) for (double h : r) std::printf("%.17g\n", h);
}}
"#,
        vals = vals.join(", ")
    );
    emit_and_run(stem, &main)
}

/// The numbers (one per line) printed by `main`, a C++ program compiled
/// with g++ -Wall -Wextra -Werror against the header `ecc` emits for `stem`
/// as `energy.hpp` (struct `E`).
fn emit_and_run(stem: &str, main: &str) -> Vec<f64> {
    let dir = tempfile::tempdir().unwrap();
    let hpp = dir.path().join("energy.hpp");
    ok(&[
        &lib(stem),
        "--emit",
        "cpp",
        "--name",
        "E",
        "-o",
        hpp.to_str().unwrap(),
    ]);
    let src = dir.path().join("main.cpp");
    std::fs::write(&src, main).unwrap();
    let exe = dir.path().join("main");
    let c = Command::new("g++")
        .args(["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(&src)
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("g++ runs (.ci/run installs it)");
    assert!(
        c.status.success(),
        "{stem}: {}",
        String::from_utf8_lossy(&c.stderr)
    );
    let out = Command::new(&exe).output().unwrap();
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect()
}

/// Every value of the C++ output within 1e-10 × the largest of `ecc eval`'s.
fn assert_agree(stem: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{stem}");
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (k, (a, b)) in got.iter().zip(want).enumerate() {
        assert!(
            (a - b).abs() <= 1e-10 * scale,
            "{stem} value {k}: C++ {a}, ecc eval {b}"
        );
    }
}

fn json_numbers(stem: &str, dim: usize, f: &[f64]) -> Vec<f64> {
    let rows: Vec<String> = f
        .chunks(dim)
        .map(|r| {
            r.iter()
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let text = ok(&[
        "eval",
        &lib(stem),
        "--dim",
        &dim.to_string(),
        "--F",
        &rows.join("; "),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut out = vec![v["psi"].as_f64().unwrap()];
    let flat = |x: &serde_json::Value| -> Vec<f64> {
        match x {
            serde_json::Value::Array(a) => a
                .iter()
                .flat_map(|e| match e {
                    serde_json::Value::Array(r) => r.iter().map(|y| y.as_f64().unwrap()).collect(),
                    y => vec![y.as_f64().unwrap()],
                })
                .collect(),
            _ => panic!("not an array"),
        }
    };
    out.extend(flat(&v["gradient"]));
    out.extend(flat(&v["hessian"]));
    out.extend(flat(&v["hessian_projected"]));
    out
}

#[test]
fn emitted_header_agrees_with_ecc_eval() {
    let cases: [(&str, usize, Vec<f64>); 4] = [
        ("snh", 3, vec![1.2, 0.1, 0.0, 0.0, 0.9, 0.1, 0.05, 0.0, 1.1]),
        (
            "ogden",
            3,
            vec![1.1, 0.2, 0.0, -0.1, 0.8, 0.0, 0.0, 0.1, 1.3],
        ),
        ("sd2", 2, vec![1.3, 0.2, -0.1, 0.7]),
        ("arap", 2, vec![0.9, 0.4, -0.3, -0.2]),
    ];
    for (stem, dim, f) in cases {
        let got = cpp_numbers(stem, dim, &f);
        let want = json_numbers(stem, dim, &f);
        assert_agree(stem, &got, &want);
    }
}

/// The C++ example (examples/cpp: projected Newton with Eigen's SimplicialLLT
/// on the emitted SD header) reaches the same final energy on camelhead as
/// `ecc sim scenes/camelhead_sd.toml`. Needs Eigen (libeigen3-dev); ~30 s in
/// a debug build, so run by hand:
/// `cargo test -p ecc-cli --test emit_cpp -- --ignored`.
#[test]
#[ignore = "builds the C++ example with Eigen and runs two solves on camelhead (~30 s)"]
fn cpp_example_reaches_the_rust_final_energy() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = tempfile::tempdir().unwrap();
    let hpp = dir.path().join("sd2.hpp");
    ok(&[&lib("sd2"), "--emit", "cpp", "-o", hpp.to_str().unwrap()]);
    let exe = dir.path().join("param_sd");
    let c = Command::new("g++")
        .args([
            "-std=c++17",
            "-O2",
            "-DNDEBUG",
            "-Wall",
            "-Wextra",
            "-Werror",
        ])
        .arg("-I")
        .arg(dir.path())
        .arg("-I/usr/include/eigen3")
        .arg(root.join("examples/cpp/param_sd.cpp"))
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("g++");
    assert!(c.status.success(), "{}", String::from_utf8_lossy(&c.stderr));
    let run = Command::new(&exe)
        .arg(root.join("data/camelhead.off"))
        .output()
        .unwrap();
    assert!(run.status.success(), "the C++ example did not converge");
    let text = String::from_utf8(run.stdout).unwrap();
    let last = text.lines().last().unwrap();
    let cpp: f64 = last.split_whitespace().nth(1).unwrap().parse().unwrap();
    let out = dir.path().join("sim");
    let json = ok(&[
        "sim",
        root.join("scenes/camelhead_sd.toml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "-q",
        "--json",
        "--no-pictures",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let rust = v["final_energy"].as_f64().unwrap();
    assert!(
        (cpp - rust).abs() <= 1e-6 * rust,
        "C++ example {cpp} vs ecc sim {rust}"
    );
    assert!(last.contains("flipped 0"), "{last}");
}

/// A `.psi` with `fiber a` emits too (#16): the header's `fibre_eval` gives
/// the same ψ, I5, gradient and raw-Hessian trace (the eigenvalue sum) as
/// `ecc eval --fiber --json`, for a closed-form (StVK) and an I4 (ARAP) energy.
#[test]
fn fibre_energies_emit_and_agree_with_ecc_eval() {
    let f = [1.2, 0.1, 0.0, 0.0, 0.9, 0.1, 0.05, 0.0, 1.1];
    let dir_a = [1.0, 0.5, 0.2];
    for stem in ["fibre_stvk", "fibre_arap"] {
        let main = format!(
            r#"#include "energy.hpp"
#include <cmath>
#include <cstdio>
int main() {{
    const double v[] = {{{f}}};
    double F[3][3], a[3] = {{{a}}};
    for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) F[i][j] = v[i * 3 + j];
    double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (double& x : a) x /= n;
    ecc::energies::E e;
    auto p = e.fibre_eval(F, a, ecc::Filter::none());
    double tr = 0.0;
    for (int i = 0; i < 9; ++i) tr += p.hess[i][i];
    std::printf("%.17g\n%.17g\n", p.psi, p.i5);
    for (double g : p.grad) std::printf("%.17g\n", g);
    std::printf("%.17g\n", tr);
}}
"#,
            f = f.map(|x| x.to_string()).join(", "),
            a = dir_a.map(|x| x.to_string()).join(", "),
        );
        let got = emit_and_run(stem, &main);
        let text = ok(&[
            "eval",
            &lib(stem),
            "--dim",
            "3",
            "--F",
            "1.2 0.1 0; 0 0.9 0.1; 0.05 0 1.1",
            "--fiber",
            "1 0.5 0.2",
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let fib = &v["fibre"];
        let num = |x: &serde_json::Value| x.as_f64().unwrap();
        let mut want = vec![num(&fib["psi"]), num(&fib["I5"])];
        want.extend(fib["gradient"].as_array().unwrap().iter().map(num));
        want.push(fib["eigenvalues"].as_array().unwrap().iter().map(num).sum());
        assert_agree(stem, &got, &want);
    }
}
