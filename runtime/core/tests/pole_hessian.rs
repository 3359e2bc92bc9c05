//! The raw Hessian exactly on a true pole of the energy (issue 12): ARAP's
//! twist eigenvalue (Ψ1 + Ψ2)/(σ1 + σ2) is +∞ on σ1 + σ2 = 0. The raw
//! Hessian is ±∞ exactly where that mode's vector reaches (sign of g_x g_y),
//! the other entries are the finite modes' sum, and nothing is NaN (before:
//! ∞·0 = NaN wherever the mode vector has a zero component). The projected
//! filters map the pole to their floor and stay finite.

use ecc_runtime::energies::Arap;
use ecc_runtime::{Energy, Filter, Rest, Svd, element_eval, hessian_f};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// σ on the pole σ1 + σ2 = 0 (pair slot 0 in 3D: the twist about axis 0).
fn pole_svd() -> Svd<3> {
    Svd {
        u: Matrix3::identity(),
        sigma: [1.2, 0.9, -0.9],
        v: Matrix3::identity(),
    }
}

#[test]
fn raw_f_space_hessian_is_infinite_only_on_the_pole_mode() {
    let svd = pole_svd();
    let s = Arap.spectral(&svd.sigma);
    assert_eq!(s.twist[0], f64::INFINITY);
    let h = hessian_f(&svd, &s, Filter::None);
    assert!(h.iter().all(|v| !v.is_nan()), "NaN in the raw Hessian: {h}");
    // With U = V = I the twist vector is (e2 e1ᵀ − e1 e2ᵀ)/√2: vec(F)
    // (column-major) entries 5 = (2, 1) and 7 = (1, 2), with signs + and −.
    let mut finite = s;
    finite.twist[0] = 0.0;
    let h0 = hessian_f(&svd, &finite, Filter::None);
    for x in 0..9 {
        for y in 0..9 {
            let on = |i: usize| i == 5 || i == 7;
            if on(x) && on(y) {
                let sign = if x == y { 1.0 } else { -1.0 };
                assert_eq!(h[(x, y)], sign * f64::INFINITY, "({x}, {y})");
            } else {
                let e = (h[(x, y)] - h0[(x, y)]).abs();
                assert!(
                    e <= 1e-12 * (1.0 + h0[(x, y)].abs()),
                    "({x}, {y}): {h} vs {h0}"
                );
            }
        }
    }
    assert_eq!(h, h.transpose());
}

#[test]
fn projected_f_space_hessians_at_the_pole_are_unchanged() {
    // The filters map the infinite eigenvalue to their floor: the Hessian is
    // the finite modes' sum plus floor · g gᵀ, PSD and finite.
    let svd = pole_svd();
    let s = Arap.spectral(&svd.sigma);
    for fl in [Filter::Clamp, Filter::ClampEps(1e-6), Filter::Abs] {
        let h = hessian_f(&svd, &s, fl);
        let mut floored = s;
        floored.twist[0] = fl.floor();
        let want = hessian_f(&svd, &floored, fl);
        assert!(h.iter().all(|v| v.is_finite()), "{fl:?}");
        assert_eq!(h, want, "{fl:?}");
        let min = SymmetricEigen::new(h).eigenvalues.min();
        assert!(min >= fl.floor() - 1e-12, "{fl:?}: {min:e}");
    }
}

#[test]
fn raw_element_hessian_on_the_pole_has_no_nan() {
    // Unit right tetrahedron (Dm = I) deformed by F = diag(1.2, 0.9, −0.9):
    // the signed SVD of a diagonal F is exact, so σ1 + σ2 = 0 exactly.
    let rest =
        Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap();
    let f = Matrix3::from_diagonal(&Vector3::new(1.2, 0.9, -0.9));
    let x: [[f64; 3]; 4] = std::array::from_fn(|n| {
        let p = match n {
            0 => Vector3::zeros(),
            k => Vector3::ith(k - 1, 1.0),
        };
        let q = f * p;
        [q[0], q[1], q[2]]
    });
    let raw = element_eval(&Arap, &rest, &x, Filter::None, true);
    assert!(raw.psi.is_finite());
    assert!(raw.hess.iter().all(|v| !v.is_nan()), "NaN: {}", raw.hess);
    let infinite = raw.hess.iter().filter(|v| v.is_infinite()).count();
    assert!(infinite > 0, "the pole is exact here: {}", raw.hess);
    assert_eq!(raw.hess, raw.hess.transpose());
    // Every row that an infinite entry reaches has +∞ on its diagonal (P is
    // positive semidefinite for a +∞ mode), rows it does not reach are the
    // finite modes' sum.
    for i in 0..12 {
        let row_inf = (0..12).any(|j| raw.hess[(i, j)].is_infinite());
        assert_eq!(raw.hess[(i, i)] == f64::INFINITY, row_inf, "row {i}");
    }
    for fl in [Filter::Clamp, Filter::ClampEps(1e-6), Filter::Abs] {
        let ev = element_eval(&Arap, &rest, &x, fl, true);
        assert!(ev.hess.iter().all(|v| v.is_finite()), "{fl:?}");
    }
}
