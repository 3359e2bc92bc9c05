//! F-space checks of one energy at one deformation gradient.
//!
//! At F = U diag(σ) Vᵀ the energy's [`Spectral`] is
//! lifted by the runtime to vec(∂Ψ/∂F), the raw Hessian ∂²Ψ/∂f², its
//! analytic eigenpairs and the filtered Hessians. [`check_f`] tests
//!
//! * Ψ from `psi` equals Ψ from `spectral` (and from `psi_i2_i3` when offered);
//! * the gradient and the raw Hessian against central differences of Ψ(F)
//!   ([`crate::reference`], whose step ladder picks each entry's step
//!   automatically), relative to max(1, max-norm). Where the ladder picks a
//!   poor step for some Hessian entry (it happens at σ = (1e3, 1.2, 0.9) under
//!   some rotations, for the hand-written ARAP as well), the Hessian is also
//!   compared with Richardson-extrapolated second differences of Ψ(F) at
//!   fixed steps h = 10⁻², 10⁻³ × min|σ|; it must agree with one of them;
//! * the analytic eigenvalues against nalgebra's `SymmetricEigen` of the raw
//!   Hessian, the eigenpair residuals and orthonormality;
//! * every filtered Hessian: finite, exactly symmetric, PSD (down to the
//!   filter's floor) and equal to the numeric projection of the raw Hessian.

use crate::reference::{fd_gradient_f, fd_hessian_f, project_psd_f, psi_f};
use crate::{
    Dim, Energy, FMat, FVec, Filter, Space, Spectral, Svd, eigen_f, gradient_f, hessian_f,
    signed_svd,
};
use nalgebra::{DMatrix, DVector, SMatrix, SymmetricEigen};

/// |a − b| ≤ tol · max(1, |a|, |b|), with equal non-finite values (same
/// infinity, or both NaN) accepted.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    if !a.is_finite() || !b.is_finite() {
        return a == b || (a.is_nan() && b.is_nan());
    }
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

/// Gradient vs central differences (which reach ≈1e-10; a wrong factor gives O(1)).
pub const GRAD_TOL: f64 = 1e-7;
/// Raw Hessian vs second central differences (which reach ≈1e-8 … 1e-7).
pub const HESS_TOL: f64 = 2e-5;
/// Analytic eigenvalues vs `SymmetricEigen`, relative to ‖H‖∞.
pub const EIG_TOL: f64 = 1e-11;
/// PSD and numeric-projection agreement, relative to ‖H‖∞.
pub const PSD_TOL: f64 = 1e-11;

/// The filters every point is checked with.
pub const FILTERS: [Filter; 4] = [
    Filter::None,
    Filter::Clamp,
    Filter::ClampEps(1e-3),
    Filter::Abs,
];

/// Worst relative errors seen (for a summary line).
#[derive(Clone, Copy, Debug, Default)]
pub struct Worst {
    /// Gradient vs differences.
    pub grad: f64,
    /// Raw Hessian vs differences.
    pub hess: f64,
    /// Eigenvalues vs `SymmetricEigen`.
    pub eig: f64,
    /// Points checked.
    pub points: usize,
}

struct Point {
    g: DVector<f64>,
    g_fd: Option<DVector<f64>>,
    h: DMatrix<f64>,
    h_fd: Option<DMatrix<f64>>,
    vals: Vec<f64>,
    vecs: Vec<DVector<f64>>,
    filtered: Vec<(Filter, DMatrix<f64>, DMatrix<f64>)>,
}

/// Richardson-extrapolated second central differences of `psi` at `x`
/// with step `h`: (4 D(h/2) − D(h))/3 entrywise.
fn fd_hessian_fixed(psi: &dyn Fn(&[f64]) -> f64, x: &[f64], h: f64) -> DMatrix<f64> {
    let n = x.len();
    let d = |h: f64| {
        let mut m = DMatrix::zeros(n, n);
        for i in 0..n {
            for j in i..n {
                let at = |a: f64, b: f64| {
                    let mut y = x.to_vec();
                    y[i] += a;
                    y[j] += b;
                    psi(&y)
                };
                let v = (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4.0 * h * h);
                m[(i, j)] = v;
                m[(j, i)] = v;
            }
        }
        m
    };
    (d(0.5 * h) * 4.0 - d(h)) / 3.0
}

/// The fixed-step estimates of the Hessian of Ψ(F) (see the module docs).
fn fixed_step_hessians<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    sigma_min: f64,
) -> Vec<DMatrix<f64>> {
    let psi = |y: &[f64]| psi_f(e, &SMatrix::<f64, D, D>::from_column_slice(y));
    [1e-2, 1e-3]
        .iter()
        .map(|c| fd_hessian_fixed(&psi, f.as_slice(), c * sigma_min.max(1e-6)))
        .collect()
}

/// Tolerance for Ψ(I2, I3) vs Ψ(σ): det F and the smallest σ each lose
/// ≈ ε‖F‖^D/|det F| relatively, and Ψ may depend on them like 1/I3².
fn i2_i3_tol(norm: f64, det: f64, dim: i32) -> f64 {
    let cond = norm.powi(dim) / det.abs().max(f64::MIN_POSITIVE);
    1e-10 + 32.0 * f64::EPSILON * cond
}

fn psi_agrees(label: &str, a: f64, b: f64, what: &str) -> Result<(), String> {
    if close(a, b, 1e-12) {
        Ok(())
    } else {
        Err(format!("{label}: {what} {a:e} vs spectral Ψ {b:e}"))
    }
}

fn dynv<const D: usize>(v: &FVec<D>) -> DVector<f64>
where
    Space<D>: Dim<D>,
{
    DVector::from_fn(D * D, |i, _| v[i])
}

fn dynf<const D: usize>(m: &FMat<D>) -> DMatrix<f64>
where
    Space<D>: Dim<D>,
{
    DMatrix::from_fn(D * D, D * D, |i, j| m[(i, j)])
}

/// The runtime's F-space lift of a [`Spectral`] at one SVD: a [`Point`]
/// without the finite-difference parts.
fn lift<const D: usize>(svd: &Svd<D>, s: &Spectral<D>) -> Point
where
    Space<D>: Dim<D>,
{
    let raw = hessian_f(svd, s, Filter::None);
    let h = dynf::<D>(&raw);
    let (vals, vecs) = eigen_f(svd, s);
    Point {
        g: dynv::<D>(&gradient_f(svd, s)),
        g_fd: None,
        vals: vals.as_ref().to_vec(),
        vecs: vecs.as_ref().iter().map(dynv::<D>).collect(),
        filtered: FILTERS
            .iter()
            .map(|&fl| {
                (
                    fl,
                    dynf::<D>(&hessian_f(svd, s, fl)),
                    dynf::<D>(&project_psd_f::<D>(&raw, fl)),
                )
            })
            .collect(),
        h,
        h_fd: None,
    }
}

/// Check an energy at F (`fd`: also compare with central differences), for
/// d = 2 or 3. `Ok(false)` when F is outside the energy's domain (Ψ = +∞).
pub fn check_f<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    fd: bool,
    label: &str,
    worst: &mut Worst,
) -> Result<bool, String>
where
    Space<D>: Dim<D>,
{
    let svd = signed_svd(f);
    let det = <Space<D> as Dim<D>>::det(f);
    let s = e.spectral(&svd.sigma);
    psi_agrees(label, e.psi(&svd.sigma), s.psi, "psi(σ)")?;
    if e.info().svd_free_psi {
        let p = e.psi_i2_i3(f.norm_squared(), det);
        let p = p.ok_or_else(|| format!("{label}: svd_free_psi without psi_i2_i3"))?;
        if !close(p, s.psi, i2_i3_tol(f.norm(), det, D as i32)) {
            return Err(format!(
                "{label}: psi_i2_i3 {p:e} vs spectral Ψ {:e}",
                s.psi
            ));
        }
    }
    if !s.psi.is_finite() {
        return Ok(false);
    }
    check_point(e, f, (&svd, &s), fd, true, label, worst)?;
    Ok(true)
}

/// [`check_f`] without the Ψ cross-checks and without the fixed-step
/// fallback for the Hessian: the lift alone, against the step ladder only
/// (the runtime's own tests, whose hand-written energies need no fallback).
pub fn check_lift<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    fd: bool,
    label: &str,
    worst: &mut Worst,
) -> Result<bool, String>
where
    Space<D>: Dim<D>,
{
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    if !s.psi.is_finite() {
        return Ok(false);
    }
    check_point(e, f, (&svd, &s), fd, false, label, worst)?;
    Ok(true)
}

/// The lift at one F (with differences when `fd`), checked; `fallback`
/// admits the fixed-step Hessians (see the module docs).
fn check_point<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    (svd, s): (&Svd<D>, &Spectral<D>),
    fd: bool,
    fallback: bool,
    label: &str,
    worst: &mut Worst,
) -> Result<(), String>
where
    Space<D>: Dim<D>,
{
    let p = Point {
        g_fd: fd.then(|| DVector::from_column_slice(fd_gradient_f(e, f).as_slice())),
        h_fd: fd.then(|| dynf::<D>(&fd_hessian_f(e, f))),
        ..lift(svd, s)
    };
    let smin = svd.sigma.iter().fold(f64::INFINITY, |m, x| m.min(x.abs()));
    let fixed = || {
        if fallback {
            fixed_step_hessians(e, f, smin)
        } else {
            Vec::new()
        }
    };
    check(&p, label, worst, &fixed)
}

fn check(
    p: &Point,
    label: &str,
    worst: &mut Worst,
    fixed: &dyn Fn() -> Vec<DMatrix<f64>>,
) -> Result<(), String> {
    worst.points += 1;
    let gs = p.g.amax().max(1.0);
    if let Some(g_fd) = &p.g_fd {
        let err = (&p.g - g_fd).amax() / gs;
        worst.grad = worst.grad.max(err);
        if err >= GRAD_TOL {
            return Err(format!(
                "{label}: gradient error {err:e}\n analytic {}\n fd {}",
                p.g, g_fd
            ));
        }
    }
    let raw_finite = p.h.iter().all(|x| x.is_finite());
    let hs = if raw_finite { p.h.amax().max(1.0) } else { 1.0 };
    if let (Some(h_fd), true) = (&p.h_fd, raw_finite) {
        let mut err = (&p.h - h_fd).amax() / hs;
        if err >= HESS_TOL {
            for m in fixed() {
                err = err.min((&p.h - m).amax() / hs);
            }
        }
        worst.hess = worst.hess.max(err);
        if err >= HESS_TOL {
            return Err(format!(
                "{label}: Hessian error {err:e}\n analytic {}\n fd {}",
                p.h, h_fd
            ));
        }
    }
    if raw_finite {
        check_eigen(p, label, hs, worst)?;
    }
    for (fl, ha, hn) in &p.filtered {
        if fl.is_raw() {
            if raw_finite && ha != &p.h {
                return Err(format!("{label}: Filter::None is not the raw Hessian"));
            }
            continue;
        }
        if !ha.iter().all(|x| x.is_finite()) {
            return Err(format!("{label}: {fl:?} Hessian not finite\n{ha}"));
        }
        if ha != &ha.transpose() {
            return Err(format!("{label}: {fl:?} Hessian not exactly symmetric"));
        }
        let scale = ha.amax().max(1.0);
        let min = SymmetricEigen::new(ha.clone()).eigenvalues.min();
        if min < fl.floor() - PSD_TOL * scale {
            return Err(format!("{label}: {fl:?} min eigenvalue {min:e}"));
        }
        if raw_finite {
            let err = (ha - hn).amax() / hs;
            if err >= PSD_TOL {
                return Err(format!(
                    "{label}: {fl:?} differs from the numeric projection by {err:e}"
                ));
            }
        }
    }
    Ok(())
}

fn check_eigen(p: &Point, label: &str, hs: f64, worst: &mut Worst) -> Result<(), String> {
    let mut theirs: Vec<f64> = SymmetricEigen::new(p.h.clone())
        .eigenvalues
        .iter()
        .copied()
        .collect();
    theirs.sort_by(|a, b| a.total_cmp(b));
    if p.vals.windows(2).any(|w| w[0] > w[1]) {
        return Err(format!("{label}: eigenvalues not ascending {:?}", p.vals));
    }
    for (k, (a, b)) in p.vals.iter().zip(&theirs).enumerate() {
        let err = (a - b).abs() / hs;
        worst.eig = worst.eig.max(err);
        if err >= EIG_TOL {
            return Err(format!(
                "{label}: eigenvalue {k}: {:?} vs SymmetricEigen {theirs:?}",
                p.vals
            ));
        }
        let e = &p.vecs[k];
        if (e.norm() - 1.0).abs() >= 1e-12 {
            return Err(format!("{label}: eigenvector {k} not unit"));
        }
        let res = (&p.h * e - e * p.vals[k]).amax() / hs;
        if res >= EIG_TOL {
            return Err(format!("{label}: eigenpair {k} residual {res:e}"));
        }
        for (m, e2) in p.vecs.iter().enumerate().skip(k + 1) {
            if e.dot(e2).abs() >= 1e-12 {
                return Err(format!("{label}: eigenvectors {k}, {m} not orthogonal"));
            }
        }
    }
    Ok(())
}
