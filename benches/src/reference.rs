//! The high-precision reference: derivatives of Ψ(F) by central differences
//! in **double-double** arithmetic, independent of every measured code path.
//!
//! Ψ(F) is evaluated from the energy's CAS graph of Ψ *alone* (no derivative
//! the DSL derived is used) in [`Dd`], after a signed SVD in [`Dd`]
//! ([`crate::linalg::signed_svd`]: Jacobi on FᵀF, σ_last = det F/Π others).
//! Derivatives with respect to the d² entries of F:
//!
//! * central differences D(h) = (Ψ(F+h eᵢ) − Ψ(F−h eᵢ))/2h, second
//!   differences (Ψ(+h) − 2Ψ + Ψ(−h))/h² and the four-point mixed formula;
//! * a ladder h_k = 0.05·s·2⁻ᵏ, k = 0…7, with s = min(‖F‖, min|σᵢ|, min|σᵢ+σⱼ|)
//!   (the smallest feature scale: a barrier at σ → 0, ARAP's pole at σᵢ = −σⱼ);
//! * two Richardson levels (error O(h⁶)); the value returned is the one whose
//!   two neighbouring estimates agree best, and that disagreement is kept as
//!   the reference's own error estimate (reported next to every table).
//!
//! With u ≈ 2.5·10⁻³² the rounding part is ≈ u·Ψ/h² ≈ 10⁻²⁷ relative and
//! the truncation part O((h/s)⁶) ≈ 10⁻¹⁸; measured self-disagreements are
//! printed in the report (typically 10⁻¹⁹…10⁻²²), far below f64 roundoff
//! (1.1·10⁻¹⁶), so every f64 method's error is resolved.
//!
//! Element quantities follow with the exact chain rule in [`Dd`]
//! (F = Ds Dm⁻¹ from the same f64 node positions and Dm⁻¹ the methods
//! receive), and the projections with the Jacobi eigensolver in [`Dd`]. The
//! PSD projection is 1-Lipschitz in the Frobenius norm, so projecting the
//! reference loses nothing: ‖P(H_ref) − P(H)‖_F ≤ ‖H_ref − H‖_F.

use ecc_runtime::Filter;

use crate::generic_kernel::{GenericEnergy, chain_rule, chain_weights, deformation, filter_value};
use crate::linalg::{signed_svd, sym_eigen};
use ecc_tests::dd::Dd;
use ecc_tests::real::Real;

/// Reference element quantities (× rest measure), rounded to f64.
#[derive(Clone, Debug)]
pub struct ElementRef {
    pub psi: f64,
    pub grad: Vec<f64>,
    /// Raw element Hessian m Bᵀ H B (row-major N×N).
    pub raw: Vec<f64>,
    /// F-space projection: m Bᵀ P(H) B (what the analytic kernel computes).
    pub fproj: Vec<f64>,
    /// Element projection: P(m Bᵀ H B) (what the numeric 12×12 / 6×6 computes).
    pub eproj: Vec<f64>,
    /// Estimated relative error of the raw F-space Hessian itself.
    pub self_error: f64,
    /// Estimated relative error of the F-space gradient.
    pub grad_self_error: f64,
}

fn ladder(scale: Dd, mut est: impl FnMut(Dd) -> Dd) -> (Dd, f64) {
    const K: usize = 8;
    let d: Vec<Dd> = (0..K)
        .map(|k| est(scale * Dd::from_f64(0.05 * 0.5f64.powi(k as i32))))
        .collect();
    let r1: Vec<Dd> = (0..K - 1)
        .map(|k| (Dd::from_f64(4.0) * d[k + 1] - d[k]) / Dd::from_f64(3.0))
        .collect();
    let r2: Vec<Dd> = (0..K - 2)
        .map(|k| (Dd::from_f64(16.0) * r1[k + 1] - r1[k]) / Dd::from_f64(15.0))
        .collect();
    let mut best = (r2[K - 3], f64::INFINITY);
    for k in 0..K - 3 {
        let diff = (r2[k] - r2[k + 1]).to_f64().abs();
        if diff.is_finite() && diff < best.1 {
            best = (r2[k + 1], diff);
        }
    }
    best
}

fn amax(v: &[Dd]) -> f64 {
    v.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max)
}

/// Reference F-space gradient (column-major vec) and raw Hessian, with
/// their estimated relative errors, at the row-major F (in double-double).
pub fn f_derivatives(e: &GenericEnergy, f: &[Dd]) -> (Vec<Dd>, Vec<Dd>, f64, f64) {
    let d = e.dim();
    let r2 = d * d;
    let mut work = Vec::new();
    let (sigma, _, _) = signed_svd(f, d);
    let mut s = f.iter().fold(Dd::zero(), |a, &x| a + x * x).sqrt();
    for i in 0..d {
        if sigma[i].abs() < s {
            s = sigma[i].abs();
        }
        for j in (i + 1)..d {
            let p = (sigma[i] + sigma[j]).abs();
            if p < s {
                s = p;
            }
        }
    }
    let fnorm = amax(f).max(1e-300);
    if s.to_f64() < 1e-12 * fnorm {
        s = Dd::from_f64(1e-12 * fnorm);
    }
    // row-major index of vec entry k (column-major): r = k % d, c = k / d
    let idx = |k: usize| (k % d) * d + (k / d);
    let mut psi_at = |delta: &[(usize, Dd)]| -> Dd {
        let mut g = f.to_vec();
        for &(k, h) in delta {
            g[idx(k)] = g[idx(k)] + h;
        }
        e.psi_f(&g, &mut work)
    };
    let psi0 = psi_at(&[]);
    let mut grad = vec![Dd::zero(); r2];
    let mut gerr = 0.0f64;
    for (k, gk) in grad.iter_mut().enumerate() {
        let (v, err) = ladder(s, |h| (psi_at(&[(k, h)]) - psi_at(&[(k, -h)])) / (h + h));
        *gk = v;
        gerr = gerr.max(err);
    }
    let mut hess = vec![Dd::zero(); r2 * r2];
    let mut herr = 0.0f64;
    for i in 0..r2 {
        for j in i..r2 {
            let (v, err) = if i == j {
                ladder(s, |h| {
                    (psi_at(&[(i, h)]) - psi0 - psi0 + psi_at(&[(i, -h)])) / (h * h)
                })
            } else {
                ladder(s, |h| {
                    (psi_at(&[(i, h), (j, h)])
                        - psi_at(&[(i, h), (j, -h)])
                        - psi_at(&[(i, -h), (j, h)])
                        + psi_at(&[(i, -h), (j, -h)]))
                        / (Dd::from_f64(4.0) * h * h)
                })
            };
            hess[i * r2 + j] = v;
            hess[j * r2 + i] = v;
            herr = herr.max(err);
        }
    }
    let gscale = amax(&grad).max(amax(&hess) * fnorm * 1e-8).max(1e-300);
    (
        grad,
        hess.clone(),
        herr / amax(&hess).max(1e-300),
        gerr / gscale,
    )
}

/// Symmetric PSD projection Q filter(Λ) Qᵀ of a row-major n×n matrix, in double-double.
pub fn project(h: &[Dd], n: usize, filter: Filter) -> Vec<Dd> {
    let (vals, vecs) = sym_eigen(h, n);
    let lam: Vec<Dd> = vals.iter().map(|&l| filter_value(filter, l)).collect();
    let mut out = vec![Dd::zero(); n * n];
    for i in 0..n {
        for j in i..n {
            let mut acc = Dd::zero();
            for k in 0..n {
                acc = acc + vecs[i * n + k] * lam[k] * vecs[j * n + k];
            }
            out[i * n + j] = acc;
            out[j * n + i] = acc;
        }
    }
    out
}

/// The reference element quantities for energy `e`, rest data `dm_inv`
/// (row-major) and `measure`, at node positions `x` (node-major f64).
pub fn element(e: &GenericEnergy, dm_inv: &[f64], measure: f64, x: &[f64]) -> ElementRef {
    let d = e.dim();
    let w = chain_weights::<Dd>(dm_inv, d);
    let xd: Vec<Dd> = x.iter().map(|&v| Dd::from_f64(v)).collect();
    let f = deformation(&xd, &w, d);
    let (g_f, h_f, herr, gerr) = f_derivatives(e, &f);
    let m = Dd::from_f64(measure);
    let mut work = Vec::new();
    let psi = e.psi_f(&f, &mut work) * m;
    let (grad, raw) = chain_rule(&w, d, m, &g_f, Some(&h_f));
    let p_f = project(&h_f, d * d, Filter::Clamp);
    let (_, fproj) = chain_rule(&w, d, m, &g_f, Some(&p_f));
    let n = (d + 1) * d;
    let eproj = project(&raw, n, Filter::Clamp);
    let r = |v: Vec<Dd>| v.into_iter().map(|x| x.to_f64()).collect::<Vec<f64>>();
    ElementRef {
        psi: psi.to_f64(),
        grad: r(grad),
        raw: r(raw),
        fproj: r(fproj),
        eproj: r(eproj),
        self_error: herr,
        grad_self_error: gerr,
    }
}

/// max|a − b| / max|b| (`b` is the reference; 0/0 = 0).
pub fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| {
            if x.is_finite() {
                (x - y).abs()
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max);
    if diff == 0.0 { 0.0 } else { diff / scale }
}
