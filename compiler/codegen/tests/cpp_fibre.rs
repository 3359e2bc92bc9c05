//! The emitted C++ of fibre energies ψ(I4, I5) (`fiber a`) compiles with the
//! strict flags (g++, and clang++ when installed) and agrees with the Rust
//! runtime (`ecc_runtime::fibre::{fibre_f, fibre_element_eval}` on the
//! generated library energies of ecc-energies, and on the interpreter for
//! the test energies below) to 10⁻¹⁰ relative (per block; a filtered Hessian
//! relative to the raw one it filters, see [`compare`]) on: ψ, I4, I5,
//! vec(∂ψ/∂F), the d²×d² Hessian under the four filters, the element energy,
//! gradient and Hessians, ψ alone, and which eigensystem was used (closed form
//! ⇔ closed form). Library: fibre_arap, fibre_stvk, fibre_fung; test energies:
//! a mixed I4 + I5 ψ with an isotropic part, an I4-only ψ and a ψ with a
//! log(I5) domain (+∞ at F a = 0).
//!
//! Hard points, each in 2D and 3D, for a generic fibre and one along a
//! singular axis, also under random rotations: rest, a generic F, F a ≈ 0 and
//! F a = 0, I4 just below and just above 0, inversion along and across the
//! fibre, tiny σ, huge stretch, σi + σj near 0 and exactly 0, a non-finite F.

mod cpp_common;

use cpp_common::{Case, compare_block, compile, compilers, nodes_of, nums, rotation, run};
use ecc_codegen::{CppOptions, generate_cpp};
use ecc_runtime::fibre::{
    FibreDim, FibrePath, fibre_element_eval, fibre_f, invariant4, invariant5,
};
use ecc_runtime::{Dim, FibreEnergy, FibreUse, Filter, Space};
use nalgebra::{SMatrix, SVector};

/// Agreement required between C++ and Rust (relative to each block's scale).
const TOL: f64 = 1e-10;

const FILTERS: [Filter; 4] = [
    Filter::None,
    Filter::Clamp,
    Filter::Abs,
    Filter::ClampEps(1e-3),
];

/// Test energies beyond the library: (name, source).
const TEST_ENERGIES: [(&str, &str); 3] = [
    (
        "fibre_mixed",
        "fiber a\nparam mu = 0.7\npsi = mu/2*(I2 - d) + (I4 - 1)^2 + 0.3*(I5 - 1)^2 - 0.2*I4*I5\n",
    ),
    (
        "fibre_i4",
        "fiber a\nparam k = 1.5\npsi = k*(I4 - 1)^2 + 0.1*I4^3\n",
    ),
    (
        "fibre_log",
        "fiber a\nparam k = 2.0\npsi = k/2*(I5 - 1 - log(I5))\n",
    ),
];

const LIBRARY: [&str; 3] = ["fibre_arap", "fibre_stvk", "fibre_fung"];

/// (module, C++ type, library energy?) for every energy tested.
fn modules() -> Vec<(ecc_dsl::Module, String, bool)> {
    let dir = format!("{}/../../energies/psi", env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for stem in LIBRARY {
        let path = format!("{dir}/{stem}.psi");
        let src = std::fs::read_to_string(&path).expect("read");
        let m =
            ecc_dsl::compile(&src, stem).unwrap_or_else(|d| panic!("{}", d.render(&path, &src)));
        out.push((m, ecc_codegen::type_name_from_stem(stem), true));
    }
    for (name, src) in TEST_ENERGIES {
        let m = ecc_dsl::compile(src, name).unwrap_or_else(|d| panic!("{}", d.render(name, src)));
        out.push((m, ecc_codegen::type_name_from_stem(name), false));
    }
    for (m, _, _) in &out {
        assert!(m.dims.iter().all(|d| d.fibre.is_some()), "{}", m.name);
    }
    out
}

/// The Rust fibre energy of a module: generated (library) or interpreted.
fn rust_energy<const D: usize>(m: &ecc_dsl::Module, lib: bool) -> Box<dyn FibreEnergy<D>> {
    if lib {
        ecc_energies::fibre_by_name::<D>(&m.name).expect("library fibre energy")
    } else {
        Box::new(
            ecc_interp::fibre_from_module::<D>(m, &m.name, &[])
                .expect("interpreted")
                .expect("has a fibre part"),
        )
    }
}

fn driver(dir: &std::path::Path, mods: &[(ecc_dsl::Module, String, bool)]) -> std::path::PathBuf {
    let mut includes = String::new();
    let mut dispatch = String::new();
    for (k, (m, ty, _)) in mods.iter().enumerate() {
        let text = generate_cpp(m, &CppOptions::named(ty.clone()))
            .unwrap_or_else(|e| panic!("{}: {e}", m.name));
        let file = format!("{}.hpp", ty.to_lowercase());
        std::fs::write(dir.join(&file), text).expect("write header");
        includes.push_str(&format!("#include \"{file}\"\n"));
        for d in [2, 3] {
            dispatch.push_str(&format!(
                "        if (idx == {k} && dim == {d}) {{ run<{d}>(ecc::energies::{ty}{{}}, in); continue; }}\n"
            ));
        }
    }
    let src = format!(
        r#"{includes}
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

/// One number; strtod reads nan and inf, which `>>` does not.
static double num(std::istringstream& in) {{
    std::string t;
    in >> t;
    return std::strtod(t.c_str(), nullptr);
}}

static void put(double x) {{
    if (std::isnan(x)) std::printf(" nan");
    else if (std::isinf(x)) std::printf(x > 0 ? " inf" : " -inf");
    else std::printf(" %.17g", x);
}}

template <int D, class E>
static void run(const E& e, std::istringstream& in) {{
    constexpr int N = D * D, K = D + 1, NE = D * K;
    double F[D][D], a[D], dm[D][D], x[K][D], measure;
    for (auto& r : F) for (double& v : r) v = num(in);
    for (double& v : a) v = num(in);
    for (auto& r : dm) for (double& v : r) v = num(in);
    measure = num(in);
    for (auto& r : x) for (double& v : r) v = num(in);
    const ecc::Filter filters[4] = {{ecc::Filter::none(), ecc::Filter::clamp(), ecc::Filter::abs(),
                                     ecc::Filter::clamp_eps(1e-3)}};
    for (int f = 0; f < 4; ++f) {{
        ecc::FibreEval<D> p = e.fibre_eval(F, a, filters[f]);
        if (f == 1) {{
            put(p.psi); put(p.i4); put(p.i5);
            for (int i = 0; i < N; ++i) put(p.grad[i]);
            put(p.path == ecc::FibrePath::Degenerate ? 0.0 : p.path == ecc::FibrePath::ClosedI5 ? 1.0 : 2.0);
        }}
        for (int i = 0; i < N; ++i) for (int j = 0; j < N; ++j) put(p.hess[i][j]);
    }}
    for (int f = 0; f < 4; ++f) {{
        ecc::ElementEval<NE> r;
        if constexpr (D == 2) r = e.fibre_eval_tri(x, dm, measure, a, filters[f]);
        else r = e.fibre_eval_tet(x, dm, measure, a, filters[f]);
        put(r.psi);
        for (int i = 0; i < NE; ++i) put(r.grad[i]);
        for (int i = 0; i < NE; ++i) for (int j = 0; j < NE; ++j) put(r.hess[i][j]);
    }}
    put(e.fibre_psi_f(F, a));
    put(ecc::fibre_invariant4<D>(F, a));
    put(ecc::fibre_invariant5<D>(F, a));
    std::printf("\n");
}}

int main() {{
    std::string line;
    while (std::getline(std::cin, line)) {{
        std::istringstream in(line);
        int idx = -1, dim = 0;
        in >> idx >> dim;
{dispatch}        std::printf("unknown %d %d\n", idx, dim);
    }}
    return 0;
}}
"#
    );
    let path = dir.join("fibre_driver.cpp");
    std::fs::write(&path, src).expect("write driver");
    path
}

/// The block layout of one answer line in dimension `d`: the raw Hessian,
/// then (with `Filter::Clamp`) ψ, I4, I5, the gradient and the path, then
/// the filtered Hessians, the element blocks and ψ alone.
fn blocks(d: usize) -> Vec<(String, usize)> {
    let (n, ne) = (d * d, d * (d + 1));
    let mut b = vec![];
    for (k, f) in FILTERS.into_iter().enumerate() {
        if k == 1 {
            b.push(("psi".to_string(), 1));
            b.push(("i4".to_string(), 1));
            b.push(("i5".to_string(), 1));
            b.push(("grad_f".to_string(), n));
            b.push(("path".to_string(), 1));
        }
        b.push((format!("hess_f {f:?}"), n * n));
    }
    for f in FILTERS {
        b.push((format!("elem psi {f:?}"), 1));
        b.push((format!("elem grad {f:?}"), ne));
        b.push((format!("elem hess {f:?}"), ne * ne));
    }
    b.push(("psi_f".to_string(), 1));
    b.push(("invariant4".to_string(), 1));
    b.push(("invariant5".to_string(), 1));
    b
}

/// A unit vector of `v`.
fn unit<const D: usize>(v: [f64; D]) -> SVector<f64, D> {
    SVector::<f64, D>::from_fn(|i, _| v[i]).normalize()
}

/// The hard points: (what, F, a).
fn points<const D: usize>() -> Vec<(String, SMatrix<f64, D, D>, SVector<f64, D>)> {
    let a = if D == 2 {
        unit::<D>(std::array::from_fn(|i| [0.8, 0.6][i]))
    } else {
        unit::<D>(std::array::from_fn(|i| [0.48, 0.6, 0.64][i]))
    };
    let c = if D == 2 {
        unit::<D>(std::array::from_fn(|i| [-0.6, 0.8][i]))
    } else {
        unit::<D>(std::array::from_fn(|i| [0.8, -0.6, 0.0][i]))
    };
    let id = SMatrix::<f64, D, D>::identity();
    let aa = a * a.transpose();
    let cc = c * c.transpose();
    let diag = |s: [f64; 3]| SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { s[i] } else { 0.0 });
    let generic = SMatrix::<f64, D, D>::from_fn(|i, j| {
        [[1.1, 0.3, -0.2], [-0.15, 0.9, 0.25], [0.1, -0.35, 1.2]][i][j]
    });
    let mut out: Vec<(&str, SMatrix<f64, D, D>)> = vec![
        ("rest", id),
        ("generic", generic),
        ("Fa ~ 0", id - aa * (1.0 - 1e-9)),
        ("Fa = 0", id - aa),
        ("I4 just below 0", id - aa * (1.0 + 1e-9)),
        ("I4 just above 0", id - aa * (1.0 - 1e-7)),
        ("inverted along a", id - aa * 1.5),
        ("inverted across a", id - cc * 1.5),
        ("tiny sigma", diag([1.0, 1e-4, 1e-7])),
        ("huge stretch along a", id + aa * 1e3),
        ("huge stretch", diag([1e3, 1.0, 1e-3])),
        ("near pole", diag([1.3, 0.9, -0.9 * (1.0 + 1e-4)])),
        ("pole", diag([1.3, 0.9, -0.9])),
        ("inverted", diag([1.4, 0.8, -0.5])),
    ];
    if D == 2 {
        out.push(("2D near pole", diag([1.2, -1.2 * (1.0 + 1e-4), 0.0])));
        out.push(("2D pole", diag([1.2, -1.2, 0.0])));
    }
    let mut st = 0xf1b5_u64 + D as u64;
    let e0 = SVector::<f64, D>::from_fn(|i, _| if i == 0 { 1.0 } else { 0.0 });
    let mut pts = Vec::new();
    for (what, f) in out {
        pts.push((what.to_string(), f, a));
        pts.push((format!("{what}, a = e0"), f, e0));
        let (r1, r2) = (rotation::<D>(&mut st), rotation::<D>(&mut st));
        pts.push((format!("{what}, rotated"), r1 * f * r2.transpose(), r2 * a));
    }
    let mut bad = SMatrix::<f64, D, D>::identity();
    bad[(0, 1)] = f64::NAN;
    pts.push(("non-finite F".into(), bad, a));
    pts
}

/// The driver's input line and the Rust answer for one point.
fn rust_line<const D: usize>(
    e: &dyn FibreEnergy<D>,
    idx: usize,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
) -> (String, Vec<f64>)
where
    Space<D>: FibreDim<D>,
{
    let rest_nodes: Vec<[f64; D]> = (0..=D)
        .map(|k| {
            std::array::from_fn(|i| {
                [
                    [0.0, 0.0, 0.0],
                    [1.0, 0.1, 0.0],
                    [0.2, 1.1, 0.0],
                    [0.1, 0.2, 0.9],
                ][k][i]
            })
        })
        .collect();
    let case = Case::<D> {
        f: *f,
        x: rest_nodes
            .iter()
            .map(|p| {
                let v = f * SVector::<f64, D>::from_fn(|i, _| p[i]);
                std::array::from_fn(|i| v[i])
            })
            .collect(),
        rest_nodes,
    };
    let rest = <Space<D> as Dim<D>>::rest(&nodes_of::<D>(&case.rest_nodes)).expect("rest");
    let x = nodes_of::<D>(&case.x);
    let xs: Vec<String> = case.x.iter().flatten().map(|v| format!("{v:e}")).collect();
    let av: Vec<String> = a.iter().map(|v| format!("{v:e}")).collect();
    let input = format!(
        "{idx} {D} {} {} {} {:e} {}\n",
        nums(f),
        av.join(" "),
        nums(&rest.dm_inv),
        rest.measure,
        xs.join(" ")
    );
    let n = D * D;
    let reads_i4 = matches!(e.uses(), FibreUse::I4 | FibreUse::Both);
    let finite = f.iter().all(|v| v.is_finite());
    let mut want = Vec::new();
    for (k, filter) in FILTERS.into_iter().enumerate() {
        let p = fibre_f(e, f, a, filter, true);
        if k == 1 {
            let i4 = if reads_i4 && finite {
                invariant4(f, a)
            } else {
                f64::NAN
            };
            let i5 = if finite { invariant5(f, a) } else { f64::NAN };
            want.extend([p.psi, i4, i5]);
            want.extend((0..n).map(|i| p.grad[i]));
            want.push(match p.path {
                FibrePath::Degenerate => 0.0,
                FibrePath::ClosedI5 => 1.0,
                FibrePath::Numeric | FibrePath::Reduced => 2.0,
            });
        }
        want.extend(
            (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .map(|ij| p.hess[ij]),
        );
    }
    let ne = D * (D + 1);
    for filter in FILTERS {
        let ev = fibre_element_eval(e, &rest, &x, a, filter, true);
        want.push(ev.psi);
        want.extend((0..ne).map(|i| ev.grad[i]));
        want.extend(
            (0..ne)
                .flat_map(|i| (0..ne).map(move |j| (i, j)))
                .map(|ij| ev.hess[ij]),
        );
    }
    want.push(fibre_f(e, f, a, Filter::Clamp, false).psi);
    let i4 = if finite { invariant4(f, a) } else { f64::NAN };
    want.push(i4);
    want.push(if finite { invariant5(f, a) } else { f64::NAN });
    (input, want)
}

/// The largest finite |x|.
fn scale_of(w: &[f64]) -> f64 {
    w.iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Compare one answer line block by block; the worst relative difference.
///
/// A block is compared relative to its largest entry, except a filtered
/// Hessian, which is compared relative to the larger of its own and the raw
/// Hessian's (the block before it with `Filter::None`): projecting a matrix
/// is accurate to ε times the *input*'s norm, and near a pole σi + σj ≈ 0 the
/// raw Hessian of I4 is ~1/(σi + σj)² times larger than what the filter keeps
/// (Rust's reduced block and C++'s d²×d² solve then differ by ~ε‖H_raw‖).
/// A raw element Hessian entry that is ∞ − ∞ at an exact pole is +∞ in both
/// runtimes (as both report at F), never NaN.
fn compare(got: &[f64], want: &[f64], d: usize) -> Result<f64, String> {
    if got.len() != want.len() {
        return Err(format!("{} numbers, expected {}", got.len(), want.len()));
    }
    let (mut at, mut worst) = (0, 0.0f64);
    let mut raw_scale = 0.0f64;
    for (name, len) in blocks(d) {
        let (g, w) = (&got[at..at + len], &want[at..at + len]);
        let mut scale = scale_of(w);
        let is_hess = name.starts_with("hess_f") || name.starts_with("elem hess");
        if is_hess && name.ends_with("None") {
            raw_scale = scale;
        } else if is_hess {
            scale = scale.max(raw_scale);
        }
        compare_block(&name, g, w, TOL, scale, &mut worst)?;
        at += len;
    }
    Ok(worst)
}

#[test]
fn fibre_energies_compile_and_agree_with_rust() {
    let mods = modules();
    let dir = tempfile::tempdir().expect("tempdir");
    let src = driver(dir.path(), &mods);
    let mut input = String::new();
    let mut expected: Vec<(String, usize, Vec<f64>)> = Vec::new();
    for (idx, (m, _, lib)) in mods.iter().enumerate() {
        let e2 = rust_energy::<2>(m, *lib);
        for (what, f, a) in points::<2>() {
            let (line, want) = rust_line::<2>(e2.as_ref(), idx, &f, &a);
            input.push_str(&line);
            expected.push((format!("{} 2D {what}", m.name), 2, want));
        }
        let e3 = rust_energy::<3>(m, *lib);
        for (what, f, a) in points::<3>() {
            let (line, want) = rust_line::<3>(e3.as_ref(), idx, &f, &a);
            input.push_str(&line);
            expected.push((format!("{} 3D {what}", m.name), 3, want));
        }
    }
    for cc in compilers() {
        let exe = compile(&cc, &src, &[]);
        let got = run(&exe, &input);
        assert_eq!(got.len(), expected.len(), "{cc}: one line per case");
        let mut worst = 0.0f64;
        let mut failures = Vec::new();
        for (g, (what, d, want)) in got.iter().zip(&expected) {
            match compare(g, want, *d) {
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
            "{cc}: {} fibre cases agree, worst relative difference {worst:e}",
            expected.len()
        );
    }
}
