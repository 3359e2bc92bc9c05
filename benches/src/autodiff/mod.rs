//! The **autodiff baseline**: what TinyAD (Schmidt et al. 2022) does, in Rust.
//!
//! The element energy e(x) = |q| ψ(F(x)) is written once as a function of the
//! element's node coordinates x ∈ ℝᴺ (N = 6 for a triangle, 12 for a tet) over a
//! generic dual number, and forward-mode second-order dual numbers with static
//! size ([`num_dual::Dual2SVec64`], what TinyAD's `Scalar<N, double, true>` is)
//! give e, ∇e and the dense N×N ∇²e in one pass. The Hessian is then projected
//! numerically per element ([`ecc_runtime::reference::project_psd_numeric`]:
//! nalgebra `SymmetricEigen`, eigenvalues clamped, Q Λ⁺ Qᵀ), TinyAD's
//! `project_positive_definite`.
//!
//! Deformation gradient (node-major x, column-major Ds):
//!
//! (1) F = Ds Dm⁻¹, Ds[:, j] = x_{j+1} − x_0.
//!
//! Energies, written without an SVD (an SVD through autodiff is not what a
//! TinyAD user writes, and not stable at repeated σ):
//!
//! (2) SD, 2D: ψ = (I₂ + I₂/I₃²)/2, I₂ = ‖F‖², I₃ = det F (`sd2.psi`; Smith,
//!     de Goes, Kim 2019, Sec. 5.2);
//! (3) SD, 3D: ψ = (‖F‖² + ‖F⁻¹‖²)/2 with ‖F⁻¹‖² = ‖cof F‖²/det² F (`sd3.psi`,
//!     whose invariant form is eq. 32 of the same paper);
//! (4) SNH: ψ = μ/2 (I_C − d) + λ/2 (J − α)² − μ/2 log(I_C + 1), I_C = ‖F‖²,
//!     J = det F, α = 1 + μ/λ − μ/((d + 1)λ) (`snh.psi`; Smith, de Goes, Kim 2018, eq. 14);
//! (5) ARAP, 2D: ψ = ‖F‖² − 2 tr(RᵀF) + 2 with the closed-form 2×2 polar
//!     factor, tr(RᵀF) = √((F₀₀ + F₁₁)² + (F₁₀ − F₀₁)²) = σ₁ + σ₂ (signed σ;
//!     `arap.psi`: I₂ − 2 I₁ + d).
//!
//! Barrier energies (SD) are +∞ for det F ≤ 0, as the generated ones; the
//! dual numbers are not evaluated there. 3D ARAP has no such closed form
//! (its polar factor needs an eigensolve), so it has no baseline here.

pub mod term;

use nalgebra::{Const, DimSub, SMatrix, SVector, U1};
use num_dual::{Dual2SVec64, DualNum, DualSVec64};

use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Filter, Rest};

/// An energy written for the autodiff baseline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AdEnergy {
    /// Symmetric Dirichlet, eq. (2) / (3) (barrier).
    Sd,
    /// Stable Neo-Hookean, eq. (4).
    Snh { mu: f64, lambda: f64 },
    /// ARAP in 2D through the closed-form polar factor, eq. (5).
    Arap2,
}

impl AdEnergy {
    /// The baseline for the report's energy `name` ("SD", "SNH", "ARAP") in
    /// dimension `d`, with the `.psi` defaults (SNH μ = 1, λ = 10); `None`
    /// where there is no honest SVD-free form (3D ARAP) or no formula here.
    pub fn for_name(name: &str, d: usize) -> Option<AdEnergy> {
        match (name, d) {
            ("SD", 2 | 3) => Some(AdEnergy::Sd),
            ("SNH", 2 | 3) => Some(AdEnergy::Snh {
                mu: 1.0,
                lambda: 10.0,
            }),
            ("ARAP", 2) => Some(AdEnergy::Arap2),
            _ => None,
        }
    }

    /// The baseline for a library energy by its `Energy::name` (the `.psi`
    /// stem: "sd2", "sd3", "snh", "arap"), as [`AdEnergy::for_name`].
    pub fn for_energy(stem: &str, d: usize) -> Option<AdEnergy> {
        let name = match stem {
            "sd2" | "sd3" => "SD",
            "snh" => "SNH",
            "arap" => "ARAP",
            _ => return None,
        };
        AdEnergy::for_name(name, d)
    }

    /// ψ = +∞ for det F ≤ 0.
    pub fn barrier(self) -> bool {
        self == AdEnergy::Sd
    }

    /// ψ(F) for a row-major d×d F (d = 2 or 3), eqs. (2)–(5).
    pub fn psi<T: DualNum<Primitive = f64> + Copy, const D: usize>(self, f: &[[T; D]; D]) -> T {
        let i2 = f.iter().flatten().fold(T::from(0.0), |a, &v| a + v * v);
        let j = det(f);
        match self {
            AdEnergy::Sd if D == 2 => (i2 + i2 / (j * j)) * 0.5,
            AdEnergy::Sd => (i2 + cof_norm2(f) / (j * j)) * 0.5,
            AdEnergy::Snh { mu, lambda } => {
                let d = D as f64;
                let alpha = 1.0 + mu / lambda - mu / ((d + 1.0) * lambda);
                let ja = j - alpha;
                (i2 - d) * (mu / 2.0) + ja * ja * (lambda / 2.0) - (i2 + 1.0).ln() * (mu / 2.0)
            }
            AdEnergy::Arap2 => {
                let (a, b) = (f[0][0] + f[1][1], f[1][0] - f[0][1]);
                i2 - (a * a + b * b).sqrt() * 2.0 + 2.0
            }
        }
    }
}

/// det F (d = 2 or 3).
fn det<T: DualNum<Primitive = f64> + Copy, const D: usize>(f: &[[T; D]; D]) -> T {
    if D == 2 {
        f[0][0] * f[1][1] - f[0][1] * f[1][0]
    } else {
        f[0][0] * (f[1][1] * f[2][2] - f[1][2] * f[2][1])
            - f[0][1] * (f[1][0] * f[2][2] - f[1][2] * f[2][0])
            + f[0][2] * (f[1][0] * f[2][1] - f[1][1] * f[2][0])
    }
}

/// ‖cof F‖² for a 3×3 F (the squared 2×2 minors).
fn cof_norm2<T: DualNum<Primitive = f64> + Copy, const D: usize>(f: &[[T; D]; D]) -> T {
    let mut acc = T::from(0.0);
    for (r0, r1) in [(1, 2), (2, 0), (0, 1)] {
        for (c0, c1) in [(1, 2), (2, 0), (0, 1)] {
            let m = f[r0][c0] * f[r1][c1] - f[r0][c1] * f[r1][c0];
            acc += m * m;
        }
    }
    acc
}

/// F of eq. (1) from node-major coordinates `x` (length (d + 1)d).
pub fn deformation<T: DualNum<Primitive = f64> + Copy, const D: usize>(
    x: &[T],
    rest: &Rest<D>,
) -> [[T; D]; D] {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            (0..D).fold(T::from(0.0), |acc, j| {
                acc + (x[(j + 1) * D + r] - x[r]) * rest.dm_inv[(j, c)]
            })
        })
    })
}

/// True when det Ds > 0 (det Dm > 0, so this is det F > 0).
fn inside<const D: usize>(x: &[f64], rest: &Rest<D>) -> bool {
    det(&deformation(x, rest)) > 0.0
}

/// e(x) = |q| ψ(F(x)) in plain f64 (+∞ outside a barrier's domain).
pub fn element_value<const D: usize>(e: AdEnergy, rest: &Rest<D>, x: &[f64]) -> f64 {
    if e.barrier() && !inside(x, rest) {
        return f64::INFINITY;
    }
    rest.measure * e.psi(&deformation(x, rest))
}

/// e and ∇e at node-major `x` by first-order dual numbers (TinyAD's
/// `eval_with_gradient`); `None` outside a barrier's domain.
pub fn element_gradient<const D: usize, const N: usize>(
    e: AdEnergy,
    rest: &Rest<D>,
    x: &[f64],
) -> Option<(f64, SVector<f64, N>)> {
    if e.barrier() && !inside(x, rest) {
        return None;
    }
    let x0 = SVector::<f64, N>::from_fn(|i, _| x[i]);
    let m = rest.measure;
    Some(num_dual::gradient(
        |v: SVector<DualSVec64<N>, N>| e.psi(&deformation(v.as_slice(), rest)) * m,
        &x0,
    ))
}

/// e, ∇e and the raw ∇²e at node-major `x` (N = (d + 1)d) by forward-mode
/// second-order dual numbers; `None` outside a barrier's domain.
pub fn element_hessian<const D: usize, const N: usize>(
    e: AdEnergy,
    rest: &Rest<D>,
    x: &[f64],
) -> Option<(f64, SVector<f64, N>, SMatrix<f64, N, N>)> {
    if e.barrier() && !inside(x, rest) {
        return None;
    }
    let x0 = SVector::<f64, N>::from_fn(|i, _| x[i]);
    let m = rest.measure;
    let (v, g, h) = num_dual::hessian(
        |v: SVector<Dual2SVec64<N>, N>| e.psi(&deformation(v.as_slice(), rest)) * m,
        &x0,
    );
    Some((v, g, h))
}

/// The baseline's element evaluation: autodiff e, ∇e, ∇²e, then the numeric
/// projection of ∇²e by `filter` (`Filter::None`: raw). `None` outside a
/// barrier's domain.
pub fn element_projected<const D: usize, const N: usize>(
    e: AdEnergy,
    rest: &Rest<D>,
    x: &[f64],
    filter: Filter,
) -> Option<(f64, SVector<f64, N>, SMatrix<f64, N, N>)>
where
    Const<N>: DimSub<U1>,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<nalgebra::DimDiff<Const<N>, U1>>,
{
    let (v, g, h) = element_hessian::<D, N>(e, rest, x)?;
    let h = if filter == Filter::None {
        h
    } else {
        project_psd_numeric(&h, filter)
    };
    Some((v, g, h))
}
