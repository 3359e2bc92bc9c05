//! Stable Neo-Hookean (Smith, de Goes, Kim 2018) in d = 2 or 3 dimensions:
//!
//! Ψ = μ/2 (I2 − d) + λ/2 (J − α)² − μ/2 log(I2 + 1),  α = 1 + μ/λ − μ/((d+1)λ),
//!
//! with I2 = ‖F‖² = I_C and J = I3 = det F. α makes F = I stress-free in d
//! dimensions. Written with κ = λ(α − 1) = μ d/(d+1):
//! λ/2 (J − α)² = λ/2 (J − 1)² − κ(J − 1) + κ²/(2λ), which stays finite for
//! λ → 0 (the constant κ²/(2λ) is then dropped: it does not affect any
//! derivative).
//!
//! Invariant derivatives: Ψ2 = μ/2 − μ/(2(I2+1)), Ψ22 = μ/(2(I2+1)²),
//! Ψ3 = λ(J − 1) − κ, Ψ33 = λ, all others 0. Hence (Smith et al. 2019 §4):
//! Ψ_σi = 2Ψ2 σ_i + Ψ3 Π_{j≠i}σ_j; twist/flip of slot k = 2Ψ2 ± σ_k Ψ3 (2D: 2Ψ2 ± Ψ3);
//! the scaling block is coupled (App. D): a_ii = 2Ψ2 + 4σ_i²Ψ22 + (Π_{j≠i}σ_j)²Ψ33,
//! a_ij = σ_kΨ3 + 4σ_iσ_jΨ22 + σ_k J Ψ33 (2D: a_01 = Ψ3 + 4JΨ22 + JΨ33).
//! Ψ depends on I2 and J only, so it is SVD-free and sign-symmetric.

use super::param_error;
use crate::energy::{Energy, EnergyInfo, ParamError};
use crate::spectral::{PAIRS_3D, ScaleBlock, Spectral};

/// Stable Neo-Hookean with parameters μ (`mu`) and λ (`lambda`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StableNeoHookean {
    /// Shear-like modulus μ.
    pub mu: f64,
    /// Volume-like modulus λ.
    pub lambda: f64,
}

impl StableNeoHookean {
    /// A Stable Neo-Hookean energy with the given μ and λ.
    pub fn new(mu: f64, lambda: f64) -> Self {
        StableNeoHookean { mu, lambda }
    }

    /// κ = μ d/(d+1) = λ(α − 1).
    #[inline]
    fn kappa(&self, d: usize) -> f64 {
        self.mu * d as f64 / (d as f64 + 1.0)
    }

    /// Ψ(I2, J) in dimension d.
    fn psi_inv(&self, d: usize, i2: f64, j: f64) -> f64 {
        let (mu, lam) = (self.mu, self.lambda);
        let k = self.kappa(d);
        let c0 = if lam != 0.0 { k * k / (2.0 * lam) } else { 0.0 };
        let jm1 = j - 1.0;
        let v = 0.5 * mu * (i2 - d as f64) + 0.5 * lam * jm1 * jm1 - k * jm1 + c0
            - 0.5 * mu * (i2 + 1.0).ln();
        if v.is_nan() { f64::INFINITY } else { v }
    }

    /// (2Ψ2, 4Ψ22, Ψ3, Ψ33) at (I2, J).
    #[inline]
    fn derivs(&self, d: usize, i2: f64, j: f64) -> (f64, f64, f64, f64) {
        let r = 1.0 / (i2 + 1.0);
        let two_p2 = self.mu * (1.0 - r);
        let four_p22 = 2.0 * self.mu * r * r;
        let p3 = self.lambda * (j - 1.0) - self.kappa(d);
        (two_p2, four_p22, p3, self.lambda)
    }

    fn params_list(&self) -> Vec<(String, f64)> {
        vec![
            ("mu".to_string(), self.mu),
            ("lambda".to_string(), self.lambda),
        ]
    }

    fn set(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        match name {
            "mu" if value.is_finite() => self.mu = value,
            "lambda" if value.is_finite() => self.lambda = value,
            _ => return Err(param_error(name, value, &["mu", "lambda"])),
        }
        Ok(())
    }
}

impl Energy<2> for StableNeoHookean {
    fn name(&self) -> &str {
        "stable_neo_hookean"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        self.psi_inv(2, s[0] * s[0] + s[1] * s[1], s[0] * s[1])
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        let i2 = s[0] * s[0] + s[1] * s[1];
        let j = s[0] * s[1];
        let psi = self.psi_inv(2, i2, j);
        if !psi.is_finite() {
            // outside the domain or overflowed: no derivatives (no ∞ − ∞ = NaN)
            return Spectral::infinite();
        }
        let (tp2, fp22, p3, p33) = self.derivs(2, i2, j);
        let a00 = tp2 + fp22 * s[0] * s[0] + s[1] * s[1] * p33;
        let a11 = tp2 + fp22 * s[1] * s[1] + s[0] * s[0] * p33;
        let a01 = p3 + fp22 * j + j * p33;
        Spectral {
            psi,
            grad: [tp2 * s[0] + p3 * s[1], tp2 * s[1] + p3 * s[0]],
            scale: ScaleBlock::Full([[a00, a01], [a01, a11]]),
            twist: [tp2 + p3, 0.0, 0.0],
            flip: [tp2 - p3, 0.0, 0.0],
        }
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: false,
            svd_free_psi: true,
        }
    }
    fn psi_i2_i3(&self, i2: f64, i3: f64) -> Option<f64> {
        Some(self.psi_inv(2, i2, i3))
    }
    fn params(&self) -> Vec<(String, f64)> {
        self.params_list()
    }
    fn set_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        self.set(name, value)
    }
}

impl Energy<3> for StableNeoHookean {
    fn name(&self) -> &str {
        "stable_neo_hookean"
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        self.psi_inv(
            3,
            s[0] * s[0] + s[1] * s[1] + s[2] * s[2],
            s[0] * s[1] * s[2],
        )
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        let i2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        let j = s[0] * s[1] * s[2];
        let psi = self.psi_inv(3, i2, j);
        if !psi.is_finite() {
            return Spectral::infinite();
        }
        let (tp2, fp22, p3, p33) = self.derivs(3, i2, j);
        let cof = [s[1] * s[2], s[2] * s[0], s[0] * s[1]];
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            a[i][i] = tp2 + fp22 * s[i] * s[i] + cof[i] * cof[i] * p33;
        }
        let mut twist = [0.0; 3];
        let mut flip = [0.0; 3];
        for (k, &(i, jj)) in PAIRS_3D.iter().enumerate() {
            let aij = s[k] * p3 + fp22 * s[i] * s[jj] + s[k] * j * p33;
            a[i][jj] = aij;
            a[jj][i] = aij;
            twist[k] = tp2 + s[k] * p3;
            flip[k] = tp2 - s[k] * p3;
        }
        Spectral {
            psi,
            grad: std::array::from_fn(|i| tp2 * s[i] + p3 * cof[i]),
            scale: ScaleBlock::Full(a),
            twist,
            flip,
        }
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: false,
            svd_free_psi: true,
        }
    }
    fn psi_i2_i3(&self, i2: f64, i3: f64) -> Option<f64> {
        Some(self.psi_inv(3, i2, i3))
    }
    fn params(&self) -> Vec<(String, f64)> {
        self.params_list()
    }
    fn set_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        self.set(name, value)
    }
}
