//! Symmetric Dirichlet: Ψ = ½(‖F‖² + ‖F⁻¹‖²) = ½ Σ(σ_i² + σ_i⁻²).
//!
//! Closed form (Smith et al. 2019 eqs. 31–35, written in σ without any
//! removable singularity): Ψ_σi = σ_i − σ_i⁻³, A = diag(1 + 3σ_i⁻⁴)
//! (decoupled), and for the pair (i, j)
//!
//! * flip  λ_l = 1 + (σ_i² + σ_iσ_j + σ_j²)/(σ_i³σ_j³)  (eq. 35; 2D eq. 31c: 1 + 1/I3² + I2/I3³),
//! * twist λ_t = 1 − (σ_i² − σ_iσ_j + σ_j²)/(σ_i³σ_j³)  (eq. 34; 2D eq. 31d: 1 + 1/I3² − I2/I3³),
//!
//! obtained by factoring σ_i ∓ σ_j out of Ψ_i ∓ Ψ_j. Barrier: Ψ = +∞ exactly at
//! det F = 0 (any σ_i = 0) or on overflow; elsewhere — including inverted
//! F — the formula value. In 2D Ψ = ½(I2 + I2/I3²) needs no SVD.

use crate::energy::{Energy, EnergyInfo};
use crate::spectral::{ScaleBlock, Spectral, pair_indices};

/// The Symmetric Dirichlet energy (no parameters).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SymmetricDirichlet;

fn psi<const D: usize>(s: &[f64; D]) -> f64 {
    if s.contains(&0.0) {
        return f64::INFINITY;
    }
    let v: f64 = s.iter().map(|x| x * x + 1.0 / (x * x)).sum::<f64>() * 0.5;
    if v.is_finite() { v } else { f64::INFINITY }
}

fn spectral<const D: usize>(s: &[f64; D]) -> Spectral<D> {
    let p = psi(s);
    if !p.is_finite() {
        return Spectral::infinite();
    }
    let inv: [f64; D] = std::array::from_fn(|i| 1.0 / s[i]);
    let mut twist = [0.0; 3];
    let mut flip = [0.0; 3];
    for k in 0..Spectral::<D>::PAIRS {
        let (i, j) = pair_indices::<D>(k);
        // 1/(σ_i³σ_j³) · (σ_i² ± σ_iσ_j + σ_j²) = q_i q_j (q_i² ± q_i q_j + q_j²), q = 1/σ.
        let (qi, qj) = (inv[i], inv[j]);
        let qq = qi * qj;
        let sq = qi * qi + qj * qj;
        flip[k] = 1.0 + qq * (sq + qq);
        twist[k] = 1.0 - qq * (sq - qq);
    }
    Spectral {
        psi: p,
        grad: std::array::from_fn(|i| s[i] - inv[i] * inv[i] * inv[i]),
        scale: ScaleBlock::Diagonal(std::array::from_fn(|i| {
            let q2 = inv[i] * inv[i];
            1.0 + 3.0 * q2 * q2
        })),
        twist,
        flip,
    }
}

impl Energy<2> for SymmetricDirichlet {
    fn name(&self) -> &str {
        "symmetric_dirichlet"
    }
    fn psi(&self, sigma: &[f64; 2]) -> f64 {
        psi(sigma)
    }
    fn spectral(&self, sigma: &[f64; 2]) -> Spectral<2> {
        spectral(sigma)
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: true,
        }
    }
    /// Ψ = ½(I2 + I2/I3²) (‖F⁻¹‖² = ‖F‖²/det² in 2D).
    fn psi_i2_i3(&self, i2: f64, i3: f64) -> Option<f64> {
        if i3 == 0.0 {
            return Some(f64::INFINITY);
        }
        let v = 0.5 * (i2 + i2 / (i3 * i3));
        Some(if v.is_finite() { v } else { f64::INFINITY })
    }
}

impl Energy<3> for SymmetricDirichlet {
    fn name(&self) -> &str {
        "symmetric_dirichlet"
    }
    fn psi(&self, sigma: &[f64; 3]) -> f64 {
        psi(sigma)
    }
    fn spectral(&self, sigma: &[f64; 3]) -> Spectral<3> {
        spectral(sigma)
    }
    /// ‖F⁻¹‖² is not a function of I2 and I3 in 3D, so Ψ needs the SVD.
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
}
