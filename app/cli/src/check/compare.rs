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
//! Skips: F outside the domain (Ψ = +∞); central differences within 10⁻⁶
//! (relative) of σi + σj = 0 for energies that are not sign-symmetric, where Ψ
//! has a genuine kink/pole (e.g. ARAP's twist 2 − 4/(σi+σj)) that no finite
//! step can resolve; eigen checks when the raw Hessian is itself non-finite.

use ecc_runtime::Energy;
use ecc_runtime::reference::{fd_gradient_f, fd_hessian_f};
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

/// Compare at `f`; `sign_symmetric` is the IR's flag (see the module docs).
pub fn compare<const D: usize>(
    e: &dyn Energy<D>,
    f: &SMatrix<f64, D, D>,
    sign_symmetric: bool,
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
    let pole = (0..D).any(|i| (i + 1..D).any(|j| (p.sigma[i] + p.sigma[j]).abs() <= 1e-6 * smax));
    if pole && !sign_symmetric {
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
    use ecc_runtime::Spectral;
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
            false,
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
            false,
        );
        assert!(bad_twist.hessian.unwrap() > TOLERANCES[1], "{bad_twist:?}");
        let bad_grad = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.001,
            },
            &f,
            false,
        );
        assert!(bad_grad.gradient.unwrap() > TOLERANCES[0], "{bad_grad:?}");
    }

    #[test]
    fn near_the_pole_differences_are_skipped_only_without_sign_symmetry() {
        let f = SMatrix::<f64, 2, 2>::new(0.7, 0.0, 0.0, -0.7 + 1e-12);
        let e = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.0,
            },
            &f,
            false,
        );
        assert!(e.gradient.is_none() && e.hessian.is_none() && e.note.is_some());
        let e = compare::<2>(
            &Broken {
                twist: 1.0,
                grad: 1.0,
            },
            &f,
            true,
        );
        assert!(e.gradient.is_some());
    }
}
