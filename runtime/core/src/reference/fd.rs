//! Central differences with an automatically chosen step.
//!
//! For Ψ(F) the length scale is ‖F‖, reduced to σ_min for barrier energies
//! (`info().barrier`) so no step crosses det F = 0.
//!
//! A fixed step cannot suit every point (Symmetric Dirichlet at σ = 10⁻⁶ needs
//! h ≪ 10⁻⁶, while a polynomial energy there needs h ≈ 10⁻⁴ to beat rounding),
//! so every derivative is estimated on a ladder of steps h_k = 0.1·s·2^{−k}
//! (s = the caller's length scale, k = 0..[`LADDER`]) and improved by Richardson
//! extrapolation R_k = (4D(h_k/2) − D(h_k))/3 (error O(h⁴)). The returned value
//! is the R_k with the smallest disagreement |R_k − R_{k+1}|, i.e. where
//! truncation and rounding error balance; estimates that hit a non-finite Ψ
//! (e.g. a step crossing a barrier) are skipped; each error estimate includes
//! a rounding-noise model (see `ladder`). Typical accuracy: ≈10⁻¹⁰
//! relative for gradients, ≈10⁻⁷ for Hessians, on smooth energies.

use super::psi_f;
use crate::dim::{Dim, FMat, FVec, Space};
use crate::energy::Energy;
use crate::svd::signed_svd;
use nalgebra::{SMatrix, SVector};

/// Number of steps on the ladder (the smallest is 0.1·s·2^-LADDER ≈ 10⁻⁹·s).
pub const LADDER: usize = 27;

/// Pick the best Richardson estimate from a ladder of central estimates `est(h)`
/// of a derivative of the given `order` (1 or 2). The error of step k is
/// estimated as the Richardson disagreement plus a rounding-noise model
/// 8ε·(max(fscale, 1)/h^order + |R_k|·xscale/h): the first term is the
/// rounding of Ψ itself (the floor 1 stands for the intermediate terms of an
/// energy that happens to vanish at x, e.g. ARAP's I2 − 2I1 + d at rest), the
/// second the quantisation of the perturbed input (entries of size `xscale`
/// carry an absolute error ≈ ε·xscale, which dominates for ill-conditioned F
/// such as σ_min = 10⁻⁶ ≪ ‖F‖). Without it, steps so small that differences
/// round to 0 or to a quantised plateau would look perfectly converged.
fn ladder(
    scale: f64,
    xscale: f64,
    order: i32,
    fscale: f64,
    mut est: impl FnMut(f64) -> f64,
) -> f64 {
    let mut d: [f64; LADDER + 2] = [f64::NAN; LADDER + 2];
    let h0 = 0.1 * scale;
    for (k, dk) in d.iter_mut().enumerate() {
        *dk = est(h0 * 0.5f64.powi(k as i32));
    }
    let r: Vec<f64> = (0..LADDER + 1)
        .map(|k| (4.0 * d[k + 1] - d[k]) / 3.0)
        .collect();
    let mut best = f64::NAN;
    let mut best_err = f64::INFINITY;
    for k in 0..LADDER {
        let h = h0 * 0.5f64.powi(k as i32 + 2);
        let noise = fscale.max(1.0) / h.powi(order) + r[k + 1].abs() * xscale / h;
        let err = (r[k] - r[k + 1]).abs() + 8.0 * f64::EPSILON * noise;
        if r[k].is_finite() && r[k + 1].is_finite() && err < best_err {
            best_err = err;
            best = r[k + 1];
        }
    }
    best
}

/// Gradient of a scalar function of N variables by central differences;
/// `scale` is the length scale of `x` (e.g. its norm or an edge length).
pub fn fd_gradient<const N: usize>(
    f: impl Fn(&SVector<f64, N>) -> f64,
    x: &SVector<f64, N>,
    scale: f64,
) -> SVector<f64, N> {
    let fscale = f(x).abs();
    let xscale = x.amax();
    SVector::from_fn(|i, _| {
        ladder(scale, xscale, 1, fscale, |h| {
            let mut xp = *x;
            let mut xm = *x;
            xp[i] += h;
            xm[i] -= h;
            (f(&xp) - f(&xm)) / (2.0 * h)
        })
    })
}

/// Hessian of a scalar function of N variables by second central differences
/// of the function values (symmetric by construction).
pub fn fd_hessian<const N: usize>(
    f: impl Fn(&SVector<f64, N>) -> f64,
    x: &SVector<f64, N>,
    scale: f64,
) -> SMatrix<f64, N, N> {
    let f0 = f(x);
    let xscale = x.amax();
    let mut h = SMatrix::<f64, N, N>::zeros();
    for i in 0..N {
        for j in i..N {
            let v = ladder(scale, xscale, 2, f0.abs(), |s| {
                let at = |di: f64, dj: f64| {
                    let mut y = *x;
                    y[i] += di;
                    y[j] += dj;
                    f(&y)
                };
                if i == j {
                    (at(s, 0.0) - 2.0 * f0 + at(-s, 0.0)) / (s * s)
                } else {
                    (at(s, s) - at(s, -s) - at(-s, s) + at(-s, -s)) / (4.0 * s * s)
                }
            });
            h[(i, j)] = v;
            h[(j, i)] = v;
        }
    }
    h
}

/// Step scale for differences of Ψ(F): ‖F‖, or the distance σ_min to the
/// nearest singular matrix when smaller and the energy's domain ends at
/// det F = 0 — a barrier energy, or one that is `+∞` at the mirror point
/// (see [`domain_ends_at_det_zero`]). Steps must not jump across det F = 0:
/// such energies are singular or undefined there, and a barrier energy,
/// being even in σ_min, would give smooth but meaningless differences.
fn scale_of<E: Energy<D> + ?Sized, const D: usize>(e: &E, f: &SMatrix<f64, D, D>) -> f64 {
    let n = f.norm();
    let n = if n > 0.0 && n.is_finite() { n } else { 1.0 };
    let sigma = signed_svd(f).sigma;
    let smin = sigma[D - 1].abs();
    if smin > 0.0 && smin < n && (e.info().barrier || domain_ends_at_det_zero(e, &sigma)) {
        return smin;
    }
    n
}

/// Ψ is finite at σ but `+∞` at its mirror image σ_min ↦ −σ_min across
/// det F = 0: the domain of what was written ends there (`exp(log(I3))`,
/// `I3^(3/2)`), though Ψ need not blow up (not a barrier).
fn domain_ends_at_det_zero<E: Energy<D> + ?Sized, const D: usize>(e: &E, sigma: &[f64; D]) -> bool {
    let mut mirror = *sigma;
    mirror[D - 1] = -mirror[D - 1];
    e.psi(sigma).is_finite() && !e.psi(&mirror).is_finite()
}

/// The point is within 10⁻²‖F‖ of a domain edge at det F = 0 of an energy
/// that stays O(1) there. Second differences of Ψ cannot resolve its
/// Hessian: steps must stay below σ_min, and the rounding of Ψ then costs
/// ε·|Ψ|/h² ≫ the tolerance. A barrier energy has no such problem (its
/// Hessian grows like Ψ/σ_min²).
fn near_a_soft_domain_edge<E: Energy<D> + ?Sized, const D: usize>(
    e: &E,
    f: &SMatrix<f64, D, D>,
) -> bool {
    let sigma = signed_svd(f).sigma;
    let smin = sigma[D - 1].abs();
    !e.info().barrier && smin > 0.0 && smin < 1e-2 * f.norm() && domain_ends_at_det_zero(e, &sigma)
}

/// ∂²Ψ/∂f² by central first differences of the analytic gradient
/// vec(∂Ψ/∂F) (which the checkers verify separately against differences of
/// Ψ), with steps below σ_min: rounding costs only ε·|∇Ψ|/h. Symmetrised.
fn fd_hessian_from_gradient<E: Energy<D> + ?Sized, const D: usize>(
    e: &E,
    f: &SMatrix<f64, D, D>,
) -> FMat<D>
where
    Space<D>: Dim<D>,
{
    let grad = |m: &SMatrix<f64, D, D>| {
        let svd = signed_svd(m);
        crate::point::gradient_f(&svd, &e.spectral(&svd.sigma))
    };
    let (n, s, xscale, g0) = (D * D, scale_of(e, f), f.amax(), grad(f));
    let mut h = vec![0.0; n * n];
    for j in 0..n {
        let (r, c) = (j % D, j / D);
        for i in 0..n {
            h[i * n + j] = ladder(s, xscale, 1, g0[i].abs(), |step| {
                let (mut fp, mut fm) = (*f, *f);
                fp[(r, c)] += step;
                fm[(r, c)] -= step;
                (grad(&fp)[i] - grad(&fm)[i]) / (2.0 * step)
            });
        }
    }
    <Space<D> as Dim<D>>::fmat_from_fn(&mut |i, j| 0.5 * (h[i * n + j] + h[j * n + i]))
}

/// ∂Ψ/∂F (as a matrix) by central differences of Ψ(F), for D = 2 or 3.
pub fn fd_gradient_f<E: Energy<D> + ?Sized, const D: usize>(
    e: &E,
    f: &SMatrix<f64, D, D>,
) -> SMatrix<f64, D, D> {
    let s = scale_of(e, f);
    let fscale = psi_f(e, f).abs();
    let xscale = f.amax();
    SMatrix::from_fn(|r, c| {
        ladder(s, xscale, 1, fscale, |h| {
            let mut fp = *f;
            let mut fm = *f;
            fp[(r, c)] += h;
            fm[(r, c)] -= h;
            (psi_f(e, &fp) - psi_f(e, &fm)) / (2.0 * h)
        })
    })
}

/// vec(∂Ψ/∂F) (column-major, d² entries) by central differences of Ψ(F).
pub fn fd_gradient_vec<E: Energy<D> + ?Sized, const D: usize>(
    e: &E,
    f: &SMatrix<f64, D, D>,
) -> FVec<D>
where
    Space<D>: Dim<D>,
{
    <Space<D> as Dim<D>>::vec(&fd_gradient_f(e, f))
}

/// ∂²Ψ/∂f² (d²×d², column-major vec) by second central differences of Ψ(F);
/// near a domain edge at det F = 0 of a non-barrier energy, by first
/// differences of the analytic gradient instead (see `near_a_soft_domain_edge`).
pub fn fd_hessian_f<E: Energy<D> + ?Sized, const D: usize>(e: &E, f: &SMatrix<f64, D, D>) -> FMat<D>
where
    Space<D>: Dim<D>,
{
    if near_a_soft_domain_edge(e, f) {
        return fd_hessian_from_gradient(e, f);
    }
    <Space<D> as Dim<D>>::fd_hessian_f(&|g| psi_f(e, g), f, scale_of(e, f))
}
