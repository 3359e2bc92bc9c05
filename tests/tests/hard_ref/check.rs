//! Checking every implementation of a formula at one F against the
//! double-double reference (shared by `hard_energies.rs` and
//! `prop_energies.rs`). What is asserted, per implementation and point:
//!
//! * nothing is NaN: Ψ, ∂Ψ/∂σ, the scaling block, twists and flips;
//! * outside the energy's domain (the reference Ψ is NaN or +∞) Ψ = +∞;
//!   inside it Ψ is finite;
//! * Ψ, vec(∂Ψ/∂F) and the raw Hessian ∂²Ψ/∂f² agree with the reference
//!   within the tolerances below, scaled by the point's condition number
//!   κ = σmax / ℓ (ℓ: distance to the nearest set where Ψ(F) is not smooth
//!   — det F = 0 for barrier energies, σi + σj = 0 for energies that are
//!   not sign-symmetric; κ = 1 elsewhere). The f64 SVD perturbs σ by
//!   ≈ ε‖F‖, which moves Ψ's derivatives by ≈ ε‖F‖/ℓ relative: κ is the
//!   honest amplification, and still catches any sign or factor-2 error;
//! * every filtered Hessian (Clamp, Abs, ClampEps) is finite, exactly
//!   symmetric, PSD down to its floor, and equal to the numeric projection
//!   of the *reference* Hessian (projection is 1-Lipschitz, so the same
//!   tolerance applies).
// `!(err <= tol)` on purpose: a NaN error must fail.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Energy, Filter, ScaleBlock, gradient_f, hessian_f, signed_svd2, signed_svd3};
use nalgebra::{DMatrix, SMatrix, SymmetricEigen};

use super::energies::Formula;
use super::fd::{psi_f, reference, step_for};

/// |Ψ − Ψref| ≤ PSI_TOL·κ·(|Ψref| + ‖F‖‖∇Ψref‖ + ‖F‖²‖Href‖): Ψ relative
/// to its own variation over the scale of F (at the rest state Ψ = 0 and
/// the gradient vanishes, so the Hessian term sets the scale).
pub const PSI_TOL: f64 = 1e-14;
/// ‖g − gref‖∞ ≤ GRAD_TOL·κ·(‖gref‖∞ + ‖F‖‖Href‖∞).
pub const GRAD_TOL: f64 = 1e-14;
/// ‖H − Href‖∞ ≤ HESS_TOL·κ·‖Href‖∞ (raw and filtered).
pub const HESS_TOL: f64 = 1e-10;
/// Filtered Hessians: min eigenvalue ≥ floor − PSD_TOL·‖H‖∞.
pub const PSD_TOL: f64 = 1e-12;

pub const FILTERS: [Filter; 3] = [Filter::Clamp, Filter::Abs, Filter::ClampEps(1e-3)];

/// An implementation's F-space quantities at one F.
pub struct Lifted {
    sigma: Vec<f64>,
    psi: f64,
    spectral_nan: Option<String>,
    grad: Vec<f64>,
    raw: Vec<f64>,
    filtered: Vec<(Filter, Vec<f64>)>,
}

pub fn spectral_nan<const D: usize>(s: &ecc_runtime::Spectral<D>) -> Option<String> {
    let scale: Vec<f64> = match s.scale {
        ScaleBlock::Diagonal(a) => a.to_vec(),
        ScaleBlock::Full(a) => a.iter().flatten().copied().collect(),
    };
    let pairs = ecc_runtime::Spectral::<D>::PAIRS;
    let bad = s.psi.is_nan()
        || s.grad.iter().any(|x| x.is_nan())
        || scale.iter().any(|x| x.is_nan())
        || s.twist[..pairs].iter().any(|x| x.is_nan())
        || s.flip[..pairs].iter().any(|x| x.is_nan());
    bad.then(|| format!("{s:?}"))
}

pub fn lift3(e: &dyn Energy<3>, f: &SMatrix<f64, 3, 3>) -> Lifted {
    let svd = signed_svd3(f);
    let s = e.spectral(&svd.sigma);
    Lifted {
        sigma: svd.sigma.to_vec(),
        psi: e.psi(&svd.sigma),
        spectral_nan: spectral_nan(&s),
        grad: gradient_f(&svd, &s).as_slice().to_vec(),
        raw: hessian_f(&svd, &s, Filter::None)
            .transpose()
            .as_slice()
            .to_vec(),
        filtered: FILTERS
            .iter()
            .map(|&fl| (fl, hessian_f(&svd, &s, fl).transpose().as_slice().to_vec()))
            .collect(),
    }
}

pub fn lift2(e: &dyn Energy<2>, f: &SMatrix<f64, 2, 2>) -> Lifted {
    let svd = signed_svd2(f);
    let s = e.spectral(&svd.sigma);
    Lifted {
        sigma: svd.sigma.to_vec(),
        psi: e.psi(&svd.sigma),
        spectral_nan: spectral_nan(&s),
        grad: gradient_f(&svd, &s).as_slice().to_vec(),
        raw: hessian_f(&svd, &s, Filter::None)
            .transpose()
            .as_slice()
            .to_vec(),
        filtered: FILTERS
            .iter()
            .map(|&fl| (fl, hessian_f(&svd, &s, fl).transpose().as_slice().to_vec()))
            .collect(),
    }
}

pub fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

pub fn diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// ℓ: the distance from σ to the nearest set where Ψ(F) is not smooth.
pub fn length_scale(sigma: &[f64], barrier: bool, sign_symmetric: bool) -> f64 {
    let mut l = amax(sigma);
    if barrier {
        l = l.min(sigma.iter().fold(f64::INFINITY, |m, x| m.min(x.abs())));
    }
    if !sign_symmetric {
        for i in 0..sigma.len() {
            for j in i + 1..sigma.len() {
                l = l.min((sigma[i] + sigma[j]).abs());
            }
        }
    }
    l
}

/// Worst scaled errors per formula (error / (tol·κ·scale), ≤ 1 passes).
#[derive(Default, Clone)]
pub struct Worst {
    /// Where the worst raw-Hessian error was seen.
    hess_at: String,
    psi: f64,
    grad: f64,
    hess: f64,
    filtered: f64,
    compared: usize,
    outside: usize,
}

pub struct Run {
    pub failures: Vec<String>,
    worst: Vec<(String, Worst)>,
}

impl Run {
    /// A new, empty run.
    pub fn new() -> Self {
        Run {
            failures: Vec::new(),
            worst: Vec::new(),
        }
    }

    fn worst(&mut self, name: &str) -> &mut Worst {
        if let Some(i) = self.worst.iter().position(|(n, _)| n == name) {
            return &mut self.worst[i].1;
        }
        self.worst.push((name.to_string(), Worst::default()));
        &mut self.worst.last_mut().unwrap().1
    }

    /// Print the table of worst errors and fail with every failure.
    pub fn finish(self, what: &str) {
        println!(
            "{what}: worst error / tolerance (≤ 1 passes), points compared, outside the domain"
        );
        for (name, w) in &self.worst {
            println!(
                "  {name:<14} Ψ {:8.2e}  ∇ {:8.2e}  H {:8.2e}  P(H) {:8.2e}  {:4} {:4}",
                w.psi, w.grad, w.hess, w.filtered, w.compared, w.outside
            );
            println!("  {:14} worst H at {}", "", w.hess_at);
        }
        assert!(
            self.failures.is_empty(),
            "{} failures:\n{}",
            self.failures.len(),
            self.failures.join("\n")
        );
    }
}

/// Check every implementation of `formula` at F (column-major `f`).
pub fn check_point<const D: usize>(
    formula: &Formula<D>,
    f: &[f64],
    lifts: &[Lifted],
    label: &str,
    run: &mut Run,
) {
    let n = D * D;
    let ir = formula.ir();
    let sigma = &lifts[0].sigma;
    let fnorm = amax(sigma);
    let l = length_scale(sigma, ir.barrier, ir.sign_symmetric);
    let kappa = (fnorm / l).max(1.0);
    let fd: Vec<_> = f.iter().map(|x| super::dd::Dd::from_f64(*x)).collect();
    let center = psi_f(&formula.graph, &fd, D).to_f64();
    let inside = center.is_finite();
    let r = (inside && l > 0.0)
        .then(|| reference(&formula.graph, f, D, step_for(l)))
        .flatten();
    let mut w = run.worst(&formula.name).clone();
    if !inside {
        w.outside += 1;
    }
    let mut failures = Vec::new();
    for (imp, lifted) in formula.impls.iter().zip(lifts) {
        let who = format!("{} ({}) / {label}", formula.name, imp.kind);
        let mut fail = |m: String| failures.push(format!("{who}: {m}"));
        if let Some(s) = &lifted.spectral_nan {
            fail(format!("NaN in the spectral data {s}"));
        }
        if lifted.psi.is_nan() {
            fail("Ψ is NaN".into());
        }
        if !inside {
            if lifted.psi != f64::INFINITY {
                fail(format!(
                    "outside the domain (reference {center}) but Ψ = {}",
                    lifted.psi
                ));
            }
        } else if !lifted.psi.is_finite() {
            fail(format!("Ψ = {} but the reference is {center}", lifted.psi));
        }
        // Filtered Hessians: finite, exactly symmetric, PSD.
        for (fl, h) in &lifted.filtered {
            if !h.iter().all(|x| x.is_finite()) {
                fail(format!("{fl:?} Hessian is not finite"));
                continue;
            }
            let m = DMatrix::from_row_slice(n, n, h);
            if m != m.transpose() {
                fail(format!("{fl:?} Hessian is not exactly symmetric"));
            }
            let min = SymmetricEigen::new(m).eigenvalues.min();
            if min < fl.floor() - PSD_TOL * amax(h).max(1.0) {
                fail(format!("{fl:?} Hessian has eigenvalue {min:e}"));
            }
        }
        let Some(r) = &r else { continue };
        w.compared += 1;
        let (gs, hs) = (amax(&r.grad), amax(&r.hess));
        let e_psi = (lifted.psi - r.psi).abs()
            / (PSI_TOL * kappa * (r.psi.abs() + fnorm * gs + fnorm * fnorm * hs));
        let e_grad = diff(&lifted.grad, &r.grad) / (GRAD_TOL * kappa * (gs + fnorm * hs));
        w.psi = w.psi.max(e_psi);
        w.grad = w.grad.max(e_grad);
        if !(e_psi <= 1.0) {
            fail(format!(
                "Ψ {:e} vs reference {:e} ({e_psi:.1e} × tolerance)",
                lifted.psi, r.psi
            ));
        }
        if !(e_grad <= 1.0) {
            fail(format!(
                "gradient {e_grad:.1e} × tolerance\n  got {:?}\n  ref {:?}",
                lifted.grad, r.grad
            ));
        }
        if lifted.raw.iter().all(|x| x.is_finite()) {
            let e_h = diff(&lifted.raw, &r.hess) / (HESS_TOL * kappa * hs);
            if e_h > w.hess {
                w.hess = e_h;
                w.hess_at = format!("{} ({label})", imp.kind);
            }
            if !(e_h <= 1.0) {
                fail(format!(
                    "raw Hessian {e_h:.1e} × tolerance (h = {:e})\n  got {:?}\n  ref {:?}",
                    r.h, lifted.raw, r.hess
                ));
            }
        }
        let href = DMatrix::from_row_slice(n, n, &r.hess);
        for (fl, h) in &lifted.filtered {
            let p = projected(&href, *fl);
            let e = diff(h, p.as_slice()) / (HESS_TOL * kappa * hs);
            w.filtered = w.filtered.max(e);
            if !(e <= 1.0) {
                fail(format!(
                    "{fl:?} Hessian vs projected reference: {e:.1e} × tolerance"
                ));
            }
        }
    }
    *run.worst(&formula.name) = w;
    run.failures.extend(failures);
}

/// The numeric projection of a (symmetric, row-major = column-major) matrix.
pub fn projected(h: &DMatrix<f64>, fl: Filter) -> DMatrix<f64> {
    match h.nrows() {
        9 => {
            let m = SMatrix::<f64, 9, 9>::from_iterator(h.iter().copied());
            DMatrix::from_iterator(9, 9, project_psd_numeric(&m, fl).iter().copied())
        }
        _ => {
            let m = SMatrix::<f64, 4, 4>::from_iterator(h.iter().copied());
            DMatrix::from_iterator(4, 4, project_psd_numeric(&m, fl).iter().copied())
        }
    }
}
