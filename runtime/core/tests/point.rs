//! F-space checks for every energy, at the hard cases (under random rotations)
//! and at random F:
//!
//! * gradient and raw Hessian vs central differences of Ψ(F) (`reference::fd_*`),
//! * eigenpairs vs nalgebra's `SymmetricEigen` of the raw Hessian,
//! * filtered Hessians (every `Filter`) symmetric, finite, PSD, and equal to the
//!   numeric projection of the raw Hessian.

mod common;

use common::energies::*;
use common::*;
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::reference::{fd_gradient_vec, fd_hessian_f, project_psd_f};
use ecc_runtime::{
    Dim, Energy, FMat, FVec, Filter, Space, eigen_f, gradient_f, hessian_f, signed_svd,
};
use nalgebra::{DMatrix, DVector, SMatrix, SymmetricEigen};

/// Gradient vs central differences, relative to max(1, ‖g‖∞). The differences
/// reach ≈1e-10; a sign or factor-2 error gives O(1).
const GRAD_TOL: f64 = 1e-7;
/// Raw Hessian vs second central differences, relative to max(1, ‖H‖∞)
/// (the differences reach ≈1e-8 … 1e-7).
const HESS_TOL: f64 = 2e-5;
/// Analytic eigenvalues vs `SymmetricEigen` of the raw Hessian, relative to ‖H‖∞.
const EIG_TOL: f64 = 1e-11;
/// PSD / numeric-projection agreement, relative to ‖H‖∞.
const PSD_TOL: f64 = 1e-11;

const FILTERS: [Filter; 4] = [
    Filter::None,
    Filter::Clamp,
    Filter::ClampEps(1e-3),
    Filter::Abs,
];

struct Point {
    g: DVector<f64>,
    g_fd: Option<DVector<f64>>,
    h: DMatrix<f64>,
    h_fd: Option<DMatrix<f64>>,
    vals: Vec<f64>,
    vecs: Vec<DVector<f64>>,
    /// (filter, analytic filtered, numeric projection of the raw Hessian)
    filtered: Vec<(Filter, DMatrix<f64>, DMatrix<f64>)>,
}

/// A d² × d² F-space matrix as a dynamic one.
fn dynf<const D: usize>(m: &FMat<D>) -> DMatrix<f64>
where
    Space<D>: Dim<D>,
{
    DMatrix::from_fn(D * D, D * D, |i, j| m[(i, j)])
}

/// A d² F-space vector as a dynamic one.
fn dynv<const D: usize>(v: &FVec<D>) -> DVector<f64>
where
    Space<D>: Dim<D>,
{
    DVector::from_fn(D * D, |i, _| v[i])
}

fn eval<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>, fd: bool) -> Option<Point>
where
    Space<D>: Dim<D>,
{
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    if !s.psi.is_finite() {
        return None;
    }
    let h = hessian_f(&svd, &s, Filter::None);
    let (vals, vecs) = eigen_f(&svd, &s);
    Some(Point {
        g: dynv::<D>(&gradient_f(&svd, &s)),
        g_fd: fd.then(|| dynv::<D>(&fd_gradient_vec(e, f))),
        h: dynf::<D>(&h),
        h_fd: fd.then(|| dynf::<D>(&fd_hessian_f(e, f))),
        vals: vals.as_ref().to_vec(),
        vecs: vecs.as_ref().iter().map(dynv::<D>).collect(),
        filtered: FILTERS
            .iter()
            .map(|&fl| {
                (
                    fl,
                    dynf::<D>(&hessian_f(&svd, &s, fl)),
                    dynf::<D>(&project_psd_f::<D>(&h, fl)),
                )
            })
            .collect(),
    })
}

/// Worst relative errors seen, for the summary line.
#[derive(Default)]
struct Worst {
    grad: f64,
    hess: f64,
    eig: f64,
}

fn check(p: &Point, label: &str, worst: &mut Worst) {
    let gs = p.g.amax().max(1.0);
    if let Some(g_fd) = &p.g_fd {
        let err = (&p.g - g_fd).amax() / gs;
        worst.grad = worst.grad.max(err);
        assert!(
            err < GRAD_TOL,
            "{label}: gradient error {err:e}\n analytic {}\n fd {}",
            p.g,
            g_fd
        );
    }
    let raw_finite = p.h.iter().all(|x| x.is_finite());
    let hs = if raw_finite { p.h.amax().max(1.0) } else { 1.0 };
    if let (Some(h_fd), true) = (&p.h_fd, raw_finite) {
        let err = (&p.h - h_fd).amax() / hs;
        worst.hess = worst.hess.max(err);
        assert!(
            err < HESS_TOL,
            "{label}: Hessian error {err:e}\n analytic {}\n fd {}",
            p.h,
            h_fd
        );
    }
    if raw_finite {
        // Eigenvalues vs nalgebra; eigenpairs satisfy H e = λ e and are orthonormal.
        let mut theirs: Vec<f64> = SymmetricEigen::new(p.h.clone())
            .eigenvalues
            .iter()
            .copied()
            .collect();
        theirs.sort_by(|a, b| a.total_cmp(b));
        for (k, (a, b)) in p.vals.iter().zip(theirs.iter()).enumerate() {
            let err = (a - b).abs() / hs;
            worst.eig = worst.eig.max(err);
            assert!(
                err < EIG_TOL,
                "{label}: eigenvalue {k}: {:?} vs {theirs:?}",
                p.vals
            );
            let e = &p.vecs[k];
            assert!(
                (e.norm() - 1.0).abs() < 1e-12,
                "{label}: eigenvector {k} not unit"
            );
            let res = (&p.h * e - e * p.vals[k]).amax() / hs;
            assert!(res < EIG_TOL, "{label}: eigenpair {k} residual {res:e}");
            for (m, e2) in p.vecs.iter().enumerate().skip(k + 1) {
                assert!(
                    e.dot(e2).abs() < 1e-12,
                    "{label}: eigenvectors {k}, {m} not orthogonal"
                );
            }
        }
        for w in p.vals.windows(2) {
            assert!(
                w[0] <= w[1],
                "{label}: eigenvalues not ascending {:?}",
                p.vals
            );
        }
    }
    for (fl, ha, hn) in &p.filtered {
        if fl.is_raw() {
            if raw_finite {
                assert_eq!(ha, &p.h, "{label}: Filter::None must be the raw Hessian");
            }
            continue;
        }
        assert!(
            ha.iter().all(|x| x.is_finite()),
            "{label}: {fl:?} Hessian not finite\n{ha}"
        );
        assert_eq!(
            ha,
            &ha.transpose(),
            "{label}: {fl:?} Hessian not exactly symmetric"
        );
        let scale = ha.amax().max(1.0);
        let min = SymmetricEigen::new(ha.clone()).eigenvalues.min();
        let floor = fl.floor();
        assert!(
            min >= floor - PSD_TOL * scale,
            "{label}: {fl:?} min eigenvalue {min:e}"
        );
        if raw_finite {
            let err = (ha - hn).amax() / hs;
            assert!(
                err < PSD_TOL,
                "{label}: {fl:?} differs from numeric projection by {err:e}"
            );
        }
    }
}

type E3 = (Box<dyn Energy<3>>, bool);
type E2 = (Box<dyn Energy<2>>, bool);

/// (energy, sign-symmetric)
fn energies_3d() -> Vec<E3> {
    vec![
        (Box::new(Arap), false),
        (Box::new(SymmetricDirichlet), true),
        (Box::new(StableNeoHookean::new(1.3, 4.1)), true),
        (Box::new(ArapInv), false),
        (Box::new(Sd3Inv { decoupled: true }), true),
        (Box::new(Sd3Inv { decoupled: false }), true),
        (Box::new(Hencky), true),
        (Box::new(Poly), true),
        (Box::new(ArapStretch), false),
    ]
}

fn energies_2d() -> Vec<E2> {
    vec![
        (Box::new(Arap), false),
        (Box::new(SymmetricDirichlet), true),
        (Box::new(StableNeoHookean::new(1.3, 4.1)), true),
        (Box::new(Mips2), true),
        (Box::new(ArapInv), false),
        (Box::new(Sd2Inv { decoupled: true }), true),
        (Box::new(Sd2Inv { decoupled: false }), true),
        (Box::new(Hencky), true),
        (Box::new(Poly), true),
        (Box::new(ArapStretch), false),
    ]
}

#[test]
fn hard_cases_3d_all_energies() {
    let mut r = rng(21);
    let mut worst = Worst::default();
    for case in hard_cases_3d() {
        for (u, v) in rotations3(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (e, sym) in energies_3d() {
                // Central differences are meaningless across a genuine pole.
                let fd = sym || !case.antipodal;
                let label = format!("{} / {} / σ = {:?}", e.name(), case.name, case.sigma);
                if let Some(p) = eval(e.as_ref(), &f, fd) {
                    check(&p, &label, &mut worst);
                }
            }
        }
    }
    println!(
        "3D hard cases: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}

#[test]
fn hard_cases_2d_all_energies() {
    let mut r = rng(22);
    let mut worst = Worst::default();
    for case in hard_cases_2d() {
        for (u, v) in rotations2(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (e, sym) in energies_2d() {
                let fd = sym || !case.antipodal;
                let label = format!("{} / {} / σ = {:?}", e.name(), case.name, case.sigma);
                if let Some(p) = eval(e.as_ref(), &f, fd) {
                    check(&p, &label, &mut worst);
                }
            }
        }
    }
    println!(
        "2D hard cases: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}

#[test]
fn random_f() {
    let mut r = rng(23);
    let mut worst = Worst::default();
    for f in random_f3(&mut r, 12) {
        for (e, _) in energies_3d() {
            let label = format!("{} / random F = {:?}", e.name(), f.as_slice());
            if let Some(p) = eval(e.as_ref(), &f, true) {
                check(&p, &label, &mut worst);
            }
        }
    }
    for f in random_f2(&mut r, 12) {
        for (e, _) in energies_2d() {
            let label = format!("{} / random F = {:?}", e.name(), f.as_slice());
            if let Some(p) = eval(e.as_ref(), &f, true) {
                check(&p, &label, &mut worst);
            }
        }
    }
    println!(
        "random F: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}
