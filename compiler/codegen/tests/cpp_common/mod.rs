//! Shared by the C++ back-end tests: emit headers, write one driver program
//! for a set of energies, compile it once per compiler (g++, and clang++ when
//! present) with `-std=c++17 -O2 -Wall -Wextra -Werror`, feed it deformation
//! gradients on stdin and compare what it prints with the Rust side.
//!
//! Driver protocol, one case per line:
//! `energy_index dim F(d², row-major) Dm⁻¹(d², row-major) measure x((d+1)·d)`;
//! the answer line: Ψ, vec(∂Ψ/∂F), the d²×d² Hessian for each filter of
//! [`FILTERS`], then the element Ψ, gradient and Hessian for each filter.

#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use ecc_codegen::{CppOptions, CppRuntime, generate_cpp};
use ecc_runtime::{Dim, Energy, Filter, Space, element_eval, gradient_f, hessian_f, signed_svd};
use nalgebra::SMatrix;

/// The filters every case is evaluated with, in driver order.
pub const FILTERS: [Filter; 4] = [
    Filter::None,
    Filter::Clamp,
    Filter::Abs,
    Filter::ClampEps(1e-3),
];

const FILTERS_CPP: &str =
    "{ecc::Filter::none(), ecc::Filter::clamp(), ecc::Filter::abs(), ecc::Filter::clamp_eps(1e-3)}";

/// The C++ compilers to test with: g++ (required) and clang++ if installed.
pub fn compilers() -> Vec<String> {
    let mut out = Vec::new();
    for c in ["g++", "clang++"] {
        let ok = Command::new(c)
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if ok {
            out.push(c.to_string());
        } else {
            eprintln!("note: {c} not found, not tested with it");
        }
    }
    assert!(
        out.iter().any(|c| c == "g++"),
        "g++ is required for the C++ back-end tests (.ci/run installs it)"
    );
    out
}

/// One energy of a driver: its C++ type and the dimensions it has.
pub struct DriverEnergy {
    pub type_name: String,
    pub dims: Vec<u8>,
}

/// Emit the headers of `modules` into `dir` (runtime inlined in each, so
/// including them together also checks the include guards), write the
/// driver and return its path.
pub fn write_driver(
    dir: &Path,
    modules: &[(ecc_dsl::Module, String)],
) -> (PathBuf, Vec<DriverEnergy>) {
    let mut includes = String::new();
    let mut cases = String::new();
    let mut energies = Vec::new();
    for (k, (module, ty)) in modules.iter().enumerate() {
        let opts = CppOptions {
            type_name: ty.clone(),
            energy_name: None,
            runtime: CppRuntime::Inline,
        };
        let text = generate_cpp(module, &opts).unwrap_or_else(|e| panic!("{}: {e}", module.name));
        let file = format!("{}.hpp", ty.to_lowercase());
        std::fs::write(dir.join(&file), text).expect("write header");
        includes.push_str(&format!("#include \"{file}\"\n"));
        let dims: Vec<u8> = module.dims.iter().map(|d| d.dim).collect();
        for &d in &dims {
            cases.push_str(&format!(
                "        if (idx == {k} && dim == {d}) {{ run<{d}>(ecc::energies::{ty}{{}}, in); continue; }}\n"
            ));
        }
        energies.push(DriverEnergy {
            type_name: ty.clone(),
            dims,
        });
    }
    let src = format!(
        r#"{includes}
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

static void put(double x) {{
    if (std::isnan(x)) std::printf(" nan");
    else if (std::isinf(x)) std::printf(x > 0 ? " inf" : " -inf");
    else std::printf(" %.17g", x);
}}

template <int D, class E>
static void run(const E& e, std::istringstream& in) {{
    constexpr int N = D * D, K = D + 1, NE = D * K;
    double F[D][D], dm[D][D], x[K][D], measure;
    for (auto& r : F) for (double& v : r) in >> v;
    for (auto& r : dm) for (double& v : r) in >> v;
    in >> measure;
    for (auto& r : x) for (double& v : r) in >> v;
    const ecc::Filter filters[4] = {FILTERS_CPP};
    for (int f = 0; f < 4; ++f) {{
        ecc::PointEval<D> p = e.eval(F, filters[f]);
        if (f == 0) {{ put(p.psi); for (int i = 0; i < N; ++i) put(p.grad[i]); }}
        for (int i = 0; i < N; ++i) for (int j = 0; j < N; ++j) put(p.hess[i][j]);
    }}
    for (int f = 0; f < 4; ++f) {{
        ecc::ElementEval<NE> r;
        if constexpr (D == 2) r = e.eval_tri(x, dm, measure, filters[f]);
        else r = e.eval_tet(x, dm, measure, filters[f]);
        put(r.psi);
        for (int i = 0; i < NE; ++i) put(r.grad[i]);
        for (int i = 0; i < NE; ++i) for (int j = 0; j < NE; ++j) put(r.hess[i][j]);
    }}
    std::printf("\n");
}}

int main() {{
    std::string line;
    while (std::getline(std::cin, line)) {{
        std::istringstream in(line);
        int idx = -1, dim = 0;
        in >> idx >> dim;
{cases}        std::printf("unknown %d %d\n", idx, dim);
    }}
    return 0;
}}
"#,
        FILTERS_CPP = FILTERS_CPP
    );
    let path = dir.join("driver.cpp");
    std::fs::write(&path, src).expect("write driver");
    (path, energies)
}

/// Compile `src` with `compiler` (strict flags); the executable's path.
pub fn compile(compiler: &str, src: &Path, extra: &[&str]) -> PathBuf {
    let exe = src.with_file_name(format!(
        "{}_{}",
        src.file_stem().and_then(|s| s.to_str()).unwrap_or("a"),
        compiler.replace('+', "p")
    ));
    let out = Command::new(compiler)
        .args(["-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror"])
        .args(extra)
        .arg(src)
        .arg("-o")
        .arg(&exe)
        .output()
        .unwrap_or_else(|e| panic!("{compiler}: {e}"));
    assert!(
        out.status.success(),
        "{compiler} failed on {}:\n{}",
        src.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

/// Run `exe` with `input` on stdin; its output lines as numbers.
pub fn run(exe: &Path, input: &str) -> Vec<Vec<f64>> {
    let mut child = Command::new(exe)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run driver");
    let mut stdin = child.stdin.take().expect("stdin");
    let data = input.to_string();
    let writer = std::thread::spawn(move || stdin.write_all(data.as_bytes()));
    let out = child.wait_with_output().expect("driver output");
    writer.join().expect("writer").expect("write stdin");
    assert!(out.status.success(), "driver exited with {}", out.status);
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| {
            assert!(!l.starts_with("unknown"), "driver: {l}");
            l.split_whitespace()
                .map(|t| {
                    t.parse::<f64>()
                        .unwrap_or_else(|_| panic!("bad number {t}"))
                })
                .collect()
        })
        .collect()
}

/// Whether two numbers agree: both non-finite the same way, or within
/// `tol`·`scale` (the scale of the quantity they belong to).
pub fn close(a: f64, b: f64, tol: f64, scale: f64) -> bool {
    if !a.is_finite() || !b.is_finite() {
        return (a.is_nan() && b.is_nan()) || a == b;
    }
    (a - b).abs() <= tol * scale.max(f64::MIN_POSITIVE)
}

/// Compare `got` (C++) with `want` (Rust) block by block (blocks of the given
/// lengths, each relative to its own largest finite |entry|); the worst
/// relative error, or a message naming the first disagreement.
pub fn compare(
    got: &[f64],
    want: &[f64],
    blocks: &[(String, usize)],
    tol: f64,
) -> Result<f64, String> {
    if got.len() != want.len() {
        return Err(format!("{} numbers, expected {}", got.len(), want.len()));
    }
    let mut at = 0;
    let mut worst = 0.0f64;
    for (name, len) in blocks {
        let (g, w) = (&got[at..at + len], &want[at..at + len]);
        let scale = w
            .iter()
            .filter(|x| x.is_finite())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        compare_block(name, g, w, tol, scale, &mut worst)?;
        at += len;
    }
    Ok(worst)
}

/// One block: every C++ value `close` to Rust's relative to `scale`;
/// `worst` grows to the largest finite relative difference.
pub fn compare_block(
    name: &str,
    got: &[f64],
    want: &[f64],
    tol: f64,
    scale: f64,
    worst: &mut f64,
) -> Result<(), String> {
    for (k, (&a, &b)) in got.iter().zip(want).enumerate() {
        if !close(a, b, tol, scale) {
            return Err(format!(
                "{name}[{k}]: C++ {a:e}, Rust {b:e} (scale {scale:e})"
            ));
        }
        if a.is_finite() && scale > 0.0 {
            *worst = worst.max((a - b).abs() / scale);
        }
    }
    Ok(())
}

/// The block layout of one answer line in dimension `d`.
pub fn blocks(d: usize) -> Vec<(String, usize)> {
    let (n, ne) = (d * d, d * (d + 1));
    let mut b = vec![("psi".to_string(), 1), ("grad_f".to_string(), n)];
    for f in FILTERS {
        b.push((format!("hess_f {f:?}"), n * n));
    }
    for f in FILTERS {
        b.push((format!("elem psi {f:?}"), 1));
        b.push((format!("elem grad {f:?}"), ne));
        b.push((format!("elem hess {f:?}"), ne * ne));
    }
    b
}

/// One case: F, and the rest/deformed nodes of an element with that F.
pub struct Case<const D: usize> {
    pub f: SMatrix<f64, D, D>,
    pub rest_nodes: Vec<[f64; D]>,
    pub x: Vec<[f64; D]>,
}

pub fn nums<const D: usize>(m: &SMatrix<f64, D, D>) -> String {
    (0..D)
        .flat_map(|i| (0..D).map(move |j| (i, j)))
        .map(|(i, j)| format!("{:e}", m[(i, j)]))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The driver's input line for `case` and the Rust answer for it.
pub fn rust_line<const D: usize>(
    e: &dyn Energy<D>,
    idx: usize,
    case: &Case<D>,
) -> (String, Vec<f64>)
where
    Space<D>: Dim<D>,
{
    let nodes = |v: &[[f64; D]]| -> <Space<D> as Dim<D>>::Nodes { nodes_of::<D>(v) };
    let rest = <Space<D> as Dim<D>>::rest(&nodes(&case.rest_nodes)).expect("rest element");
    let x = nodes(&case.x);
    let xs: Vec<String> = case.x.iter().flatten().map(|v| format!("{v:e}")).collect();
    let input = format!(
        "{idx} {D} {} {} {:e} {}\n",
        nums(&case.f),
        nums(&rest.dm_inv),
        rest.measure,
        xs.join(" ")
    );
    let svd = signed_svd(&case.f);
    let s = e.spectral(&svd.sigma);
    let n = D * D;
    let mut want = vec![s.psi];
    let g = gradient_f(&svd, &s);
    want.extend((0..n).map(|i| g[i]));
    for f in FILTERS {
        let h = hessian_f(&svd, &s, f);
        want.extend(
            (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .map(|ij| h[ij]),
        );
    }
    let ne = D * (D + 1);
    for f in FILTERS {
        let ev = element_eval(e, &rest, &x, f, true);
        want.push(ev.psi);
        want.extend((0..ne).map(|i| ev.grad[i]));
        want.extend(
            (0..ne)
                .flat_map(|i| (0..ne).map(move |j| (i, j)))
                .map(|ij| ev.hess[ij]),
        );
    }
    (input, want)
}

pub fn nodes_of<const D: usize>(v: &[[f64; D]]) -> <Space<D> as Dim<D>>::Nodes
where
    Space<D>: Dim<D>,
{
    // Nodes<D> is [[f64; D]; D + 1]; build it through the 2D/3D arrays.
    let any: Box<dyn std::any::Any> = if D == 2 {
        let a: [[f64; 2]; 3] = std::array::from_fn(|k| std::array::from_fn(|i| v[k][i]));
        Box::new(a)
    } else {
        let a: [[f64; 3]; 4] = std::array::from_fn(|k| std::array::from_fn(|i| v[k][i]));
        Box::new(a)
    };
    *any.downcast::<<Space<D> as Dim<D>>::Nodes>()
        .unwrap_or_else(|_| panic!("Nodes<{D}> is [[f64; D]; D + 1]"))
}

/// Deterministic numbers in [−1, 1).
pub fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// A random rotation (2D angle, 3D unit quaternion).
pub fn rotation<const D: usize>(st: &mut u64) -> SMatrix<f64, D, D> {
    if D == 2 {
        let a = std::f64::consts::PI * lcg(st);
        SMatrix::from_fn(|i, j| match (i, j) {
            (0, 0) | (1, 1) => a.cos(),
            (0, 1) => -a.sin(),
            _ => a.sin(),
        })
    } else {
        let q: [f64; 4] = std::array::from_fn(|_| lcg(st));
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
        let r = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        SMatrix::from_fn(|i, j| r[i][j])
    }
}
