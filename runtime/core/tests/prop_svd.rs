//! Property tests (proptest) of the runtime over random input:
//!
//! * the signed SVD of any finite F — entries over 1e±150, rank-deficient,
//!   repeated or graded singular values — reconstructs F to 1e-13‖F‖ (a
//!   handful of roundings, ≈ 500 ε), has orthonormal U, V with det +1,
//!   |σ0| ≥ |σ1| ≥ |σ2| ≥ 0 apart from the sign, and puts the sign of
//!   det F on the last value; a non-finite F gives a non-finite σ (never a
//!   panic);
//! * element evaluation is frame-indifferent: Ψ of R·x + t equals Ψ of x
//!   and the gradient rotates with R (to 1e-12·κ³ relative, κ = σmax/σmin
//!   of the element's F, capped at 1e4), and every
//!   filtered element Hessian is finite, symmetric and PSD — for the
//!   hand-written ARAP, symmetric Dirichlet and Stable Neo-Hookean.
//!
//! Failures are shrunk and saved next to this file
//! (`prop_svd.proptest-regressions`, committed, replayed first).

use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, Filter, Rest, element_eval, signed_svd2, signed_svd3};
use nalgebra::{DMatrix, Matrix2, Matrix3, Quaternion, SymmetricEigen, UnitQuaternion};
use proptest::prelude::*;

/// A 3×3 matrix: O(1) entries times 10^k (k in ±150), sometimes with a
/// dependent row (rank-deficient) or a repeated structure.
fn matrix3() -> impl Strategy<Value = Matrix3<f64>> {
    (prop::array::uniform9(-2.0f64..2.0), -150i32..150, 0usize..4).prop_map(|(e, k, kind)| {
        let mut m = Matrix3::from_column_slice(&e) * 10f64.powi(k);
        match kind {
            1 => {
                // rank 2: third row = first + second
                let r = m.row(0) + m.row(1);
                m.set_row(2, &r);
            }
            2 => m = m.transpose() * m, // symmetric PSD: repeated-ish values
            3 => m = Matrix3::from_diagonal(&m.diagonal()), // exactly diagonal, any signs
            _ => {}
        }
        m
    })
}

fn rotation() -> impl Strategy<Value = Matrix3<f64>> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-degenerate", |q| {
            q.iter().map(|x| x * x).sum::<f64>() > 1e-2
        })
        .prop_map(|q| {
            UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
                .to_rotation_matrix()
                .into_inner()
        })
}

fn check_svd3(f: &Matrix3<f64>) -> Result<(), TestCaseError> {
    let svd = signed_svd3(f);
    let n = f.abs().max();
    let tol = 1e-13 * n;
    prop_assert!(
        (svd.reconstruct() - f).abs().max() <= tol,
        "reconstruction {f}"
    );
    for q in [svd.u, svd.v] {
        prop_assert!((q.transpose() * q - Matrix3::identity()).abs().max() <= 1e-13);
        prop_assert!((q.determinant() - 1.0).abs() <= 1e-13);
    }
    let s = svd.sigma;
    prop_assert!(s[0] >= s[1].abs() && s[1] >= s[2].abs(), "{s:?}");
    prop_assert!(s[0] >= 0.0 && s[1] >= 0.0, "{s:?}");
    // the sign of det F, where it is not lost in rounding (scaled first:
    // det of a 1e-107 matrix underflows)
    let det = (f / n).determinant();
    if det.abs() > 1e-10 {
        prop_assert_eq!(s[2] < 0.0, det < 0.0, "σ {:?}, det {:e}", s, det);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn signed_svd3_of_any_finite_matrix(f in matrix3()) {
        check_svd3(&f)?;
    }

    #[test]
    fn signed_svd2_of_any_finite_matrix(e in prop::array::uniform4(-2.0f64..2.0), k in -150i32..150) {
        let f = Matrix2::from_column_slice(&e) * 10f64.powi(k);
        let svd = signed_svd2(&f);
        let n = f.abs().max();
        prop_assert!((svd.reconstruct() - f).abs().max() <= 1e-13 * n);
        let s = svd.sigma;
        prop_assert!(s[0] >= s[1].abs(), "{:?}", s);
        let det = (f / n).determinant();
        if det.abs() > 1e-10 {
            prop_assert_eq!(s[1] < 0.0, det < 0.0);
        }
    }

    #[test]
    fn non_finite_matrices_never_panic(e in prop::array::uniform9(-2.0f64..2.0), at in 0usize..9,
        bad in prop::sample::select(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY][..])) {
        let mut f = Matrix3::from_column_slice(&e);
        f[at] = bad;
        let svd = signed_svd3(&f);
        prop_assert!(!svd.is_finite());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn elements_are_frame_indifferent_and_filtered_hessians_psd(
        x in prop::array::uniform4(prop::array::uniform3(-1.0f64..1.0)),
        r in rotation(),
        t in prop::array::uniform3(-5.0f64..5.0),
    ) {
        let rest = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let rest = Rest::<3>::new(rest).unwrap();
        let moved: [[f64; 3]; 4] = x.map(|p| {
            let q = r * nalgebra::Vector3::from(p);
            [q[0] + t[0], q[1] + t[1], q[2] + t[2]]
        });
        let energies: [(&str, &dyn Energy<3>); 3] = [
            ("arap", &Arap),
            ("sd", &SymmetricDirichlet),
            ("snh", &StableNeoHookean::new(1.0, 10.0)),
        ];
        for (name, e) in energies {
            let a = element_eval(e, &rest, &x, Filter::Clamp, true);
            let b = element_eval(e, &rest, &moved, Filter::Clamp, true);
            prop_assert!(!a.psi.is_nan(), "{name}");
            if !a.psi.is_finite() {
                prop_assert_eq!(b.psi, a.psi, "{}", name);
                continue;
            }
            // σ carries ≈ ε‖F‖ absolute error, so Ψ and its gradient (which
            // may go like σmin⁻²…σmin⁻³ near a barrier) carry ≈ κ³ε relative,
            // κ = σmax/σmin
            let sv = signed_svd3(&ecc_runtime::element_f(&rest, &x)).sigma;
            let kappa = (sv[0] / sv[2].abs()).clamp(1.0, 1e4);
            let tol = 1e-12 * kappa * kappa * kappa;
            let scale = a.psi.abs().max(1.0);
            prop_assert!((a.psi - b.psi).abs() <= tol * scale, "{name}: {} vs {}", a.psi, b.psi);
            let gs = a.grad.amax().max(1.0);
            for node in 0..4 {
                let ga = nalgebra::Vector3::from_column_slice(&a.grad.as_slice()[3 * node..3 * node + 3]);
                let gb = nalgebra::Vector3::from_column_slice(&b.grad.as_slice()[3 * node..3 * node + 3]);
                prop_assert!((r * ga - gb).amax() <= 10.0 * tol * gs, "{name}: gradient does not rotate");
            }
            for fl in [Filter::Clamp, Filter::Abs, Filter::ClampEps(1e-3)] {
                let h = element_eval(e, &rest, &moved, fl, true).hess;
                prop_assert!(h.iter().all(|v| v.is_finite()), "{name} {fl:?}");
                prop_assert!(h == h.transpose(), "{name} {fl:?} not symmetric");
                let min = SymmetricEigen::new(DMatrix::from_column_slice(12, 12, h.as_slice()))
                    .eigenvalues
                    .min();
                // the floor is scaled by the rest volume (1/6) in the element Hessian
                prop_assert!(min >= -1e-12 * h.amax().max(1.0), "{name} {fl:?}: {min:e}");
            }
        }
    }
}
