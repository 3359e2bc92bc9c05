//! Per-element speed of the emitted C++ (g++ -O3) against the generated Rust,
//! on the same tetrahedra: energy, gradient and Clamp-projected 12×12 Hessian
//! per element (`eval_tet` vs ecc-runtime's `element_eval`), for a few
//! library energies. A measurement, not a check: run it by hand, in release,
//! on a quiet machine:
//!
//! `cargo test --release -p ecc-codegen --test cpp_bench -- --ignored --nocapture`
//!
//! Both sides evaluate the same 4096 random elements (F = R₁ diag(σ) R₂ᵀ,
//! σ ∈ [0.6, 1.5]) in rounds; the best of 5 rounds is reported in ns/element.

mod cpp_common;

use std::time::Instant;

use cpp_common::{lcg, nodes_of, rotation};
use ecc_codegen::{CppOptions, generate_cpp};
use ecc_runtime::{Dim, Filter, Space, element_eval};
use nalgebra::SMatrix;

const ENERGIES: [(&str, &str); 5] = [
    ("arap", "Arap"),
    ("snh", "Snh"),
    ("neohookean", "Neohookean"),
    ("sd3", "Sd3"),
    ("ogden", "Ogden"),
];
const ELEMENTS: usize = 4096;
const REPEAT: usize = 20;
const ROUNDS: usize = 5;

/// Rest and deformed nodes of one tetrahedron.
type Tet = ([[f64; 3]; 4], [[f64; 3]; 4]);

/// (rest nodes, deformed nodes) of the benchmark elements.
fn elements() -> Vec<Tet> {
    let mut st = 42u64;
    (0..ELEMENTS)
        .map(|_| {
            let rest: [[f64; 3]; 4] = [
                [0.0; 3],
                [1.0 + 0.1 * lcg(&mut st), 0.1 * lcg(&mut st), 0.0],
                [0.1 * lcg(&mut st), 1.0 + 0.1 * lcg(&mut st), 0.0],
                [0.1 * lcg(&mut st), 0.1 * lcg(&mut st), 1.0],
            ];
            let s: [f64; 3] = std::array::from_fn(|_| 1.05 + 0.45 * lcg(&mut st));
            let d = SMatrix::<f64, 3, 3>::from_fn(|i, j| if i == j { s[i] } else { 0.0 });
            let f = rotation::<3>(&mut st) * d * rotation::<3>(&mut st).transpose();
            let x = rest.map(|p| {
                let v = f * nalgebra::Vector3::new(p[0], p[1], p[2]);
                [v[0], v[1], v[2]]
            });
            (rest, x)
        })
        .collect()
}

fn rust_ns(stem: &str, els: &[Tet]) -> f64 {
    let e = ecc_energies::by_name::<3>(stem).expect("3D energy");
    let data: Vec<_> = els
        .iter()
        .map(|(r, x)| {
            let rest = <Space<3> as Dim<3>>::rest(&nodes_of::<3>(r)).expect("rest");
            (rest, nodes_of::<3>(x))
        })
        .collect();
    let mut best = f64::INFINITY;
    let mut sink = 0.0;
    for _ in 0..ROUNDS {
        let t = Instant::now();
        for _ in 0..REPEAT {
            for (rest, x) in &data {
                let ev = element_eval(e.as_ref(), rest, x, Filter::Clamp, true);
                sink += ev.psi + ev.hess[(3, 7)];
            }
        }
        best = best.min(t.elapsed().as_secs_f64());
    }
    assert!(sink.is_finite());
    best * 1e9 / (REPEAT * ELEMENTS) as f64
}

fn cpp_program(dir: &std::path::Path) -> std::path::PathBuf {
    let mut src = String::new();
    let mut calls = String::new();
    for (stem, ty) in ENERGIES {
        let path = format!(
            "{}/../../energies/psi/{stem}.psi",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(&path).expect("read");
        let m = ecc_dsl::compile(&text, stem).expect("compile");
        let h = generate_cpp(&m, &CppOptions::named(ty)).expect("emit");
        std::fs::write(dir.join(format!("{stem}.hpp")), h).expect("write");
        src.push_str(&format!("#include \"{stem}.hpp\"\n"));
        calls.push_str(&format!(
            "    std::printf(\"{stem} %.2f\\n\", bench(ecc::energies::{ty}{{}}, xs, dms, vols));\n"
        ));
    }
    src.push_str(&format!(
        r#"#include <chrono>
#include <cstdio>
#include <vector>
template <class E>
double bench(const E& e, const std::vector<std::array<std::array<double, 3>, 4>>& xs,
             const std::vector<std::array<std::array<double, 3>, 3>>& dms, const std::vector<double>& vols) {{
    double best = 1e300, sink = 0.0;
    for (int round = 0; round < {ROUNDS}; ++round) {{
        auto t = std::chrono::steady_clock::now();
        for (int r = 0; r < {REPEAT}; ++r)
            for (size_t k = 0; k < xs.size(); ++k) {{
                double x[4][3], dm[3][3];
                for (int a = 0; a < 4; ++a) for (int b = 0; b < 3; ++b) x[a][b] = xs[k][a][b];
                for (int a = 0; a < 3; ++a) for (int b = 0; b < 3; ++b) dm[a][b] = dms[k][a][b];
                ecc::ElementEval<12> ev = e.eval_tet(x, dm, vols[k], ecc::Filter::clamp());
                sink += ev.psi + ev.hess[3][7];
            }}
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
        if (s < best) best = s;
    }}
    if (!(sink == sink)) std::printf("nan\n");
    return best * 1e9 / ({REPEAT}.0 * xs.size());
}}
#include <array>
int main() {{
    std::vector<std::array<std::array<double, 3>, 4>> xs;
    std::vector<std::array<std::array<double, 3>, 3>> dms;
    std::vector<double> vols;
    std::array<std::array<double, 3>, 4> x;
    std::array<std::array<double, 3>, 3> dm;
    double v;
    while (std::scanf("%lf", &x[0][0]) == 1) {{
        for (int k = 1; k < 12; ++k) std::scanf("%lf", &x[k / 3][k % 3]);
        for (int k = 0; k < 9; ++k) std::scanf("%lf", &dm[k / 3][k % 3]);
        std::scanf("%lf", &v);
        xs.push_back(x); dms.push_back(dm); vols.push_back(v);
    }}
{calls}}}
"#
    ));
    let p = dir.join("bench.cpp");
    std::fs::write(
        &p,
        src.replace("#include <chrono>", "#include <array>\n#include <chrono>"),
    )
    .expect("write");
    p
}

#[test]
#[ignore = "a benchmark: run by hand in release (see the module docs)"]
fn cpp_vs_rust_per_element() {
    let els = elements();
    let dir = tempfile::tempdir().expect("tempdir");
    let src = cpp_program(dir.path());
    let exe = dir.path().join("bench");
    let c = std::process::Command::new("g++")
        .args(["-std=c++17", "-O3", "-DNDEBUG"])
        .arg(&src)
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("g++");
    assert!(c.status.success(), "{}", String::from_utf8_lossy(&c.stderr));
    let mut input = String::new();
    for (r, x) in &els {
        let rest = <Space<3> as Dim<3>>::rest(&nodes_of::<3>(r)).expect("rest");
        for p in x.iter().flatten() {
            input.push_str(&format!("{p:e} "));
        }
        for i in 0..3 {
            for j in 0..3 {
                input.push_str(&format!("{:e} ", rest.dm_inv[(i, j)]));
            }
        }
        input.push_str(&format!("{:e}\n", rest.measure));
    }
    // Interleave C++ and Rust runs and keep each side's best: on a shared
    // machine the load changes during the measurement.
    let mut best: Vec<(f64, f64)> = vec![(f64::INFINITY, f64::INFINITY); ENERGIES.len()];
    for _ in 0..3 {
        let text = run_cpp(&exe, &input);
        for (k, (stem, _)) in ENERGIES.iter().enumerate() {
            let cpp: f64 = text
                .lines()
                .find_map(|l| l.strip_prefix(&format!("{stem} ")))
                .and_then(|v| v.trim().parse().ok())
                .unwrap_or_else(|| panic!("no C++ time for {stem} in {text}"));
            let rust = rust_ns(stem, &els);
            best[k] = (best[k].0.min(rust), best[k].1.min(cpp));
        }
    }
    println!("| energy | Rust ns/element | C++ (g++ -O3) ns/element | C++/Rust |");
    println!("|---|---|---|---|");
    for ((stem, _), (rust, cpp)) in ENERGIES.iter().zip(best) {
        println!("| {stem} | {rust:.1} | {cpp:.1} | {:.2} |", cpp / rust);
    }
}

/// Run the C++ benchmark once; its output.
fn run_cpp(exe: &std::path::Path, input: &str) -> String {
    use std::io::Write;
    let mut child = std::process::Command::new(exe)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("run");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("write");
    let out = child.wait_with_output().expect("output");
    String::from_utf8_lossy(&out.stdout).to_string()
}
