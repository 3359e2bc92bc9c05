//! Closed-form symmetric eigensolvers vs nalgebra's `SymmetricEigen`.

mod common;

use common::*;
use ecc_runtime::sym::{sym2_eigen, sym3_eigen};
use nalgebra::{Matrix2, Matrix3, SymmetricEigen, Vector3};
use rand::Rng;

/// Residual/eigenvalue tolerance relative to max |A_ij| (backward stable ⇒ a few ε).
const TOL: f64 = 1e-13;

fn check3(a: &Matrix3<f64>, what: &str) {
    let m: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[(i, j)]));
    let (vals, vecs) = sym3_eigen(&m);
    let scale = a.abs().max().max(f64::MIN_POSITIVE);
    assert!(
        vals[0] >= vals[1] && vals[1] >= vals[2],
        "{what}: not descending {vals:?}"
    );
    let q = Matrix3::from_fn(|i, j| vecs[j][i]);
    assert!(
        max_diff(&(q.transpose() * q), &Matrix3::identity()) < TOL,
        "{what}: not orthonormal"
    );
    assert!(
        (q.determinant() - 1.0).abs() < TOL,
        "{what}: det {}",
        q.determinant()
    );
    for k in 0..3 {
        let v = Vector3::from(vecs[k]);
        let res = (a * v - v * vals[k]).abs().max() / scale;
        assert!(res < 10.0 * TOL, "{what}: residual {res:e} for pair {k}");
    }
    let mut theirs: Vec<f64> = SymmetricEigen::new(*a)
        .eigenvalues
        .iter()
        .copied()
        .collect();
    theirs.sort_by(|x, y| y.total_cmp(x));
    for k in 0..3 {
        assert!(
            (vals[k] - theirs[k]).abs() < TOL * scale,
            "{what}: {vals:?} vs {theirs:?}"
        );
    }
}

#[test]
fn sym3_random_and_degenerate() {
    let mut r = rng(11);
    let mut mats = vec![
        Matrix3::zeros(),
        Matrix3::identity(),
        Matrix3::from_diagonal(&Vector3::new(2.0, 2.0, -1.0)),
        Matrix3::from_diagonal(&Vector3::new(1.0, 1.0 + 1e-12, 1.0 - 1e-12)),
        Matrix3::from_diagonal(&Vector3::new(1e200, 1.0, -1e-200)),
        Matrix3::new(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0),
    ];
    for _ in 0..3000 {
        let b = Matrix3::from_fn(|_, _| r.gen_range(-1.0..1.0));
        mats.push(b + b.transpose());
        // Prescribed spectra with (near-)repeats under random rotations.
        let q = rot3(&mut r);
        let l0: f64 = r.gen_range(-2.0..2.0);
        let gap = 10f64.powf(r.gen_range(-15.0..0.0));
        let l2: f64 = r.gen_range(-2.0..2.0);
        mats.push(q * Matrix3::from_diagonal(&Vector3::new(l0, l0 + gap, l2)) * q.transpose());
        mats.push(
            q * Matrix3::from_diagonal(&Vector3::new(l0, l0 + gap, l0 - gap)) * q.transpose(),
        );
    }
    for (k, a) in mats.iter().enumerate() {
        let a = (a + a.transpose()) * 0.5;
        check3(&a, &format!("matrix {k}"));
    }
}

#[test]
fn sym2_random_and_degenerate() {
    let mut r = rng(12);
    let mut mats = vec![
        Matrix2::zeros(),
        Matrix2::identity(),
        Matrix2::new(1.0, 1e-300, 1e-300, 1.0),
    ];
    for _ in 0..3000 {
        let (a, b, c) = (
            r.gen_range(-1.0..1.0),
            r.gen_range(-1.0..1.0),
            r.gen_range(-1.0..1.0),
        );
        mats.push(Matrix2::new(a, b, b, c));
        mats.push(Matrix2::new(a, b * 1e-12, b * 1e-12, a + c * 1e-14));
    }
    for a in &mats {
        let (vals, vecs) = sym2_eigen(a[(0, 0)], a[(0, 1)], a[(1, 1)]);
        let scale = a.abs().max().max(f64::MIN_POSITIVE);
        assert!(vals[0] >= vals[1]);
        let q = Matrix2::from_fn(|i, j| vecs[j][i]);
        assert!(max_diff(&(q.transpose() * q), &Matrix2::identity()) < TOL);
        assert!((q.determinant() - 1.0).abs() < TOL);
        for k in 0..2 {
            let v = nalgebra::Vector2::from(vecs[k]);
            assert!(
                (a * v - v * vals[k]).abs().max() < 10.0 * TOL * scale,
                "{a}"
            );
        }
    }
}

#[test]
fn non_finite_input_is_reported_not_panicking() {
    let (v, _) = sym3_eigen(&[[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(v.iter().all(|x| x.is_nan()));
    let (v, _) = sym3_eigen(&[[1.0, f64::INFINITY, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(v.iter().all(|x| x.is_nan()));
    let (v, _) = sym2_eigen(1.0, f64::NAN, 0.0);
    assert!(v.iter().all(|x| x.is_nan()));
}
