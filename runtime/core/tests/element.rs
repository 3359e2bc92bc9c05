//! Element kernels (x-space): rest data, energy/gradient/Hessian vs central
//! differences of the element energy, the structured chain rule vs a dense
//! B = ∂f/∂x built numerically from `tet_f`/`tri_f`, filters, and singular input.

mod common;

use common::energies::Poly;
use common::*;
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::reference::{fd_gradient, fd_hessian, project_psd_numeric};
use ecc_runtime::{
    Energy, Filter, Rest, RestError, element_eval, element_f, element_psi, hessian_f, signed_svd2,
    signed_svd3,
};
use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, SymmetricEigen};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Element gradient vs differences of ψ_e(x), relative to max(1, ‖g‖∞).
const GRAD_TOL: f64 = 1e-7;
/// Raw element Hessian vs second differences, relative to max(1, ‖H‖∞).
const HESS_TOL: f64 = 2e-5;
/// Structured chain rule vs dense BᵀHB, relative to max(1, ‖H‖∞).
const CHAIN_TOL: f64 = 1e-12;

fn random_tet(r: &mut ChaCha8Rng) -> [[f64; 3]; 4] {
    loop {
        let p: [[f64; 3]; 4] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        if Rest::<3>::new(p).is_ok_and(|rest| rest.measure > 0.02) {
            return p;
        }
    }
}

/// Deformed positions x_n = F p_n + t.
fn deform3(p: &[[f64; 3]; 4], f: &Matrix3<f64>, t: [f64; 3]) -> [[f64; 3]; 4] {
    std::array::from_fn(|n| {
        let y = f * vec3(p[n]);
        [y[0] + t[0], y[1] + t[1], y[2] + t[2]]
    })
}

fn flat3(x: &[[f64; 3]; 4]) -> SVector<f64, 12> {
    SVector::from_fn(|k, _| x[k / 3][k % 3])
}
fn unflat3(v: &SVector<f64, 12>) -> [[f64; 3]; 4] {
    std::array::from_fn(|n| std::array::from_fn(|r| v[n * 3 + r]))
}
fn flat2(x: &[[f64; 2]; 3]) -> SVector<f64, 6> {
    SVector::from_fn(|k, _| x[k / 2][k % 2])
}
fn unflat2(v: &SVector<f64, 6>) -> [[f64; 2]; 3] {
    std::array::from_fn(|n| std::array::from_fn(|r| v[n * 2 + r]))
}

/// Dense B = ∂vec(F)/∂x of a tet, column k = vec(F(e_k)) − vec(F(0)) (F is linear in x).
fn dense_b3(rest: &Rest<3>) -> SMatrix<f64, 9, 12> {
    let f0 = element_f(rest, &[[0.0; 3]; 4]);
    SMatrix::from_fn(|i, k| {
        let mut e = SVector::<f64, 12>::zeros();
        e[k] = 1.0;
        let f = element_f(rest, &unflat3(&e)) - f0;
        f[(i % 3, i / 3)]
    })
}

fn dense_b2(rest: &Rest<2>) -> SMatrix<f64, 4, 6> {
    let f0 = element_f(rest, &[[0.0; 2]; 3]);
    SMatrix::from_fn(|i, k| {
        let mut e = SVector::<f64, 6>::zeros();
        e[k] = 1.0;
        let f = element_f(rest, &unflat2(&e)) - f0;
        f[(i % 2, i / 2)]
    })
}

fn energies3() -> Vec<Box<dyn Energy<3>>> {
    vec![
        Box::new(Arap),
        Box::new(SymmetricDirichlet),
        Box::new(StableNeoHookean::new(1.3, 4.1)),
        Box::new(Poly),
    ]
}
fn energies2() -> Vec<Box<dyn Energy<2>>> {
    vec![
        Box::new(Arap),
        Box::new(SymmetricDirichlet),
        Box::new(StableNeoHookean::new(1.3, 4.1)),
        Box::new(Poly),
    ]
}

#[test]
fn rest_data_and_errors() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rest = Rest::<3>::new(p).unwrap();
    assert!((rest.measure - 1.0 / 6.0).abs() < 1e-15);
    assert!(max_diff(&element_f(&rest, &p), &Matrix3::identity()) < 1e-15);
    let inv = [p[0], p[2], p[1], p[3]];
    assert!(
        matches!(Rest::<3>::new(inv), Err(RestError::Inverted { measure }) if (measure + 1.0 / 6.0).abs() < 1e-15)
    );
    let flat = [p[0], p[1], p[2], [1.0, 1.0, 0.0]];
    assert!(matches!(
        Rest::<3>::new(flat),
        Err(RestError::Degenerate { .. })
    ));
    assert!(matches!(
        Rest::<3>::new([p[0], p[0], p[2], p[3]]),
        Err(RestError::Degenerate { .. })
    ));
    let mut nan = p;
    nan[2][1] = f64::NAN;
    assert!(
        matches!(Rest::<3>::new(nan), Err(RestError::Degenerate { measure }) if measure.is_nan())
    );
    let mut inf = p;
    inf[3][0] = f64::INFINITY;
    assert!(matches!(
        Rest::<3>::new(inf),
        Err(RestError::Degenerate { .. })
    ));
    // Error messages say what is wrong.
    assert!(
        Rest::<3>::new(inv)
            .unwrap_err()
            .to_string()
            .contains("inverted")
    );
    assert!(
        Rest::<3>::new(flat)
            .unwrap_err()
            .to_string()
            .contains("degenerate")
    );

    let t = [[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]];
    let tr = Rest::<2>::new(t).unwrap();
    assert!((tr.measure - 1.0).abs() < 1e-15);
    assert!(matches!(
        Rest::<2>::new([t[0], t[2], t[1]]),
        Err(RestError::Inverted { .. })
    ));
    assert!(matches!(
        Rest::<2>::new([t[0], t[1], [4.0, 0.0]]),
        Err(RestError::Degenerate { .. })
    ));
    assert!(matches!(
        Rest::<2>::from_3d([[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]),
        Err(RestError::Degenerate { .. })
    ));

    // A surface triangle is measured isometrically: embedding a planar triangle
    // rigidly in 3D (either orientation) gives F ∈ O(2) for its 2D positions.
    let mut r = rng(41);
    for _ in 0..50 {
        let t: [[f64; 2]; 3] =
            std::array::from_fn(|_| [r.gen_range(-1.0..1.0), r.gen_range(-1.0..1.0)]);
        let Ok(planar) = Rest::<2>::new(t) else {
            continue;
        };
        if planar.measure < 1e-2 {
            continue;
        }
        let q = rot3(&mut r);
        let p3: [[f64; 3]; 3] = std::array::from_fn(|n| {
            let y = q * nalgebra::Vector3::new(t[n][0], t[n][1], 0.0);
            [y[0] + 0.3, y[1], y[2] - 1.0]
        });
        let s = Rest::<2>::from_3d(p3).unwrap();
        assert!((s.measure - planar.measure).abs() < 1e-13);
        let f = element_f(&s, &t);
        assert!(
            max_diff(&(f.transpose() * f), &Matrix2::identity()) < 1e-12,
            "{f}"
        );
    }
}

#[test]
fn tet_kernels_match_differences_and_dense_chain_rule() {
    let mut r = rng(42);
    let mut fs: Vec<Matrix3<f64>> = random_f3(&mut r, 4);
    for case in hard_cases_3d() {
        if !case.antipodal {
            let (u, v) = (rot3(&mut r), rot3(&mut r));
            fs.push(compose(&u, &case.sigma, &v));
        }
    }
    let mut worst = (0.0f64, 0.0f64);
    for f in &fs {
        let p = random_tet(&mut r);
        let rest = Rest::<3>::new(p).unwrap();
        // x = F_target Dm ... chosen so that element_f(rest, x) = f exactly up to rounding.
        let x = deform3(&p, f, [0.3, -0.2, 0.7]);
        let fx = element_f(&rest, &x);
        let b = dense_b3(&rest);
        // Node steps δ change F by at most δ‖Dm⁻¹‖; keep them below σ_min(F)/‖Dm⁻¹‖
        // so barrier energies never see a step across det F = 0.
        let dm_norm = signed_svd3(&rest.dm_inv).sigma[0];
        let barrier_scale = signed_svd3(&fx).sigma[2].abs() / dm_norm;
        for e in energies3() {
            let scale = if e.info().barrier {
                barrier_scale
            } else {
                flat3(&x).amax().max(1.0) * 0.2
            };
            let label = format!("{} at F = {:?}", e.name(), f.as_slice());
            let raw = element_eval(e.as_ref(), &rest, &x, Filter::None, true);
            if !raw.psi.is_finite() {
                continue;
            }
            assert!(
                (raw.psi - element_psi(e.as_ref(), &rest, &x)).abs()
                    <= 1e-12 * raw.psi.abs().max(1.0)
            );
            let psi_x = |v: &SVector<f64, 12>| element_psi(e.as_ref(), &rest, &unflat3(v));
            let g_fd = fd_gradient(psi_x, &flat3(&x), scale);
            let gs = raw.grad.amax().max(1.0);
            let eg = (raw.grad - g_fd).amax() / gs;
            assert!(eg < GRAD_TOL, "{label}: element gradient error {eg:e}");
            let hs = raw.hess.amax().max(1.0);
            // Second differences only where the energy is comfortably smooth at this step scale.
            let smin = signed_svd3(&fx).sigma[2].abs();
            if smin > 1e-3 {
                let h_fd = fd_hessian(psi_x, &flat3(&x), scale);
                let eh = (raw.hess - h_fd).amax() / hs;
                worst.1 = worst.1.max(eh);
                assert!(eh < HESS_TOL, "{label}: element Hessian error {eh:e}");
            }
            worst.0 = worst.0.max(eg);
            // Structured chain rule vs dense Bᵀ H B, raw and every filter.
            let svd = signed_svd3(&fx);
            let s = e.spectral(&svd.sigma);
            for fl in [
                Filter::None,
                Filter::Clamp,
                Filter::ClampEps(1e-4),
                Filter::Abs,
            ] {
                let hf = hessian_f(&svd, &s, fl);
                let dense = b.transpose() * hf * b * rest.measure;
                let got = element_eval(e.as_ref(), &rest, &x, fl, true);
                let err = (got.hess - dense).amax() / dense.amax().max(1.0);
                assert!(err < CHAIN_TOL, "{label}: {fl:?} chain rule error {err:e}");
                assert_eq!(
                    got.hess,
                    got.hess.transpose(),
                    "{label}: {fl:?} not symmetric"
                );
                assert!(got.hess.iter().all(|v| v.is_finite()));
                assert_eq!(got.grad, raw.grad);
                if !fl.is_raw() {
                    let min = SymmetricEigen::new(got.hess).eigenvalues.min();
                    assert!(
                        min >= -1e-11 * got.hess.amax(),
                        "{label}: {fl:?} not PSD ({min:e})"
                    );
                }
            }
            // When the F-Hessian is already PSD, the filtered 12×12 equals the
            // numeric projection of the raw 12×12 (which is then PSD itself).
            let hraw = hessian_f(&svd, &s, Filter::None);
            if SymmetricEigen::new(hraw).eigenvalues.min() > 1e-9 * hraw.amax() {
                let clamp = element_eval(e.as_ref(), &rest, &x, Filter::Clamp, true);
                let num = project_psd_numeric(&raw.hess, Filter::Clamp);
                let err = (clamp.hess - num).amax() / hs;
                assert!(
                    err < 1e-11,
                    "{label}: clamp vs numeric 12×12 projection {err:e}"
                );
            }
            // Skipping the Hessian does not change ψ or the gradient.
            let light = element_eval(e.as_ref(), &rest, &x, Filter::Clamp, false);
            assert_eq!(light.psi, raw.psi);
            assert_eq!(light.grad, raw.grad);
            assert_eq!(light.hess, SMatrix::<f64, 12, 12>::zeros());
        }
    }
    println!(
        "tet kernels: worst gradient error {:e}, Hessian error {:e}",
        worst.0, worst.1
    );
}

#[test]
fn tri_kernels_match_differences_and_dense_chain_rule() {
    let mut r = rng(43);
    let mut fs: Vec<Matrix2<f64>> = random_f2(&mut r, 4);
    for case in hard_cases_2d() {
        if !case.antipodal {
            let (u, v) = (rot2(&mut r), rot2(&mut r));
            fs.push(compose(&u, &case.sigma, &v));
        }
    }
    for f in &fs {
        let p: [[f64; 2]; 3] = loop {
            let p: [[f64; 2]; 3] =
                std::array::from_fn(|_| [r.gen_range(-1.0..1.0), r.gen_range(-1.0..1.0)]);
            if Rest::<2>::new(p).is_ok_and(|t| t.measure > 0.05) {
                break p;
            }
        };
        let rest = Rest::<2>::new(p).unwrap();
        let x: [[f64; 2]; 3] = std::array::from_fn(|n| {
            let y = f * nalgebra::Vector2::new(p[n][0], p[n][1]);
            [y[0] - 0.4, y[1] + 0.1]
        });
        let fx = element_f(&rest, &x);
        let b = dense_b2(&rest);
        let dm_norm = signed_svd2(&rest.dm_inv).sigma[0];
        let barrier_scale = signed_svd2(&fx).sigma[1].abs() / dm_norm;
        for e in energies2() {
            let scale = if e.info().barrier {
                barrier_scale
            } else {
                flat2(&x).amax().max(1.0) * 0.2
            };
            let label = format!("{} at F = {:?}", e.name(), f.as_slice());
            let raw = element_eval(e.as_ref(), &rest, &x, Filter::None, true);
            if !raw.psi.is_finite() {
                continue;
            }
            // The SVD-free ψ (SD, SNH in 2D) agrees with ψ(σ).
            let via_svd = rest.measure * e.psi(&signed_svd2(&fx).sigma);
            let psi = element_psi(e.as_ref(), &rest, &x);
            assert!(
                (psi - via_svd).abs() <= 1e-9 * psi.abs().max(1.0),
                "{label}: {psi} vs {via_svd}"
            );
            let psi_x = |v: &SVector<f64, 6>| element_psi(e.as_ref(), &rest, &unflat2(v));
            let g_fd = fd_gradient(psi_x, &flat2(&x), scale);
            let eg = (raw.grad - g_fd).amax() / raw.grad.amax().max(1.0);
            assert!(eg < GRAD_TOL, "{label}: element gradient error {eg:e}");
            if signed_svd2(&fx).sigma[1].abs() > 1e-3 {
                let h_fd = fd_hessian(psi_x, &flat2(&x), scale);
                let eh = (raw.hess - h_fd).amax() / raw.hess.amax().max(1.0);
                assert!(eh < HESS_TOL, "{label}: element Hessian error {eh:e}");
            }
            let svd = signed_svd2(&fx);
            let s = e.spectral(&svd.sigma);
            for fl in [
                Filter::None,
                Filter::Clamp,
                Filter::ClampEps(1e-4),
                Filter::Abs,
            ] {
                let dense = b.transpose() * hessian_f(&svd, &s, fl) * b * rest.measure;
                let got = element_eval(e.as_ref(), &rest, &x, fl, true);
                let err = (got.hess - dense).amax() / dense.amax().max(1.0);
                assert!(err < CHAIN_TOL, "{label}: {fl:?} chain rule error {err:e}");
                assert_eq!(got.hess, got.hess.transpose());
            }
        }
    }
}

#[test]
fn singular_and_bad_input_never_leak_nan_into_filtered_output() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rest = Rest::<3>::new(p).unwrap();
    // Flattened tet: det F = 0 → SD is +∞, with zero gradient/Hessian.
    let flat = [p[0], p[1], p[2], [0.3, 0.3, 0.0]];
    let ev = element_eval(&SymmetricDirichlet, &rest, &flat, Filter::Clamp, true);
    assert_eq!(ev.psi, f64::INFINITY);
    assert!(ev.grad.iter().all(|v| *v == 0.0) && ev.hess.iter().all(|v| *v == 0.0));
    assert_eq!(
        element_psi(&SymmetricDirichlet, &rest, &flat),
        f64::INFINITY
    );
    // ARAP exactly on its twist pole (σ = (1.2, 0.9, −0.9)): raw Hessian has an
    // infinite mode, every filtered Hessian is finite, symmetric and PSD.
    let f = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.2, 0.9, -0.9));
    let x = deform3(&p, &f, [0.0; 3]);
    for fl in [Filter::Clamp, Filter::ClampEps(1e-6), Filter::Abs] {
        let ev = element_eval(&Arap, &rest, &x, fl, true);
        assert!(ev.psi.is_finite());
        assert!(ev.hess.iter().all(|v| v.is_finite()), "{fl:?}: {}", ev.hess);
        assert_eq!(ev.hess, ev.hess.transpose());
        // (The computed σ_1 + σ_2 is ~1e-16, not 0: Abs turns the pole into a
        // huge but finite stiffness, so the PSD check is relative.)
        let min = SymmetricEigen::new(ev.hess).eigenvalues.min();
        assert!(
            min >= -1e-12 * ev.hess.amax(),
            "{fl:?}: min eigenvalue {min:e}"
        );
    }
    let raw = element_eval(&Arap, &rest, &x, Filter::None, true);
    let big = raw.hess.iter().any(|v| !v.is_finite()) || raw.hess.amax() > 1e10;
    assert!(big, "the raw Hessian is genuinely singular there");
    // With σ exactly on the pole the raw mode is +∞ (every back end's pole
    // convention; the one-sided limits are ∓∞), filtered ones finite.
    let svd = ecc_runtime::Svd {
        u: Matrix3::identity(),
        sigma: [1.2, 0.9, -0.9],
        v: Matrix3::identity(),
    };
    let s = Arap.spectral(&svd.sigma);
    assert_eq!(s.twist[0], f64::INFINITY);
    assert!(
        hessian_f(&svd, &s, Filter::None)
            .iter()
            .any(|v| !v.is_finite())
    );
    for fl in [Filter::Clamp, Filter::ClampEps(1e-6), Filter::Abs] {
        let h = hessian_f(&svd, &s, fl);
        assert!(h.iter().all(|v| v.is_finite()), "{fl:?}");
        assert!(
            SymmetricEigen::new(h).eigenvalues.min() >= fl.floor() - 1e-12,
            "{fl:?}"
        );
    }
    // NaN / ∞ positions: ψ = NaN, zero derivatives, no panic.
    let mut bad = p;
    bad[1][2] = f64::NAN;
    let ev = element_eval(
        &StableNeoHookean::new(1.0, 1.0),
        &rest,
        &bad,
        Filter::Clamp,
        true,
    );
    assert!(ev.psi.is_nan());
    assert!(ev.grad.iter().all(|v| *v == 0.0) && ev.hess.iter().all(|v| *v == 0.0));
    assert!(element_psi(&Arap, &rest, &bad).is_nan());
    bad[1][2] = f64::INFINITY;
    assert!(
        element_eval(&Arap, &rest, &bad, Filter::Abs, true)
            .psi
            .is_nan()
    );
    let t = Rest::<2>::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).unwrap();
    let ev = element_eval(
        &SymmetricDirichlet,
        &t,
        &[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
        Filter::Clamp,
        true,
    );
    assert_eq!(ev.psi, f64::INFINITY);
    assert_eq!(
        element_psi(
            &SymmetricDirichlet,
            &t,
            &[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
        ),
        f64::INFINITY
    );
    assert!(
        element_eval(
            &Arap,
            &t,
            &[[f64::NAN, 0.0], [1.0, 0.0], [0.0, 1.0]],
            Filter::Clamp,
            true
        )
        .psi
        .is_nan()
    );
}
