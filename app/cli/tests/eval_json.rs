//! `ecc eval --json`: the documented shape, and values against independent
//! in-process baselines (central differences, nalgebra's eigensolver), for
//! every library energy in every dimension it compiles for.

mod common;

use common::{ecc, library, ok};
use ecc_runtime::reference::{fd_gradient_f, fd_hessian_f};
use ecc_runtime::signed_svd;
use nalgebra::{DMatrix, SMatrix, SymmetricEigen};
use serde_json::Value;

const F2: &str = "1.2 0.15; -0.1 0.85";
const F3: &str = "1.1 0.2 -0.05; 0.1 0.9 0.15; -0.08 0.05 1.05";

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

fn matrix(v: &Value, n: usize) -> DMatrix<f64> {
    let rows = v.as_array().expect("rows");
    assert_eq!(rows.len(), n);
    let rows: Vec<Vec<f64>> = rows.iter().map(numbers).collect();
    assert!(rows.iter().all(|r| r.len() == n));
    DMatrix::from_fn(n, n, |i, j| rows[i][j])
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn check<const D: usize>(name: &str, path: &str, f_text: &str, rows: [[f64; D]; D])
where
    ecc_runtime::Space<D>: ecc_runtime::Dim<D>,
{
    let dim = D.to_string();
    let text = ok(&["eval", path, "--dim", &dim, "--F", f_text, "--json"]);
    let v: Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{name}: bad JSON ({e}):\n{text}"));
    let n = D * D;
    assert_eq!(v["dim"], D);
    assert_eq!(v["domain"], "inside", "{name}");
    assert_eq!(v["finite"], true, "{name}");
    let psi = v["psi"].as_f64().expect("psi is a number");
    let grad = numbers(&v["gradient"]);
    assert_eq!(grad.len(), n);
    let h = matrix(&v["hessian"], n);
    let p = matrix(&v["hessian_projected"], n);
    let ev = numbers(&v["eigenvalues"]);
    assert_eq!(ev.len(), n);
    assert!(
        ev.windows(2).all(|w| w[0] <= w[1]),
        "{name}: eigenvalues ascending"
    );

    // Independent baselines from the same energy loaded in-process.
    let e = ecc_interp::load_psi::<D>(path, &[]).unwrap();
    let f = SMatrix::<f64, D, D>::from_fn(|r, c| rows[r][c]);
    let psi_ref = e.psi(&signed_svd(&f).sigma);
    assert!(
        (psi - psi_ref).abs() <= 1e-14 * psi_ref.abs().max(1.0),
        "{name}: psi {psi} vs {psi_ref}"
    );
    let g_fd = fd_gradient_f(e.as_ref(), &f);
    assert!(
        rel(&grad, g_fd.as_slice()) < 1e-7,
        "{name}: gradient vs differences"
    );
    let h_fd = fd_hessian_f(e.as_ref(), &f);
    let h_fd: Vec<f64> = (0..n * n).map(|k| h_fd[(k % n, k / n)]).collect();
    assert!(
        rel(h.as_slice(), &h_fd) < 1e-5,
        "{name}: Hessian vs differences"
    );
    let sym = (&h + h.transpose()) * 0.5;
    assert!(
        rel(h.as_slice(), sym.as_slice()) < 1e-14,
        "{name}: Hessian symmetric"
    );
    let eig = SymmetricEigen::new(sym);
    let mut lam: Vec<f64> = eig.eigenvalues.iter().copied().collect();
    lam.sort_by(f64::total_cmp);
    assert!(
        rel(&ev, &lam) < 1e-10,
        "{name}: eigenvalues vs SymmetricEigen: {ev:?} vs {lam:?}"
    );
    let q = &eig.eigenvectors;
    let clamped = DMatrix::from_fn(n, n, |i, j| {
        (0..n)
            .map(|k| q[(i, k)] * eig.eigenvalues[k].max(0.0) * q[(j, k)])
            .sum::<f64>()
    });
    let scale = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let perr = (&p - &clamped).iter().fold(0.0f64, |m, x| m.max(x.abs())) / scale;
    assert!(
        perr < 1e-10,
        "{name}: projected Hessian vs numeric projection ({perr})"
    );
    let pe = SymmetricEigen::new(p.clone()).eigenvalues;
    assert!(
        pe.iter().all(|&l| l >= -1e-10 * scale),
        "{name}: projected Hessian is PSD"
    );
}

#[test]
fn every_library_energy_in_every_dimension() {
    let f2 = [[1.2, 0.15], [-0.1, 0.85]];
    let f3 = [[1.1, 0.2, -0.05], [0.1, 0.9, 0.15], [-0.08, 0.05, 1.05]];
    let mut runs = 0;
    for (name, path) in library() {
        let src = std::fs::read_to_string(&path).unwrap();
        let module = ecc_dsl::compile(&src, &name).unwrap();
        // Fibre energies (`fiber a`) need --fiber; tests/eval_fibre.rs covers them.
        if module.dims.iter().any(|d| d.fibre.is_some()) {
            continue;
        }
        for ir in &module.dims {
            match ir.dim {
                2 => check::<2>(&name, &path, F2, f2),
                _ => check::<3>(&name, &path, F3, f3),
            }
            runs += 1;
        }
    }
    assert!(runs >= 18, "{runs} energy/dimension pairs");
}

#[test]
fn the_dimension_is_inferred_from_f_and_params_apply() {
    let path = common::lib("snh");
    let a: Value = serde_json::from_str(&ok(&["eval", &path, "--F", F3, "--json"])).unwrap();
    assert_eq!(a["dim"], 3);
    assert_eq!(a["params"]["mu"], 1.0);
    let b: Value = serde_json::from_str(&ok(&[
        "eval", &path, "--F", F3, "--param", "mu=2", "--param", "lambda=5", "--json",
    ]))
    .unwrap();
    assert_eq!(b["params"]["mu"], 2.0);
    assert_eq!(b["params"]["lambda"], 5.0);
    assert_ne!(a["psi"], b["psi"]);
    let e =
        ecc_interp::load_psi::<3>(&path, &[("mu".into(), 2.0), ("lambda".into(), 5.0)]).unwrap();
    let f =
        SMatrix::<f64, 3, 3>::from_row_slice(&[1.1, 0.2, -0.05, 0.1, 0.9, 0.15, -0.08, 0.05, 1.05]);
    let want = e.psi(&signed_svd(&f).sigma);
    assert!((b["psi"].as_f64().unwrap() - want).abs() < 1e-14 * want.abs().max(1.0));
}

#[test]
fn f_is_row_major_and_the_gradient_column_major() {
    // ARAP at F = [[a, b], [c, d]]: ∂Ψ/∂F = 2(F − R); shear F = [[1, t], [0, 1]] has
    // an asymmetric gradient, so transposing either convention would show.
    let v: Value = serde_json::from_str(&ok(&[
        "eval",
        &common::lib("arap"),
        "--F",
        "1 0.5; 0 1",
        "--json",
    ]))
    .unwrap();
    let g = numbers(&v["gradient"]);
    let f = SMatrix::<f64, 2, 2>::new(1.0, 0.5, 0.0, 1.0);
    let svd = signed_svd(&f);
    let r = svd.u * svd.v.transpose();
    let want = (f - r) * 2.0;
    // vec column-major: [G00, G10, G01, G11].
    let want_vec = [want[(0, 0)], want[(1, 0)], want[(0, 1)], want[(1, 1)]];
    assert!(rel(&g, &want_vec) < 1e-12, "{g:?} vs {want_vec:?}");
    assert_eq!(v["F"][0][1], 0.5);
}

#[test]
fn outside_the_domain_is_null_with_a_reason() {
    let out = ecc(&[
        "eval",
        &common::lib("neohookean"),
        "--F",
        "1 0 0; 0 1 0; 0 0 -1",
        "--json",
    ]);
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["domain"], "outside");
    assert_eq!(v["finite"], false);
    assert!(v["psi"].is_null() && v["gradient"].is_null() && v["hessian"].is_null());
    assert!(v["hessian_projected"].is_null() && v["eigenvalues"].is_null());
    assert!(v["error"].as_str().unwrap().contains("outside"));
}

#[test]
fn a_genuine_pole_gives_nulls_but_a_finite_projection() {
    // ARAP's twist eigenvalue 2 − 4/(σ0 + σ1) is infinite at σ = (1, −1).
    let v: Value = serde_json::from_str(&ok(&[
        "eval",
        &common::lib("arap"),
        "--F",
        "1 0; 0 -1",
        "--json",
    ]))
    .unwrap();
    assert_eq!(v["domain"], "inside");
    assert_eq!(v["finite"], false);
    assert!(v["psi"].is_number());
    let ev = v["eigenvalues"].as_array().unwrap();
    assert!(
        ev.iter().any(|x| x.is_null()),
        "the infinite eigenvalue is null: {ev:?}"
    );
    let p = v["hessian_projected"].as_array().unwrap();
    assert!(
        p.iter()
            .flat_map(|r| r.as_array().unwrap())
            .all(|x| x.is_number())
    );
}

#[test]
fn the_table_form_is_readable() {
    let text = ok(&["eval", &common::lib("stvk"), "--F", F2]);
    for key in [
        "psi",
        "gradient",
        "hessian",
        "hessian_projected",
        "eigenvalues",
        "sigma",
        "mu = ",
    ] {
        assert!(text.contains(key), "missing {key}:\n{text}");
    }
}
