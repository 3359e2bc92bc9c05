//! One point of `ecc check`: the analytic eigensystem against independent baselines.
//!
//! | check | analytic (what `ecc eval` prints) | baseline |
//! |---|---|---|
//! | gradient | vec(U diag(∂Ψ/∂σ) Vᵀ) | central differences of Ψ(F) |
//! | hessian | Σ λ e eᵀ over the analytic modes | second central differences of Ψ(F) |
//! | eigenvalues | the analytic mode eigenvalues | nalgebra `SymmetricEigen` of the raw Hessian |
//! | projected | clamped analytic modes | Q max(Λ, 0) Qᵀ from `SymmetricEigen` |
//!
//! Errors are relative to the size of the quantity: ‖a − b‖∞ / s with
//! s = max(‖∂Ψ/∂F‖∞, ‖H‖∞·‖F‖∞) for the gradient (so a vanishing gradient at
//! rest is judged against the energy's stiffness) and s = ‖H‖∞ (largest
//! |entry|) for the matrices and eigenvalues. A non-finite analytic value where
//! the baseline is finite counts as an infinite error.
//!
//! Skips: F outside the domain (Ψ = +∞); central differences within 10⁻²
//! (relative) of σi + σj = 0 for a pair whose twist the compiler proved to be
//! a genuine pole ([`Twist::Pole`], e.g. ARAP's 2 − 4/(σi+σj)): no finite step
//! resolves a pole that close; eigen checks when the raw Hessian is itself
//! non-finite. A NaN eigenvalue always fails (a pole is +∞, never NaN).
//!
//! Removable twists are checked there like anywhere else, except that a
//! removable twist of an energy that is not sign-symmetric ([`Twist::Kinked`],
//! e.g. 2D I1²·e^{I1}) sits where Ψ(F) is only C² (I1 = tr S has a kink, which
//! I1² smooths to second order only), so second central differences lose
//! O(h): within 10⁻² of σi + σj = 0 the hessian column compares instead the
//! twist eigenvalue with the divided difference (Ψi + Ψj)/(σi + σj) of the
//! energy's own gradient (itself checked against central differences) at
//! t = ±10⁻²·|σi|, ±½·10⁻²·|σi| off the plane, Richardson-extrapolated
//! (even and odd parts) to the point.

use ecc_runtime::reference::{fd_gradient_f, fd_hessian_f};
use ecc_runtime::{Energy, Spectral, pair_indices};
use nalgebra::{DMatrix, SMatrix, SymmetricEigen};

use crate::point::evaluate;
use ecc_runtime::{Dim, Space};

/// Worst relative errors at one point (`None` = skipped).
#[derive(Clone, Copy, Debug, Default)]
pub struct Errors {
    /// Gradient vs central differences.
    pub gradient: Option<f64>,
    /// Raw Hessian vs central differences.
    pub hessian: Option<f64>,
    /// Analytic eigenvalues vs numeric eigensolve.
    pub eigenvalues: Option<f64>,
    /// Projected Hessian vs numeric projection.
    pub projected: Option<f64>,
    /// Why something was skipped.
    pub note: Option<&'static str>,
}

fn inf_norm<'a>(xs: impl IntoIterator<Item = &'a f64>) -> f64 {
    xs.into_iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// ‖a − b‖∞ / scale, ∞ when a difference is not finite.
fn rel_err<'a>(
    a: impl IntoIterator<Item = &'a f64>,
    b: impl IntoIterator<Item = &'a f64>,
    scale: f64,
) -> f64 {
    let mut worst: f64 = 0.0;
    for (x, y) in a.into_iter().zip(b) {
        let d = (x - y).abs();
        if !d.is_finite() {
            return f64::INFINITY;
        }
        worst = worst.max(d);
    }
    worst / scale.max(f64::MIN_POSITIVE)
}

/// How the twist of one pair slot behaves on σi + σj = 0 (from the IR).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Twist {
    /// No singularity, or removable with Ψ smooth there (sign-symmetric).
    Smooth,
    /// Removable, Ψ not sign-symmetric: Ψ(F) is only C² on the plane.
    Kinked,
    /// A genuine pole of the energy.
    Pole,
}

/// Relative distance to σi + σj = 0 within which [`Twist::Pole`] skips central
/// differences and [`Twist::Kinked`] checks the twist against gradients.
const PLANE_BAND: f64 = 1e-2;

/// The twist of pair (i, j) at σ from the energy's own gradients: λ(t) =
/// (Ψi + Ψj)/(σi + σj) along σi = b + t, σj = −b + t, extrapolated to the
/// point's t from t0 = ±10⁻²·|b| and ±t0/2 (Richardson on the even and odd
/// parts, error O(t0⁴)).
fn twist_from_gradients<const D: usize>(
    e: &dyn Energy<D>,
    sigma: &[f64],
    (i, j): (usize, usize),
) -> f64 {
    let t = 0.5 * (sigma[i] + sigma[j]);
    let b = 0.5 * (sigma[i] - sigma[j]);
    let lam = |x: f64| {
        let mut s: [f64; D] = std::array::from_fn(|k| sigma[k]);
        s[i] = b + x;
        s[j] = -b + x;
        let g = e.spectral(&s).grad;
        (g[i] + g[j]) / (s[i] + s[j])
    };
    let t0 = PLANE_BAND * b.abs();
    let even = |x: f64| 0.5 * (lam(x) + lam(-x));
    let odd = |x: f64| (lam(x) - lam(-x)) / (2.0 * x);
    let l0 = (4.0 * even(0.5 * t0) - even(t0)) / 3.0;
    let l1 = (4.0 * odd(0.5 * t0) - odd(t0)) / 3.0;
    let l2 = (even(0.5 * t0) - l0) / (0.25 * t0 * t0);
    l0 + l1 * t + l2 * t * t
}

/// Compare at `f`; `twists[k]` is what the twist of pair slot k does on
/// σi + σj = 0 (the IR's `twist_kind`, see the module docs).
pub fn compare<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    twists: [Twist; 3],
) -> Errors
where
    Space<D>: Dim<D>,
{
    let p = evaluate::<D>(e, f);
    if !p.inside_domain() {
        return Errors {
            note: Some("outside the domain (psi = +inf)"),
            ..Errors::default()
        };
    }
    let n = D * D;
    let h_flat: Vec<f64> = p.hessian.iter().flatten().copied().collect();
    let mut out = Errors::default();

    let smax = inf_norm(&p.sigma);
    // Poles: within the band of the largest σ (the difference steps scale
    // with F); kinks: of the pair's own σ (where the twist is evaluated).
    let near = |kind: Twist| {
        (0..Spectral::<D>::PAIRS).find(|&k| {
            let (i, j) = pair_indices::<D>(k);
            let (si, sj) = (p.sigma[i], p.sigma[j]);
            let scale = if kind == Twist::Pole {
                smax
            } else {
                si.abs().max(sj.abs())
            };
            twists[k] == kind && (si + sj).abs() <= PLANE_BAND * scale
        })
    };
    if near(Twist::Pole).is_some() {
        out.note = Some("central differences skipped: at the genuine pole sigma_i + sigma_j = 0");
    } else {
        let g_fd = fd_gradient_f(e, f);
        let h_fd = fd_hessian_f(e, f);
        // Both are symmetric; compare entry by entry (row-major vs nalgebra's column-major is the same set).
        let h_fd_rows: Vec<f64> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| h_fd[(i, j)])
            .collect();
        let h_scale = inf_norm(&h_fd_rows);
        let g_scale = inf_norm(g_fd.iter()).max(h_scale * inf_norm(f.iter()));
        out.gradient = Some(rel_err(&p.gradient, g_fd.as_slice(), g_scale));
        out.hessian = Some(rel_err(&h_flat, &h_fd_rows, h_scale));
        if let Some(k) = near(Twist::Kinked) {
            let (i, j) = pair_indices::<D>(k);
            let s: [f64; D] = std::array::from_fn(|m| p.sigma[m]);
            let got = e.spectral(&s).twist[k];
            let want = twist_from_gradients(e, &p.sigma, (i, j));
            out.hessian = Some(rel_err(&[got], &[want], h_scale));
            out.note = Some("hessian: twist vs gradient divided differences (Psi is C2 here)");
        }
    }

    if p.eigenvalues.iter().any(|x| x.is_nan()) {
        out.eigenvalues = Some(f64::INFINITY);
        out.note = Some("NaN eigenvalue (a pole must be +inf, a removable singularity its limit)");
        return out;
    }
    if !h_flat.iter().all(|x| x.is_finite()) {
        out.note = Some("raw Hessian not finite (genuine singularity): eigen checks skipped");
        return out;
    }
    let h = DMatrix::from_fn(n, n, |i, j| 0.5 * (p.hessian[i][j] + p.hessian[j][i]));
    let eig = SymmetricEigen::new(h.clone());
    let mut lam: Vec<f64> = eig.eigenvalues.iter().copied().collect();
    lam.sort_by(f64::total_cmp);
    let scale = inf_norm(h.iter());
    out.eigenvalues = Some(rel_err(&p.eigenvalues, &lam, scale));
    let q = &eig.eigenvectors;
    let clamped = DMatrix::from_fn(n, n, |i, j| {
        (0..n)
            .map(|k| q[(i, k)] * eig.eigenvalues[k].max(0.0) * q[(j, k)])
            .sum::<f64>()
    });
    let proj_rows: Vec<f64> = p.hessian_projected.iter().flatten().copied().collect();
    let num_rows: Vec<f64> = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| clamped[(i, j)])
        .collect();
    out.projected = Some(rel_err(&proj_rows, &num_rows, scale));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::TOLERANCES;
    use ecc_runtime::energies::Arap;

    /// ARAP with a deliberately wrong twist eigenvalue or gradient.
    struct Broken {
        twist: f64,
        grad: f64,
    }

    impl Energy<2> for Broken {
        fn name(&self) -> &str {
            "broken"
        }
        fn psi(&self, s: &[f64; 2]) -> f64 {
            Energy::<2>::psi(&Arap, s)
        }
        fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
            let mut sp = Energy::<2>::spectral(&Arap, s);
            sp.twist[0] *= self.twist;
            sp.grad[0] *= self.grad;
            sp
        }
    }

    #[test]
    fn wrong_eigensystems_are_caught() {
        let f = SMatrix::<f64, 2, 2>::new(1.2, 0.3, -0.1, 0.8);
        let good = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.0,
            },
            &f,
            [Twist::Pole; 3],
        );
        for (k, e) in [
            good.gradient,
            good.hessian,
            good.eigenvalues,
            good.projected,
        ]
        .iter()
        .enumerate()
        {
            assert!(e.unwrap() <= TOLERANCES[k], "check {k}: {e:?}");
        }
        let bad_twist = compare::<2>(
            &Broken {
                twist: 1.1,
                grad: 1.0,
            },
            &f,
            [Twist::Pole; 3],
        );
        assert!(bad_twist.hessian.unwrap() > TOLERANCES[1], "{bad_twist:?}");
        let bad_grad = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.001,
            },
            &f,
            [Twist::Pole; 3],
        );
        assert!(bad_grad.gradient.unwrap() > TOLERANCES[0], "{bad_grad:?}");
    }

    #[test]
    fn near_the_pole_differences_are_skipped_only_for_genuine_poles() {
        let f = SMatrix::<f64, 2, 2>::new(0.7, 0.0, 0.0, -0.7 + 1e-12);
        let e = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.0,
            },
            &f,
            [Twist::Pole; 3],
        );
        assert!(e.gradient.is_none() && e.hessian.is_none() && e.note.is_some());
        let e = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.0,
            },
            &f,
            [Twist::Smooth; 3],
        );
        assert!(e.gradient.is_some());
    }
}
