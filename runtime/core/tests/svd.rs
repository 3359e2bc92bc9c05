//! Signed SVD: orthogonality, det = +1, reconstruction, ordering/sign
//! convention, agreement with nalgebra's singular values — at every hard case
//! under random rotations, at random F and at near-rank-deficient F.

mod common;

use common::*;
use ecc_runtime::svd::{Svd, signed_svd, signed_svd2, signed_svd3};
use nalgebra::{Matrix2, Matrix3, SMatrix};
use rand::Rng;

/// Orthogonality and reconstruction tolerance, relative to ‖F‖ (a backward-stable
/// SVD reaches a few ε; 1e-13 catches any real error).
const TOL: f64 = 1e-13;

fn check<const D: usize>(f: &SMatrix<f64, D, D>, s: &Svd<D>, what: &str) {
    let id = SMatrix::<f64, D, D>::identity();
    let scale = f.abs().max().max(f64::MIN_POSITIVE);
    assert!(
        max_diff(&(s.u.transpose() * s.u), &id) < TOL,
        "{what}: UᵀU ≠ I"
    );
    assert!(
        max_diff(&(s.v.transpose() * s.v), &id) < TOL,
        "{what}: VᵀV ≠ I"
    );
    assert!(
        (dynm(&s.u).determinant() - 1.0).abs() < TOL,
        "{what}: det U = {}",
        dynm(&s.u).determinant()
    );
    assert!(
        (dynm(&s.v).determinant() - 1.0).abs() < TOL,
        "{what}: det V = {}",
        dynm(&s.v).determinant()
    );
    let err = max_diff(&s.reconstruct(), f) / scale;
    assert!(err < TOL, "{what}: reconstruction error {err:e} {s:?}");
    for i in 0..D - 1 {
        assert!(s.sigma[i] >= 0.0, "{what}: σ_{i} = {} < 0", s.sigma[i]);
        assert!(
            s.sigma[i] >= s.sigma[i + 1].abs(),
            "{what}: order {:?}",
            s.sigma
        );
    }
    // Sign convention: σ_last < 0 exactly when det F < 0 (when det is not tiny).
    let det = dynm(f).determinant();
    if det.abs() > 1e-10 * scale.powi(D as i32) {
        assert_eq!(
            s.sigma[D - 1] < 0.0,
            det < 0.0,
            "{what}: sign of σ vs det {det}"
        );
    }
    // Magnitudes agree with nalgebra's (unsigned, sorted) singular values.
    let mut ours: Vec<f64> = s.sigma.iter().map(|x| x.abs()).collect();
    ours.sort_by(|a, b| b.total_cmp(a));
    let mut theirs: Vec<f64> = dynm(f).singular_values().iter().copied().collect();
    theirs.sort_by(|a, b| b.total_cmp(a));
    for (a, b) in ours.iter().zip(theirs.iter()) {
        assert!(
            (a - b).abs() <= 1e-13 * scale,
            "{what}: σ {ours:?} vs nalgebra {theirs:?}"
        );
    }
}

#[test]
fn hard_cases_3d_under_rotations() {
    let mut r = rng(1);
    for case in hard_cases_3d() {
        for (u, v) in rotations3(&mut r, 8) {
            let f = compose(&u, &case.sigma, &v);
            let s = signed_svd3(&f);
            check(&f, &s, case.name);
            // σ matches the constructed one up to ordering (and sign placement).
            let mut want: Vec<f64> = case.sigma.iter().map(|x| x.abs()).collect();
            want.sort_by(|a, b| b.total_cmp(a));
            for (k, w) in want.iter().enumerate() {
                assert!(
                    (s.sigma[k].abs() - w).abs() <= 1e-13 * f.abs().max(),
                    "{}: {:?}",
                    case.name,
                    s.sigma
                );
            }
        }
    }
}

#[test]
fn hard_cases_2d_under_rotations() {
    let mut r = rng(2);
    for case in hard_cases_2d() {
        for (u, v) in rotations2(&mut r, 8) {
            let f = compose(&u, &case.sigma, &v);
            check(&f, &signed_svd2(&f), case.name);
        }
    }
}

#[test]
fn random_matrices() {
    let mut r = rng(3);
    for f in random_f3(&mut r, 2000) {
        check(&f, &signed_svd3(&f), "random 3x3");
        check(&f, &signed_svd(&f), "random 3x3 via dispatch");
    }
    for f in random_f2(&mut r, 2000) {
        check(&f, &signed_svd2(&f), "random 2x2");
        check(&f, &signed_svd(&f), "random 2x2 via dispatch");
    }
}

#[test]
fn near_rank_deficient_and_special_matrices() {
    let mut r = rng(4);
    let mut cases: Vec<Matrix3<f64>> = vec![
        Matrix3::zeros(),
        Matrix3::identity(),
        -Matrix3::identity(),
        Matrix3::from_diagonal_element(1e-300),
        Matrix3::from_diagonal_element(1e300),
        Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0), // rank 2
        Matrix3::new(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0), // rank 1
        Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 5e-324), // subnormal
        Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0), // permutation
        Matrix3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0), // reflection
    ];
    for _ in 0..200 {
        let u = rot3(&mut r);
        let v = rot3(&mut r);
        let tiny = 10f64.powf(r.gen_range(-16.0..-4.0));
        let sign = if r.gen_bool(0.5) { 1.0 } else { -1.0 };
        cases.push(compose(
            &u,
            &[r.gen_range(0.5..2.0), r.gen_range(0.5..2.0), sign * tiny],
            &v,
        ));
        cases.push(compose(
            &u,
            &[r.gen_range(0.5..2.0), tiny, sign * tiny * 0.5],
            &v,
        ));
        cases.push(compose(&u, &[1.0, 1.0 + tiny, sign * (1.0 - tiny)], &v));
        // Graded: σ spanning up to 16 orders of magnitude.
        let a = 10f64.powf(r.gen_range(-16.0..0.0));
        let b = a * 10f64.powf(r.gen_range(-16.0..0.0));
        cases.push(compose(&u, &[1.0, a, sign * b], &v));
        cases.push(compose(&u, &[1.0, 1.0 - a, sign * b], &v));
    }
    for f in &cases {
        check(f, &signed_svd3(f), &format!("special {:?}", f.as_slice()));
    }
    let cases2 = [
        Matrix2::zeros(),
        Matrix2::new(1.0, 2.0, 2.0, 4.0),
        Matrix2::new(0.0, 1.0, 1.0, 0.0),
        Matrix2::new(1e-300, 0.0, 0.0, -1e-300),
    ];
    for f in &cases2 {
        check(f, &signed_svd2(f), &format!("special {:?}", f.as_slice()));
    }
}

#[test]
fn non_finite_input_gives_nan_sigma_without_panicking() {
    let mut f = Matrix3::identity();
    f[(1, 2)] = f64::NAN;
    let s = signed_svd3(&f);
    assert!(s.sigma.iter().all(|x| x.is_nan()));
    assert_eq!(s.u, Matrix3::identity());
    f[(1, 2)] = f64::INFINITY;
    assert!(signed_svd3(&f).sigma.iter().all(|x| x.is_nan()));
    let g = Matrix2::new(1.0, f64::NEG_INFINITY, 0.0, 1.0);
    assert!(signed_svd2(&g).sigma.iter().all(|x| x.is_nan()));
}
