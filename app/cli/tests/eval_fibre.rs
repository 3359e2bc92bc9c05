//! `ecc eval --fiber` (issue 16): the `fibre` object of the JSON for the
//! library's fibre energies, HOBAK's eigenvalues, and the usage errors.

mod common;

use common::{ecc, lib, ok};
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    serde_json::from_str(&ok(args)).expect("one JSON object")
}

#[test]
fn stvk_fibre_along_x_has_hobaks_eigenvalues() {
    let path = lib("fibre_stvk");
    let v = json(&[
        "eval",
        &path,
        "--F",
        "1.2 0 0; 0 1 0; 0 0 1",
        "--fiber",
        "2 0 0",
        "--json",
    ]);
    let f = &v["fibre"];
    assert_eq!(f["direction"], serde_json::json!([1.0, 0.0, 0.0]));
    let i5 = f["I5"].as_f64().unwrap();
    assert!((i5 - 1.44).abs() < 1e-14);
    assert!((f["psi"].as_f64().unwrap() - 0.5 * 0.44 * 0.44).abs() < 1e-14);
    assert_eq!(f["eigensystem"], "closed-form");
    // λ_along = 2μ(I5 − 1) + 4μ I5, λ_across = 2μ(I5 − 1) (×2), 0 (×6).
    let eig: Vec<f64> = f["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let want = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.88, 0.88, 0.88 + 5.76];
    for (g, w) in eig.iter().zip(want) {
        assert!((g - w).abs() < 1e-12, "{eig:?}");
    }
    // The isotropic part of a pure fibre energy is 0; its keys are unchanged.
    assert_eq!(v["psi"].as_f64(), Some(0.0));
}

#[test]
fn inverted_fibre_in_2d_arap() {
    let path = lib("fibre_arap");
    let v = json(&[
        "eval",
        &path,
        "--F",
        "-0.5 0; 0 1",
        "--fibre",
        "1 0",
        "--json",
    ]);
    let f = &v["fibre"];
    assert!(f["I4"].as_f64().unwrap() < 0.0);
    // The compressed axis carries the inversion (signed polar S = F):
    // I4 = −0.5, ψ = ½(√I5 − sign(I4))² = ½(0.5 + 1)².
    assert!((f["I4"].as_f64().unwrap() + 0.5).abs() < 1e-14);
    assert!((f["psi"].as_f64().unwrap() - 1.125).abs() < 1e-13);
}

#[test]
fn usage_errors_are_clear() {
    let out = ecc(&["eval", &lib("fibre_fung"), "--F", "1 0; 0 1"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("has a fibre part (`fiber a`): give the direction with --fiber \"ax ay\""),
        "{err}"
    );
    let out = ecc(&["eval", &lib("snh"), "--F", "1 0; 0 1", "--fiber", "1 0"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("has no `fiber` statement"));
    let out = ecc(&[
        "eval",
        &lib("fibre_stvk"),
        "--F",
        "1 0; 0 1",
        "--fiber",
        "0 0",
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("finite and nonzero"));
    let out = ecc(&[
        "eval",
        &lib("fibre_stvk"),
        "--F",
        "1 0; 0 1",
        "--fiber",
        "1 0 0",
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("expected 2 numbers, found 3"));
}
