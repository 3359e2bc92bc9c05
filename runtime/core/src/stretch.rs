//! The stretch path (Zhu 2020 §4): Ψ given through ∂Ψ/∂σ and ∂²Ψ/∂σ².
//!
//! The scaling block is A = ∂²Ψ/∂σ² itself; each pair (i, j) contributes the
//! flip λ_l = (Ψ_i − Ψ_j)/(σ_i − σ_j) and the twist λ_t = (Ψ_i + Ψ_j)/(σ_i + σ_j)
//! (Zhu eq. 28), evaluated by [`crate::divided`] so that σ_i = σ_j and, for
//! sign-symmetric energies, σ_i = −σ_j use the exact limits instead of a
//! vanishing difference.

use crate::divided::{TwistRule, flip_value, twist_by_rule};
use crate::spectral::{ScaleBlock, Spectral, pair_indices};

/// Ψ's stretch-space description from ∂Ψ/∂σ (`grad`) and ∂²Ψ/∂σ² (`hess`,
/// symmetrised here). `sign_symmetric` declares Ψ unchanged by
/// (σ_i, σ_j) ↦ (−σ_j, −σ_i) (see [`crate::divided`]). An exactly diagonal
/// `hess` becomes [`ScaleBlock::Diagonal`]. `psi = +∞` yields
/// [`Spectral::infinite`]. D must be 2 or 3 (checked at compile time).
/// [`spectral_from_stretch_with`] takes a [`TwistRule`] per pair instead.
pub fn spectral_from_stretch<const D: usize>(
    sigma: &[f64; D],
    psi: f64,
    grad: [f64; D],
    hess: [[f64; D]; D],
    sign_symmetric: bool,
) -> Spectral<D> {
    let rule = if sign_symmetric {
        TwistRule::SignSymmetric
    } else {
        TwistRule::Regular
    };
    spectral_from_stretch_with(sigma, psi, grad, hess, [rule; 3])
}

/// [`spectral_from_stretch`] with the twist of pair slot k resolved by
/// `twist[k]` (what the compiler proved about σ_i + σ_j = 0). The quotient
/// is never formed exactly on σ_i + σ_j = 0 unless the rule is a removable
/// one (then the limit is used); otherwise the value there is +∞.
pub fn spectral_from_stretch_with<const D: usize>(
    sigma: &[f64; D],
    psi: f64,
    grad: [f64; D],
    hess: [[f64; D]; D],
    twist_rules: [TwistRule; 3],
) -> Spectral<D> {
    const {
        assert!(
            D == 2 || D == 3,
            "spectral_from_stretch supports D = 2 or 3"
        )
    };
    if psi == f64::INFINITY {
        return Spectral::infinite();
    }
    let mut a = hess;
    let mut diagonal = true;
    for i in 0..D {
        for j in (i + 1)..D {
            let m = 0.5 * (hess[i][j] + hess[j][i]);
            a[i][j] = m;
            a[j][i] = m;
            diagonal &= m == 0.0;
        }
    }
    let mut twist = [0.0; 3];
    let mut flip = [0.0; 3];
    for k in 0..Spectral::<D>::PAIRS {
        let (i, j) = pair_indices::<D>(k);
        let (si, sj, gi, gj) = (sigma[i], sigma[j], grad[i], grad[j]);
        let (aii, ajj, aij) = (a[i][i], a[j][j], a[i][j]);
        flip[k] = flip_value(si, sj, gi, gj, aii, ajj, aij);
        let direct = || {
            let s = si + sj;
            if s == 0.0 {
                f64::INFINITY
            } else {
                (gi + gj) / s
            }
        };
        let sym_limit = || 0.5 * (aii + ajj) + aij;
        twist[k] = twist_by_rule(si, sj, sym_limit, direct, twist_rules[k]);
    }
    let scale = if diagonal {
        ScaleBlock::Diagonal(std::array::from_fn(|i| a[i][i]))
    } else {
        ScaleBlock::Full(a)
    };
    Spectral {
        psi,
        grad,
        scale,
        twist,
        flip,
    }
}
