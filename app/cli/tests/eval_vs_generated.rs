//! `ecc eval --json` (the interpreter route, run as the real binary) against
//! the generated energies of ecc-energies (CAS-specialised code) evaluated
//! in-process, at hard deformation gradients under a rotation and at random
//! F, for every library energy and dimension.

mod common;

use common::{library, ok};
use ecc_runtime::{Energy, Filter, signed_svd};
use nalgebra::{Matrix2, Matrix3, SMatrix};
use rand::{Rng, SeedableRng};
use serde_json::Value;

fn rot3(a: f64, b: f64) -> Matrix3<f64> {
    let (ca, sa, cb, sb) = (a.cos(), a.sin(), b.cos(), b.sin());
    Matrix3::new(ca, -sa, 0.0, sa, ca, 0.0, 0.0, 0.0, 1.0)
        * Matrix3::new(1.0, 0.0, 0.0, 0.0, cb, -sb, 0.0, sb, cb)
}

fn rot2(a: f64) -> Matrix2<f64> {
    Matrix2::new(a.cos(), -a.sin(), a.sin(), a.cos())
}

/// Hard σ (rest, uniform, repeated, 1e-9 apart, σi+σj ≈ 0, 1e-6, inverted, 1e3) under rotations, plus random F.
fn points<const D: usize>() -> Vec<(String, SMatrix<f64, D, D>)> {
    let hard3: [(&str, [f64; 3]); 8] = [
        ("rest", [1.0, 1.0, 1.0]),
        ("uniform", [1.7, 1.7, 1.7]),
        ("repeated", [1.3, 1.3, 0.8]),
        ("1e-9 apart", [1.3, 1.3 + 1e-9, 0.8]),
        ("antipodal", [1.2, 0.7, -0.7 + 1e-9]),
        ("1e-6", [1.0, 0.9, 1e-6]),
        ("inverted", [1.2, 0.9, -0.8]),
        ("1e3", [1e3, 2.0, 0.5]),
    ];
    let mut out = Vec::new();
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(D as u64);
    for (name, s) in hard3 {
        let f = if D == 3 {
            let d = Matrix3::from_diagonal(&s.into());
            let f = rot3(0.3, -1.1) * d * rot3(2.0, 0.4).transpose();
            SMatrix::<f64, D, D>::from_fn(|i, j| f[(i, j)])
        } else {
            let s2 = if name == "antipodal" {
                [0.7, -0.7 + 1e-9]
            } else {
                [s[0], s[2].min(s[1])]
            };
            let f = rot2(0.7) * Matrix2::from_diagonal(&s2.into()) * rot2(-1.9).transpose();
            SMatrix::<f64, D, D>::from_fn(|i, j| f[(i, j)])
        };
        out.push((name.to_string(), f));
    }
    for k in 0..3 {
        let f = SMatrix::<f64, D, D>::from_fn(|i, j| {
            f64::from(u8::from(i == j)) + r.gen_range(-0.5..0.5)
        });
        out.push((format!("random {k}"), f));
    }
    out
}

fn f_arg<const D: usize>(f: &SMatrix<f64, D, D>) -> String {
    (0..D)
        .map(|i| {
            (0..D)
                .map(|j| format!("{:e}", f[(i, j)]))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn nums(v: &Value) -> Vec<Option<f64>> {
    match v {
        Value::Array(a) => a.iter().flat_map(nums).collect(),
        Value::Null => vec![None],
        x => vec![Some(x.as_f64().expect("number"))],
    }
}

/// What `ecc eval` reports, from the generated energy.
fn reference<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>) -> Option<Vec<f64>> {
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    if s.psi == f64::INFINITY {
        return None;
    }
    let mut v = vec![s.psi];
    let any: &dyn std::any::Any = &svd;
    let sp: &dyn std::any::Any = &s;
    if let (Some(svd), Some(s)) = (
        any.downcast_ref::<ecc_runtime::Svd<2>>(),
        sp.downcast_ref::<ecc_runtime::Spectral<2>>(),
    ) {
        v.extend(ecc_runtime::gradient_f(svd, s).iter());
        v.extend(
            ecc_runtime::hessian_f(svd, s, Filter::None)
                .transpose()
                .iter(),
        );
        v.extend(
            ecc_runtime::hessian_f(svd, s, Filter::Clamp)
                .transpose()
                .iter(),
        );
        v.extend(ecc_runtime::eigen_f(svd, s).0);
    } else if let (Some(svd), Some(s)) = (
        any.downcast_ref::<ecc_runtime::Svd<3>>(),
        sp.downcast_ref::<ecc_runtime::Spectral<3>>(),
    ) {
        v.extend(ecc_runtime::gradient_f(svd, s).iter());
        v.extend(
            ecc_runtime::hessian_f(svd, s, Filter::None)
                .transpose()
                .iter(),
        );
        v.extend(
            ecc_runtime::hessian_f(svd, s, Filter::Clamp)
                .transpose()
                .iter(),
        );
        v.extend(ecc_runtime::eigen_f(svd, s).0);
    }
    Some(v)
}

fn compare<const D: usize>(
    name: &str,
    path: &str,
    e: &dyn Energy<D>,
    failures: &mut Vec<String>,
) -> usize {
    let mut n = 0;
    for (case, f) in points::<D>() {
        let text = ok(&[
            "eval",
            path,
            "--dim",
            &D.to_string(),
            "--F",
            &f_arg(&f),
            "--json",
        ]);
        let v: Value = serde_json::from_str(&text).unwrap();
        // The generated energy at the F that `ecc eval` parsed (identical bits).
        let parsed = SMatrix::<f64, D, D>::from_fn(|i, j| v["F"][i][j].as_f64().unwrap());
        let Some(want) = reference(e, &parsed) else {
            if v["domain"] != "outside" {
                failures.push(format!(
                    "{name} {D}D {case}: generated is outside the domain, eval is not"
                ));
            }
            continue;
        };
        let got: Vec<Option<f64>> = [
            "psi",
            "gradient",
            "hessian",
            "hessian_projected",
            "eigenvalues",
        ]
        .iter()
        .flat_map(|k| nums(&v[*k]))
        .collect();
        assert_eq!(got.len(), want.len(), "{name} {case}");
        let scale = want
            .iter()
            .filter(|x| x.is_finite())
            .fold(1.0f64, |m, x| m.max(x.abs()));
        let bad = got.iter().zip(&want).any(|(g, w)| match g {
            Some(g) => {
                let d = (g - w).abs();
                !d.is_finite() || d > 1e-9 * scale
            }
            None => w.is_finite(),
        });
        if bad {
            failures.push(format!(
                "{name} {D}D {case}: eval and generated code differ"
            ));
        }
        n += 1;
    }
    n
}

#[test]
fn ecc_eval_agrees_with_the_generated_energies() {
    let mut failures = Vec::new();
    let mut n = 0;
    for (name, path) in library() {
        let src = std::fs::read_to_string(&path).unwrap();
        let module = ecc_dsl::compile(&src, &name).unwrap();
        // Fibre energies (`fiber a`) need --fiber; tests/eval_fibre.rs covers them.
        if module.dims.iter().any(|d| d.fibre.is_some()) {
            continue;
        }
        for ir in &module.dims {
            if ir.dim == 2 {
                let e = ecc_energies::by_name::<2>(&name)
                    .unwrap_or_else(|| panic!("no generated 2D {name}"));
                n += compare::<2>(&name, &path, e.as_ref(), &mut failures);
            } else {
                let e = ecc_energies::by_name::<3>(&name)
                    .unwrap_or_else(|| panic!("no generated 3D {name}"));
                n += compare::<3>(&name, &path, e.as_ref(), &mut failures);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(n > 150, "{n} points compared");
}
