//! ψ(I4, I5), vec(∂ψ/∂F) and the (filtered) ∂²ψ/∂f² at one F.
//!
//! With g4 = vec(∂I4/∂F), g5 = vec(∂I5/∂F) and H4, H5 their Hessians
//! ([`super::frame`], eqs. F3–F5), the chain rule gives
//!
//!   ∂ψ/∂F = ψ4 g4 + ψ5 g5,                                                 (P1)
//!   ∂²ψ/∂f² = ψ5 H5 + ψ4 H4 + [g4 g5] [[ψ44, ψ45], [ψ45, ψ55]] [g4 g5]ᵀ.  (P2)
//!
//! **Closed form, ψ without I4 terms** ([`FibrePath::ClosedI5`]; every
//! energy of I5 alone, and anisotropic ARAP, whose sign(I4) is locally
//! constant): g5 = 2‖Fa‖ vec(n aᵀ) with n = F a/‖F a‖, so P2 is
//! 2ψ5 (a aᵀ ⊗ I) + 4ψ55 I5 vec(n aᵀ)vec(n aᵀ)ᵀ with eigenpairs
//!
//!   λ_along = 2ψ5 + 4ψ55 I5 on vec(n aᵀ),                                 (P3)
//!   λ_across = 2ψ5 on vec(q aᵀ), q ⊥ n (d − 1 modes),                      (P4)
//!   0 on vec(q cᵀ), c ⊥ a (d² − d modes).                                  (P5)
//!
//! (§4.1's eigensystem of I5, eqs. 6–7 of Kim, de Goes & Iben 2019, carried
//! through the chain rule; HOBAK's `ANISOTROPIC_STVK::clampedHessian` and
//! `ANISOTROPIC_FUNG::clampedHessian` use exactly these two non-zero values,
//! λ1 = 2ψ5 and λ0 = λ1 + 4ψ55 I5 in their variables, and
//! `ANISOTROPIC_ARAP::hessian` is (1 − S/√I5) H5 + S/√I5³ f fᵀ with H5 =
//! `kronIdentity(A)`: along μ, across μ(1 − S/√I5).) The filtered Hessian
//! is assembled from the three orthogonal projectors, so no vector q is
//! ever chosen:
//! H = f(λ_along) e eᵀ + f(λ_across)(P − e eᵀ) + f(0)(I − P), P = a aᵀ ⊗ I,
//! e = a ⊗ n. At F a = 0 the direction n is undefined but λ_along = λ_across
//! there, so any n gives the same H (n = e₀ is used).
//!
//! **ψ with I4 terms** ([`FibrePath::Reduced`]). H4 couples the scaling
//! and twist modes (see [`super::frame`]); `fibre/reduced.rs` writes it in
//! polar coordinates (eqs. R1–R3), proves that ψ(I4)'s Hessian vanishes on
//! d − 1 explicit symmetric directions (eq. R4) and projects by an
//! eigensolve of the rest only: 7 × 7 in 3D, 3 × 3 in 2D. ψ(I4, I5) has no
//! such null space for a generic fibre and keeps a d² × d² eigensolve (of the
//! same cheap form). The raw request (`Filter::None`) and the poles
//! σ_i + σ_j = 0 use the analytic F5 Hessian P2 ([`FibrePath::Numeric`],
//! with a d² × d² eigensolve when filtered): the reference the reduced path
//! is tested against.
//!
//! **Non-finite values.** ψ = +∞ gives zero derivatives. An infinite ψ5 at
//! F a = 0 (e.g. √I5 in anisotropic ARAP: a cone point, ψ is not
//! differentiable there) multiplies an exact zero and contributes nothing to
//! the gradient; the eigenvalues it makes infinite are dropped to the
//! filter's floor (raw: passed through). NaN in a raw Hessian entry (∞ − ∞
//! at a pole of H4, σ_i + σ_j = 0) is reported as +∞; filters never see it
//! (a non-finite raw Hessian projects to zero).

use nalgebra::{SMatrix, SVector};

use super::frame::{Frame, fa_i5, mul0};
use crate::fibre::{FibreDerivs, FibreEnergy, FibreUse};
use crate::filter::Filter;

/// Which eigensystem produced a fibre Hessian.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FibrePath {
    /// ψ was not finite or F had a non-finite entry: zero derivatives.
    Degenerate,
    /// Closed form (eqs. P3–P5): ψ has no I4 derivative at this point.
    ClosedI5,
    /// Analytic raw Hessian (eq. F5), projected by a d² × d² symmetric
    /// eigensolve: the raw (`Filter::None`) request and the fallback at a
    /// pole σ_i + σ_j = 0.
    Numeric,
    /// ψ with I4 terms: the closed-form I4 Hessian on its range (eq. R3 of
    /// `fibre/reduced.rs`) and an eigensolve of that block only: 7 × 7 in 3D
    /// and 3 × 3 in 2D for ψ(I4) (d − 1 null modes in closed form, eq. R4),
    /// d² × d² for ψ(I4, I5).
    Reduced,
}

/// The three distinct eigenvalues of a ψ without I4 terms (eqs. P3–P5):
/// `[λ_along, λ_across, 0]`, with 0·∞ = 0 at F a = 0.
pub fn i5_eigenvalues(d: &FibreDerivs, i5: f64) -> [f64; 3] {
    [2.0 * d.d5 + mul0(4.0 * d.d55, i5), 2.0 * d.d5, 0.0]
}

/// Unit n = F a/‖F a‖ (e₀ when F a = 0), scaled first so tiny F a is exact.
pub(crate) fn unit<const D: usize>(fa: &[f64; D]) -> [f64; D] {
    let m = fa.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 {
        return std::array::from_fn(|i| if i == 0 { 1.0 } else { 0.0 });
    }
    let y: [f64; D] = std::array::from_fn(|i| fa[i] / m);
    let n = y.iter().map(|x| x * x).sum::<f64>().sqrt();
    std::array::from_fn(|i| y[i] / n)
}

/// Closed-form Hessian of eqs. P3–P5 from the filtered eigenvalues
/// `[along, across, null]` and n.
fn closed_hessian<const D: usize, const N: usize>(
    f: [f64; 3],
    a: &SVector<f64, D>,
    n: &[f64; D],
) -> SMatrix<f64, N, N> {
    let [f1, f2, f0] = f;
    SMatrix::from_fn(|i, j| {
        let (ci, ri, cj, rj) = (i / D, i % D, j / D, j % D);
        let p = if ri == rj { a[ci] * a[cj] } else { 0.0 };
        let e = a[ci] * n[ri] * a[cj] * n[rj];
        let id = if i == j { 1.0 } else { 0.0 };
        mul0(f0, id - p) + mul0(f2, p - e) + mul0(f1, e)
    })
}

/// Raw Hessian P2 from the frame (numeric path).
fn raw_hessian<const D: usize, const N: usize>(
    fr: &Frame<D>,
    a: &SVector<f64, D>,
    d: &FibreDerivs,
    g4: &SVector<f64, N>,
    g5: &SVector<f64, N>,
) -> SMatrix<f64, N, N> {
    let h5 = Frame::<D>::hess5::<N>(a);
    let h4 = if d.d4 != 0.0 {
        fr.hess4::<N>()
    } else {
        SMatrix::zeros()
    };
    SMatrix::from_fn(|i, j| {
        let v = mul0(d.d5, h5[(i, j)])
            + mul0(d.d4, h4[(i, j)])
            + mul0(d.d44, g4[i] * g4[j])
            + mul0(d.d45, g4[i] * g5[j] + g5[i] * g4[j])
            + mul0(d.d55, g5[i] * g5[j]);
        if v.is_nan() { f64::INFINITY } else { v }
    })
}

/// Whether ψ has an I4 derivative at this point (decides the path).
fn has_i4(uses: FibreUse, d: &FibreDerivs) -> bool {
    matches!(uses, FibreUse::I4 | FibreUse::Both) && (d.d4 != 0.0 || d.d44 != 0.0 || d.d45 != 0.0)
}

/// The Hessian of [`point_kernel`]: closed form (filtered eigenvalues
/// `[along, across, null]` and n, eqs. P3–P5) or a full d² × d² matrix.
pub(crate) enum Hess<const D: usize, const N: usize> {
    Closed([f64; 3], [f64; D]),
    Full(SMatrix<f64, N, N>),
}

impl<const D: usize, const N: usize> Hess<D, N> {
    /// The d² × d² matrix.
    pub(crate) fn matrix(&self, a: &SVector<f64, D>) -> SMatrix<f64, N, N> {
        match self {
            Hess::Closed(f, n) => closed_hessian::<D, N>(*f, a, n),
            Hess::Full(h) => *h,
        }
    }
}

/// The reduced projection of one size: (frame, partials, filter, ψ has no
/// I5 derivative) ↦ filtered F-space Hessian, `None` at a pole.
pub(crate) type Reduce<const D: usize, const N: usize> =
    fn(&Frame<D>, &FibreDerivs, Filter, bool) -> Option<SMatrix<f64, N, N>>;

/// Result of [`point_kernel`]: ψ, vec(∂ψ/∂F), ∂²ψ/∂f², path.
pub(crate) type PointOut<const D: usize, const N: usize> =
    (f64, SVector<f64, N>, Hess<D, N>, FibrePath);

/// ψ, gradient and (if asked) Hessian at F; `project` is the d² × d²
/// numeric projection (monomorphised per size by the caller).
/// `reduce` is [`super::reduced::reduced_hessian`] monomorphised for this
/// size (`None` falls back to `project`).
pub(crate) fn point_kernel<const D: usize, const N: usize, E: FibreEnergy<D> + ?Sized>(
    e: &E,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
    filter: Filter,
    want_hessian: bool,
    project: impl Fn(&SMatrix<f64, N, N>, Filter) -> SMatrix<f64, N, N>,
    reduce: Reduce<D, N>,
) -> PointOut<D, N> {
    let degenerate = |psi: f64| {
        (
            psi,
            SVector::zeros(),
            Hess::Full(SMatrix::zeros()),
            FibrePath::Degenerate,
        )
    };
    if !f.iter().all(|x| x.is_finite()) {
        return degenerate(f64::NAN);
    }
    let uses = e.uses();
    let frame = matches!(uses, FibreUse::I4 | FibreUse::Both).then(|| Frame::new(f, a));
    let (fa, i5) = fa_i5(f, a);
    let i4 = frame.as_ref().map_or(f64::NAN, |fr| fr.i4);
    let d = e.fibre(i4, i5);
    if !d.psi.is_finite() {
        return degenerate(d.psi);
    }
    let g5: SVector<f64, N> = SVector::from_fn(|k, _| 2.0 * fa[k % D] * a[k / D]);
    match frame.filter(|_| has_i4(uses, &d)) {
        None => {
            let grad = g5.map(|x| mul0(d.d5, x));
            let hess = if want_hessian {
                Hess::Closed(i5_eigenvalues(&d, i5).map(|l| filter.apply(l)), unit(&fa))
            } else {
                Hess::Full(SMatrix::zeros())
            };
            (d.psi, grad, hess, FibrePath::ClosedI5)
        }
        Some(fr) => {
            let g4: SVector<f64, N> = fr.grad4();
            let grad = SVector::from_fn(|k, _| mul0(d.d4, g4[k]) + mul0(d.d5, g5[k]));
            if !want_hessian {
                return (
                    d.psi,
                    grad,
                    Hess::Full(SMatrix::zeros()),
                    FibrePath::Reduced,
                );
            }
            let i4_only = d.d5 == 0.0 && d.d45 == 0.0 && d.d55 == 0.0;
            if !filter.is_raw()
                && let Some(h) = reduce(&fr, &d, filter, i4_only)
            {
                return (d.psi, grad, Hess::Full(h), FibrePath::Reduced);
            }
            let h = project(&raw_hessian(&fr, a, &d, &g4, &g5), filter);
            (d.psi, grad, Hess::Full(h), FibrePath::Numeric)
        }
    }
}
