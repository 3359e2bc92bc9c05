//! Test-only energies built through the two generic paths
//! (`spectral_from_invariants`, `spectral_from_stretch`). Their derivatives are
//! written out by hand here, independently of the runtime's hand-written energies.

use ecc_runtime::{Energy, EnergyInfo, Spectral, spectral_from_invariants, spectral_from_stretch};

fn inv3(s: &[f64; 3]) -> (f64, f64, f64) {
    (
        s[0] + s[1] + s[2],
        s[0] * s[0] + s[1] * s[1] + s[2] * s[2],
        s[0] * s[1] * s[2],
    )
}
fn inv2(s: &[f64; 2]) -> (f64, f64, f64) {
    (s[0] + s[1], s[0] * s[0] + s[1] * s[1], s[0] * s[1])
}

/// MIPS 2D, Ψ = I2/I3 (Smith et al. 2019 §5.3): coupled scaling modes.
pub struct Mips2;
impl Energy<2> for Mips2 {
    fn name(&self) -> &str {
        "mips2d (invariants)"
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        let (_, i2, i3) = inv2(s);
        if i3 == 0.0 { f64::INFINITY } else { i2 / i3 }
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        let (_, i2, i3) = inv2(s);
        if i3 == 0.0 {
            return Spectral::infinite();
        }
        let d1 = [0.0, 1.0 / i3, -i2 / (i3 * i3)];
        // [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23]
        let d2 = [
            0.0,
            0.0,
            2.0 * i2 / (i3 * i3 * i3),
            0.0,
            0.0,
            -1.0 / (i3 * i3),
        ];
        spectral_from_invariants(s, i2 / i3, d1, d2, false, true)
    }
}

/// ARAP through the invariant path: Ψ = I2 − 2 I1 + d (not sign-symmetric).
pub struct ArapInv;
impl Energy<2> for ArapInv {
    fn name(&self) -> &str {
        "arap (invariants)"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        let (i1, i2, _) = inv2(s);
        i2 - 2.0 * i1 + 2.0
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        spectral_from_invariants(
            s,
            Energy::<2>::psi(self, s),
            [-2.0, 1.0, 0.0],
            [0.0; 6],
            true,
            false,
        )
    }
}
impl Energy<3> for ArapInv {
    fn name(&self) -> &str {
        "arap (invariants)"
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        let (i1, i2, _) = inv3(s);
        i2 - 2.0 * i1 + 3.0
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        spectral_from_invariants(
            s,
            Energy::<3>::psi(self, s),
            [-2.0, 1.0, 0.0],
            [0.0; 6],
            true,
            false,
        )
    }
}

/// Symmetric Dirichlet 2D through invariants: Ψ = (I2 + I2/I3²)/2.
pub struct Sd2Inv {
    pub decoupled: bool,
}
impl Energy<2> for Sd2Inv {
    fn name(&self) -> &str {
        "sd2d (invariants)"
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        let (_, i2, i3) = inv2(s);
        if i3 == 0.0 {
            f64::INFINITY
        } else {
            0.5 * (i2 + i2 / (i3 * i3))
        }
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        let (_, i2, i3) = inv2(s);
        if i3 == 0.0 {
            return Spectral::infinite();
        }
        let i3_2 = i3 * i3;
        let d1 = [0.0, 0.5 * (1.0 + 1.0 / i3_2), -i2 / (i3_2 * i3)];
        let d2 = [
            0.0,
            0.0,
            3.0 * i2 / (i3_2 * i3_2),
            0.0,
            0.0,
            -1.0 / (i3_2 * i3),
        ];
        spectral_from_invariants(s, Energy::<2>::psi(self, s), d1, d2, self.decoupled, true)
    }
}

/// Symmetric Dirichlet 3D through invariants, Smith et al. 2019 eq. 32:
/// Ψ = I2/2 + ((I1² − I2)/I3)²/8 − I1/I3 (uses I1 although sign-symmetric).
pub struct Sd3Inv {
    pub decoupled: bool,
}
impl Energy<3> for Sd3Inv {
    fn name(&self) -> &str {
        "sd3d (invariants, eq. 32)"
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        let (i1, i2, i3) = inv3(s);
        if i3 == 0.0 {
            return f64::INFINITY;
        }
        let q = (i1 * i1 - i2) / i3;
        0.5 * i2 + q * q / 8.0 - i1 / i3
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        let (i1, i2, i3) = inv3(s);
        if i3 == 0.0 {
            return Spectral::infinite();
        }
        let q = (i1 * i1 - i2) / i3;
        let j2 = i3 * i3;
        let d1 = [
            q * i1 / (2.0 * i3) - 1.0 / i3,
            0.5 - q / (4.0 * i3),
            -q * q / (4.0 * i3) + i1 / j2,
        ];
        let p11 = (2.0 * i1 * i1 / i3 + q) / (2.0 * i3);
        let p12 = -i1 / (2.0 * j2);
        let p13 = -i1 * q / j2 + 1.0 / j2;
        let p22 = 1.0 / (4.0 * j2);
        let p23 = q / (2.0 * j2);
        let p33 = 3.0 * q * q / (4.0 * j2) - 2.0 * i1 / (j2 * i3);
        spectral_from_invariants(
            s,
            Energy::<3>::psi(self, s),
            d1,
            [p11, p22, p33, p12, p13, p23],
            self.decoupled,
            true,
        )
    }
}

/// Hencky-like Σ log²|σ_i| through the stretch path (sign-symmetric; +∞ at σ = 0).
pub struct Hencky;
fn hencky<const D: usize>(s: &[f64; D]) -> Spectral<D> {
    if s.contains(&0.0) {
        return Spectral::infinite();
    }
    let l: [f64; D] = std::array::from_fn(|i| s[i].abs().ln());
    let psi = l.iter().map(|x| x * x).sum();
    let grad = std::array::from_fn(|i| 2.0 * l[i] / s[i]);
    let hess = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                (2.0 - 2.0 * l[i]) / (s[i] * s[i])
            } else {
                0.0
            }
        })
    });
    spectral_from_stretch(s, psi, grad, hess, true)
}
impl Energy<2> for Hencky {
    fn name(&self) -> &str {
        "hencky (stretch)"
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        hencky(s).psi
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        hencky(s)
    }
}
impl Energy<3> for Hencky {
    fn name(&self) -> &str {
        "hencky (stretch)"
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo {
            barrier: true,
            svd_free_psi: false,
        }
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        hencky(s).psi
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        hencky(s)
    }
}

/// Polynomial Σσ_i⁴ + 2(J − 1)² + I2 through the stretch path (sign-symmetric,
/// coupled scaling block).
pub struct Poly;
fn poly<const D: usize>(s: &[f64; D]) -> Spectral<D> {
    let j: f64 = s.iter().product();
    // cof_i = Π_{k≠i} σ_k, and ∂cof_i/∂σ_l = Π_{k∉{i,l}} σ_k.
    let cof: [f64; D] = std::array::from_fn(|i| (0..D).filter(|&k| k != i).map(|k| s[k]).product());
    let cof2 = |i: usize, l: usize| -> f64 {
        (0..D).filter(|&k| k != i && k != l).map(|k| s[k]).product()
    };
    let psi = s.iter().map(|x| x.powi(4) + x * x).sum::<f64>() + 2.0 * (j - 1.0) * (j - 1.0);
    let grad = std::array::from_fn(|i| 4.0 * s[i].powi(3) + 2.0 * s[i] + 4.0 * (j - 1.0) * cof[i]);
    let hess = std::array::from_fn(|i| {
        std::array::from_fn(|l| {
            if i == l {
                12.0 * s[i] * s[i] + 2.0 + 4.0 * cof[i] * cof[i]
            } else {
                4.0 * cof[l] * cof[i] + 4.0 * (j - 1.0) * cof2(i, l)
            }
        })
    });
    spectral_from_stretch(s, psi, grad, hess, true)
}
impl Energy<2> for Poly {
    fn name(&self) -> &str {
        "poly (stretch)"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        poly(s).psi
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        poly(s)
    }
}
impl Energy<3> for Poly {
    fn name(&self) -> &str {
        "poly (stretch)"
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        poly(s).psi
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        poly(s)
    }
}

/// ARAP through the stretch path, Ψ = Σ(σ_i − 1)², declared not sign-symmetric.
pub struct ArapStretch;
fn arap_stretch<const D: usize>(s: &[f64; D]) -> Spectral<D> {
    let psi = s.iter().map(|x| (x - 1.0) * (x - 1.0)).sum();
    let grad = std::array::from_fn(|i| 2.0 * (s[i] - 1.0));
    let hess = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 2.0 } else { 0.0 }));
    spectral_from_stretch(s, psi, grad, hess, false)
}
impl Energy<2> for ArapStretch {
    fn name(&self) -> &str {
        "arap (stretch)"
    }
    fn psi(&self, s: &[f64; 2]) -> f64 {
        arap_stretch(s).psi
    }
    fn spectral(&self, s: &[f64; 2]) -> Spectral<2> {
        arap_stretch(s)
    }
}
impl Energy<3> for ArapStretch {
    fn name(&self) -> &str {
        "arap (stretch)"
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        arap_stretch(s).psi
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        arap_stretch(s)
    }
}
