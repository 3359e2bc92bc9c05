//! One (F, a) point of `ecc check`'s fibre section: the runtime's lift of
//! ψ(I4, I5) to F-space against independent baselines.
//!
//! | check | analytic (`ecc_runtime::fibre::fibre_f`) | baseline |
//! |---|---|---|
//! | gradient | vec(∂ψ/∂F) = ψ4 g4 + ψ5 g5 (eq. P1 of `fibre/point.rs`) | central differences of ψ(I4(F), I5(F)) |
//! | hessian | raw ∂²ψ/∂f² (eq. P2, `Filter::None`) | central differences of the runtime's gradient (eq. P1), itself checked against ψ in the gradient column |
//! | eigenvalues | closed form 2ψ5 + 4ψ55 I5, 2ψ5 (×(d−1)), 0 (×(d²−d)) (eqs. P3–P5), when the runtime used it | nalgebra `SymmetricEigen` of the raw Hessian |
//! | projected | clamped Hessian (`Filter::Clamp`, whichever eigensystem the runtime picked) | `project_psd_numeric` of the raw Hessian |
//!
//! The baselines evaluate ψ only through the interpreter's ψ(I4, I5) and
//! the invariants I4 = aᵀ S a (signed polar decomposition), I5 = ‖F a‖²:
//! central differences on the same Richardson ladder as the isotropic check
//! (`ecc_runtime::reference::fd_gradient`: h_k = 0.1·s·2^{−k}, Richardson
//! (4D(h/2) − D(h))/3, the step of least disagreement; measured ≈1e-9
//! relative or better on the library's fibre energies, against tolerances
//! 1e-6 and 1e-5), step scale s = ‖F‖ or the local scale of
//! [`local_scale`]. Errors
//! are relative as in [`super::compare`] (gradient against
//! max(‖∂ψ/∂F‖∞, ‖H‖∞·‖F‖∞), matrices and eigenvalues against ‖H‖∞).
//!
//! Any NaN (ψ, gradient, raw or clamped Hessian, ψ's partials at a finite
//! ψ) is an infinite error, and so is ψ = −∞ (an energy is +∞ outside its
//! domain, never −∞). Skips, each with a note:
//! * ψ = +∞: outside ψ's domain (or an overflow, e.g. a Fung exponential at σ = 1e3);
//! * ψ(I4, I5) jumps at the point (e.g. sign(I4) at I4 = 0): no derivative
//!   exists, differences are skipped (the runtime's values must be finite);
//! * ψ's first or second partials are infinite at a finite ψ (√I5 or log I5
//!   at F a = 0): ψ is not differentiable there; the gradient (resp.
//!   Hessian) comparison is skipped and the clamped Hessian must be finite;
//! * ψ uses I4 and σi + σj is within 10⁻² of 0 (relative to max |σ|): I4's
//!   Hessian has the genuine pole 1/(σi + σj) of the polar decomposition
//!   there, which no finite step resolves.

use ecc_runtime::fibre::{FibreDim, fibre_f, i5_eigenvalues, invariant4, invariant5};
use ecc_runtime::reference::{fd_gradient, project_psd_f};
use ecc_runtime::{Dim, FMat, FibreEnergy, FibreUse, Filter, Space, signed_svd};
use nalgebra::{DMatrix, SMatrix, SVector, SymmetricEigen};

use super::compare::Errors;

/// Relative distance to σi + σj = 0 within which an I4 energy's differences are skipped.
const PLANE_BAND: f64 = 1e-2;

fn inf_norm<'a>(xs: impl IntoIterator<Item = &'a f64>) -> f64 {
    xs.into_iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// ‖a − b‖∞ / scale, ∞ when a difference is not finite.
fn rel_err(a: &[f64], b: &[f64], scale: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        if !d.is_finite() {
            return f64::INFINITY;
        }
        worst = worst.max(d);
    }
    worst / scale.max(f64::MIN_POSITIVE)
}

/// The d² × d² entries of an F-space matrix, column by column.
fn entries<const D: usize>(m: &FMat<D>) -> Vec<f64>
where
    Space<D>: Dim<D>,
{
    let n = D * D;
    (0..n * n).map(|k| m[(k % n, k / n)]).collect()
}

/// ψ(I4(F), I5(F)) (NaN for a non-finite F).
fn psi_of<const D: usize>(
    e: &dyn FibreEnergy<D>,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
) -> f64 {
    if !f.iter().all(|x| x.is_finite()) {
        return f64::NAN;
    }
    e.fibre_psi(invariant4(f, a), invariant5(f, a))
}

/// Whether ψ(I4, I5) jumps at (i4, i5): a one-sided difference in either
/// invariant that does not shrink when the offset shrinks 1000-fold (for a
/// continuous ψ it shrinks with the offset).
fn jumps<const D: usize>(e: &dyn FibreEnergy<D>, i4: f64, i5: f64, psi: f64) -> bool {
    let level = 1e-8 * psi.abs().max(1.0);
    let gap = |which: usize, d: f64| {
        let (p, m) = if which == 0 {
            (e.fibre_psi(i4 + d, i5), e.fibre_psi(i4 - d, i5))
        } else {
            (e.fibre_psi(i4, i5 + d), e.fibre_psi(i4, i5 - d))
        };
        (p - m).abs()
    };
    (0..2).any(|k| {
        let x = if k == 0 { i4 } else { i5 };
        let d1 = 1e-6 * x.abs().max(1.0);
        let (g1, g2) = (gap(k, d1), gap(k, 1e-3 * d1));
        g1.is_finite() && g2.is_finite() && g1 > level && g2 > 0.5 * g1
    })
}

/// vec(∂ψ/∂F) (column-major) by central differences, entry by entry.
fn fd_grad<const D: usize>(
    e: &dyn FibreEnergy<D>,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    scale: f64,
) -> Vec<f64> {
    (0..D * D)
        .map(|k| {
            let (r, c) = (k % D, k / D);
            let at = |x: &SVector<f64, 1>| {
                let mut g = *f;
                g[(r, c)] = x[0];
                psi_of(e, &g, a)
            };
            fd_gradient(at, &SVector::<f64, 1>::new(f[(r, c)]), scale)[0]
        })
        .collect()
}

/// The step scale of the differences at (F, a): ‖F‖, or the distance to
/// the nearest place where a fibre energy typically stops being smooth when
/// that is below 10⁻²·‖F‖: ‖F a‖ (the distance from F to {G : G a = 0},
/// the cone point of √I5 and pole of log I5) and, for ψ using I4, |I4|
/// (sign(I4) jumps at I4 = 0; |∂I4/∂F| ≤ 1 away from the poles).
fn local_scale<const D: usize>(
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    i4: f64,
    uses_i4: bool,
) -> (f64, bool) {
    let n = f.norm();
    let n = if n > 0.0 && n.is_finite() { n } else { 1.0 };
    let mut s = n;
    let fa = (f * a).norm();
    if fa > 0.0 {
        s = s.min(fa);
    }
    if uses_i4 && i4 != 0.0 {
        s = s.min(i4.abs());
    }
    if s < 1e-2 * n { (s, true) } else { (n, false) }
}

/// The difference baselines at one point.
struct Differences {
    gradient: Vec<f64>,
    hessian: Vec<f64>,
    note: Option<&'static str>,
}

/// Central differences (Richardson ladder) at step scale `scale`: of ψ for
/// the gradient, and of the runtime's raw analytic gradient (itself checked
/// against ψ's) for the Hessian, symmetrised. Second differences of ψ would
/// drown in rounding wherever ψ is large against its curvature (ε|ψ|/h²,
/// e.g. 3e-3 relative for k/2 (I4 − 1)² at σ = 1e3), first differences of
/// the gradient lose only ε|∇ψ|/h.
fn differences<const D: usize>(
    e: &dyn FibreEnergy<D>,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    (scale, local): (f64, bool),
) -> Differences
where
    Space<D>: FibreDim<D>,
{
    let gradient = fd_grad(e, f, a, scale);
    let n = D * D;
    let mut h = vec![0.0; n * n];
    for j in 0..n {
        let (r, c) = (j % D, j / D);
        for i in 0..n {
            let at = |x: &SVector<f64, 1>| {
                let mut g = *f;
                g[(r, c)] = x[0];
                fibre_f(e, &g, a, Filter::None, false).grad[i]
            };
            h[j * n + i] = fd_gradient(at, &SVector::<f64, 1>::new(f[(r, c)]), scale)[0];
        }
    }
    let sym: Vec<f64> = (0..n * n)
        .map(|k| 0.5 * (h[k] + h[(k % n) * n + k / n]))
        .collect();
    Differences {
        gradient,
        hessian: sym,
        note: local.then_some("near F a = 0 or I4 = 0: local step scale"),
    }
}

/// Compare the runtime's fibre eigensystem at (F, a) with the baselines.
pub fn compare_fibre<const D: usize>(
    e: &dyn FibreEnergy<D>,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
) -> Errors
where
    Space<D>: FibreDim<D>,
{
    let raw = fibre_f(e, f, a, Filter::None, true);
    let clamped = fibre_f(e, f, a, Filter::Clamp, true);
    let (i4, i5) = (invariant4(f, a), invariant5(f, a));
    let d = e.fibre(i4, i5);
    let fail = |note| Errors {
        gradient: Some(f64::INFINITY),
        note: Some(note),
        ..Errors::default()
    };
    if raw.psi.is_nan() {
        return fail("NaN psi");
    }
    if raw.psi == f64::INFINITY {
        return Errors {
            note: Some("psi = +inf (outside the domain, or overflow)"),
            ..Errors::default()
        };
    }
    if raw.psi == f64::NEG_INFINITY {
        return fail("psi = -inf (an energy is +inf outside its domain, never -inf)");
    }
    let h_raw = entries::<D>(&raw.hess);
    let h_clamped = entries::<D>(&clamped.hess);
    let grad: Vec<f64> = (0..D * D).map(|k| raw.grad[k]).collect();
    let partials = [d.d4, d.d5, d.d44, d.d45, d.d55];
    let nan = |xs: &[f64]| xs.iter().any(|x| x.is_nan());
    for (xs, note) in [
        (&grad[..], "NaN in the gradient"),
        (&h_raw[..], "NaN in the raw Hessian"),
        (&h_clamped[..], "NaN in the clamped Hessian"),
        (&partials[..], "NaN partial of psi(I4, I5) at a finite psi"),
    ] {
        if nan(xs) {
            return fail(note);
        }
    }
    let mut out = Errors::default();
    let first_ok = d.d4.is_finite() && d.d5.is_finite();
    let second_ok = first_ok && [d.d44, d.d45, d.d55].iter().all(|x| x.is_finite());
    let uses_i4 = matches!(e.uses(), FibreUse::I4 | FibreUse::Both)
        || d.d4 != 0.0
        || d.d44 != 0.0
        || d.d45 != 0.0;
    let sigma = signed_svd(f).sigma;
    let at_pole = uses_i4
        && (0..D).any(|i| {
            (i + 1..D).any(|j| {
                (sigma[i] + sigma[j]).abs() <= PLANE_BAND * sigma[i].abs().max(sigma[j].abs())
            })
        });
    if jumps(e, i4, i5, raw.psi) {
        out.note = Some("psi(I4, I5) jumps here (e.g. sign(I4) at I4 = 0): differences skipped");
    } else if !first_ok {
        out.note = Some("psi's partials are infinite (not differentiable): differences skipped");
    } else if at_pole {
        out.note = Some("differences skipped: at the pole sigma_i + sigma_j = 0 of I4's Hessian");
    } else {
        let fd = differences(e, f, a, local_scale(f, a, i4, uses_i4));
        let h_scale = inf_norm(&fd.hessian);
        let g_scale = inf_norm(&fd.gradient).max(h_scale * inf_norm(f.iter()));
        out.gradient = Some(rel_err(&grad, &fd.gradient, g_scale));
        out.note = fd.note;
        if second_ok {
            out.hessian = Some(rel_err(&h_raw, &fd.hessian, h_scale));
        } else {
            out.note = Some("psi's second partials are infinite: hessian differences skipped");
        }
    }
    if out.gradient.is_none() && !grad.iter().all(|x| x.is_finite()) {
        out.gradient = Some(f64::INFINITY);
        out.note = Some("gradient not finite at a finite psi");
        return out;
    }
    let raw_may_be_infinite = !second_ok || at_pole;
    eigen_checks::<D>(
        &mut out,
        (&h_raw, &h_clamped),
        raw_may_be_infinite,
        clamped.path,
        &d,
        i5,
    );
    out
}

/// The eigenvalue and projection columns (see the module docs). The raw
/// Hessian may be non-finite only where ψ's second partials are or at a
/// pole of I4's Hessian; the clamped one never.
fn eigen_checks<const D: usize>(
    out: &mut Errors,
    (h_raw, h_clamped): (&[f64], &[f64]),
    raw_may_be_infinite: bool,
    path: ecc_runtime::fibre::FibrePath,
    d: &ecc_runtime::FibreDerivs,
    i5: f64,
) where
    Space<D>: Dim<D>,
{
    let n = D * D;
    if !h_clamped.iter().all(|x| x.is_finite()) {
        out.projected = Some(f64::INFINITY);
        out.note = Some("clamped Hessian not finite");
        return;
    }
    if !h_raw.iter().all(|x| x.is_finite()) {
        if raw_may_be_infinite {
            out.note
                .get_or_insert("raw Hessian not finite (psi not twice differentiable)");
        } else {
            out.projected = Some(f64::INFINITY);
            out.note = Some("raw Hessian not finite where psi's partials are");
        }
        return;
    }
    let h = DMatrix::from_column_slice(n, n, h_raw);
    let h = (&h + h.transpose()) * 0.5;
    let scale = inf_norm(h.iter());
    let mut lam: Vec<f64> = SymmetricEigen::new(h.clone())
        .eigenvalues
        .iter()
        .copied()
        .collect();
    lam.sort_by(f64::total_cmp);
    if path == ecc_runtime::fibre::FibrePath::ClosedI5 {
        let [along, across, zero] = i5_eigenvalues(d, i5);
        let mut closed = vec![along];
        closed.extend(std::iter::repeat_n(across, D - 1));
        closed.extend(std::iter::repeat_n(zero, n - D));
        closed.sort_by(f64::total_cmp);
        out.eigenvalues = Some(rel_err(&closed, &lam, scale));
    }
    let raw_fmat = <Space<D> as Dim<D>>::fmat_from_fn(&mut |i, j| h[(i, j)]);
    let num = entries::<D>(&project_psd_f::<D>(&raw_fmat, Filter::Clamp));
    out.projected = Some(rel_err(h_clamped, &num, scale));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::TOLERANCES;
    use ecc_runtime::FibreDerivs;

    /// k (I5 − 1)² (+ c I4²) with deliberately scaled partials.
    struct Broken {
        d5: f64,
        d55: f64,
        with_i4: bool,
    }

    impl FibreEnergy<3> for Broken {
        fn name(&self) -> &str {
            "broken"
        }
        fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs {
            // The runtime passes no I4 (NaN) to a ψ of I5 alone.
            let (c, i4) = if self.with_i4 { (0.5, i4) } else { (0.0, 0.0) };
            FibreDerivs {
                psi: (i5 - 1.0).powi(2) + c * i4 * i4,
                d4: 2.0 * c * i4,
                d5: 2.0 * (i5 - 1.0) * self.d5,
                d44: 2.0 * c,
                d45: 0.0,
                d55: 2.0 * self.d55,
            }
        }
        fn uses(&self) -> FibreUse {
            if self.with_i4 {
                FibreUse::Both
            } else {
                FibreUse::I5
            }
        }
    }

    fn at(e: &Broken) -> Errors {
        let f = SMatrix::<f64, 3, 3>::new(1.2, 0.3, -0.1, 0.2, 0.9, 0.1, 0.0, -0.2, 1.1);
        let a = SVector::<f64, 3>::new(1.0, 2.0, 2.0) / 3.0;
        compare_fibre::<3>(e, &f, &a)
    }

    #[test]
    fn wrong_fibre_derivatives_are_caught() {
        for with_i4 in [false, true] {
            let good = at(&Broken {
                d5: 1.0,
                d55: 1.0,
                with_i4,
            });
            let cols = [
                good.gradient,
                good.hessian,
                good.eigenvalues,
                good.projected,
            ];
            for (k, e) in cols.iter().enumerate() {
                // The closed-form eigenvalues exist only without I4.
                if with_i4 && k == 2 {
                    assert!(e.is_none());
                    continue;
                }
                assert!(e.unwrap() <= TOLERANCES[k], "{with_i4} check {k}: {good:?}");
            }
            let bad_grad = at(&Broken {
                d5: 1.001,
                d55: 1.0,
                with_i4,
            });
            assert!(bad_grad.gradient.unwrap() > TOLERANCES[0], "{bad_grad:?}");
            let bad_hess = at(&Broken {
                d5: 1.0,
                d55: 1.1,
                with_i4,
            });
            assert!(bad_hess.hessian.unwrap() > TOLERANCES[1], "{bad_hess:?}");
        }
    }

    #[test]
    fn a_jump_in_i4_is_detected_and_smooth_psi_is_not() {
        struct Sign;
        impl FibreEnergy<3> for Sign {
            fn name(&self) -> &str {
                "sign"
            }
            fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs {
                FibreDerivs {
                    psi: i5 - i4.signum(),
                    d5: 1.0,
                    ..FibreDerivs::default()
                }
            }
            fn uses(&self) -> FibreUse {
                FibreUse::Both
            }
        }
        assert!(jumps::<3>(&Sign, 0.0, 1.0, 0.0));
        assert!(!jumps::<3>(&Sign, 0.5, 1.0, 0.0));
        let smooth = Broken {
            d5: 1.0,
            d55: 1.0,
            with_i4: true,
        };
        assert!(!jumps::<3>(&smooth, 0.0, 1.0, 0.0));
    }
}
