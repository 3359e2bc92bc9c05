//! As-Rigid-As-Possible: Ψ = ‖F − R‖² = Σ(σ_i − 1)² = I2 − 2I1 + d.
//!
//! Closed form (Smith et al. 2019 eqs. 28–30): Ψ_σi = 2(σ_i − 1), A = 2I
//! (decoupled), flips λ_l = 2, twists λ_t = (Ψ_i + Ψ_j)/(σ_i + σ_j) =
//! 2 − 4/(σ_i + σ_j). The twist has a genuine pole at σ_i + σ_j = 0 (ARAP is
//! not sign-symmetric): exactly there it is +∞, the convention every back end
//! follows for a pole (the two one-sided limits differ in sign), and the
//! filters map it to their floor.

use crate::energy::{Energy, EnergyInfo};
use crate::spectral::{ScaleBlock, Spectral, pair_indices};

/// The ARAP energy (no parameters).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Arap;

fn psi<const D: usize>(s: &[f64; D]) -> f64 {
    s.iter().map(|x| (x - 1.0) * (x - 1.0)).sum()
}

fn spectral<const D: usize>(s: &[f64; D]) -> Spectral<D> {
    let psi = psi(s);
    if !psi.is_finite() {
        // Ψ overflowed (|σ| ≳ 1e154): no derivatives, as for any Ψ = +∞
        return Spectral::infinite();
    }
    let mut twist = [0.0; 3];
    let mut flip = [0.0; 3];
    for k in 0..Spectral::<D>::PAIRS {
        let (i, j) = pair_indices::<D>(k);
        let sum = s[i] + s[j];
        twist[k] = if sum == 0.0 {
            f64::INFINITY // the pole itself (see the module docs)
        } else {
            2.0 - 4.0 / sum
        };
        flip[k] = 2.0;
    }
    Spectral {
        psi,
        grad: std::array::from_fn(|i| 2.0 * (s[i] - 1.0)),
        scale: ScaleBlock::Diagonal([2.0; D]),
        twist,
        flip,
    }
}

impl Energy<2> for Arap {
    fn name(&self) -> &str {
        "arap"
    }
    fn psi(&self, sigma: &[f64; 2]) -> f64 {
        psi(sigma)
    }
    fn spectral(&self, sigma: &[f64; 2]) -> Spectral<2> {
        spectral(sigma)
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: false,
            svd_free_psi: false,
        }
    }
}

impl Energy<3> for Arap {
    fn name(&self) -> &str {
        "arap"
    }
    fn psi(&self, sigma: &[f64; 3]) -> f64 {
        psi(sigma)
    }
    fn spectral(&self, sigma: &[f64; 3]) -> Spectral<3> {
        spectral(sigma)
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: false,
            svd_free_psi: false,
        }
    }
}
