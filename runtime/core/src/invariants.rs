//! The invariant path (Smith et al. 2019 §4): Ψ given through ∂Ψ/∂I_k and
//! ∂²Ψ/∂I_k∂I_l of the stretch invariants I1 = tr S = Σσ_i, I2 = ‖F‖² = Σσ_i²,
//! I3 = det F = Πσ_i.
//!
//! With Ψ_k = ∂Ψ/∂I_k, Ψ_kl = ∂²Ψ/∂I_k∂I_l and, in 3D, the slot k pair (i, j):
//!
//! * gradient (eqs. 8, 10, 15, 16, 19): ∂Ψ/∂F = Ψ1 R + 2Ψ2 F + Ψ3 G, i.e. in the
//!   SVD frame Ψ_σi = Ψ1 + 2σ_i Ψ2 + (Π_{j≠i} σ_j) Ψ3 (no division by σ_i);
//! * twist/flip (eqs. 22–23): 2D λ_t = 2Ψ1/(σ0+σ1) + 2Ψ2 + Ψ3, λ_l = 2Ψ2 − Ψ3;
//!   3D λ_t = 2Ψ1/(σ_i+σ_j) + 2Ψ2 + σ_k Ψ3, λ_l = 2Ψ2 − σ_k Ψ3;
//! * scaling block A (App. D), 2D with j the other index:
//!   a_ii = 2Ψ2 + Ψ11 + 4σ_i²Ψ22 + σ_j²Ψ33 + 4σ_iΨ12 + 4I3Ψ23 + 2σ_jΨ13,
//!   a_01 = Ψ3 + Ψ11 + 4I3Ψ22 + I3Ψ33 + 2I1Ψ12 + 2I2Ψ23 + I1Ψ13;
//!   3D with {i, j, k} = {0, 1, 2}:
//!   a_ii = 2Ψ2 + Ψ11 + 4σ_i²Ψ22 + σ_j²σ_k²Ψ33 + 4σ_iΨ12 + 4I3Ψ23 + 2σ_jσ_kΨ13,
//!   a_ij = σ_kΨ3 + Ψ11 + 4σ_iσ_jΨ22 + σ_k I3 Ψ33 + 2(I1−σ_k)Ψ12 +
//!   2σ_k(I2−σ_k²)Ψ23 + σ_k(I1−σ_k)Ψ13.
//!   These equal ∂²Ψ/∂σ_i∂σ_j by the chain rule. When the energy declares the
//!   scaling modes decoupled (a_ij ≡ 0) only the diagonal is formed
//!   (eqs. 26–27, App. E) and no eigensolve is needed.
//!
//! The only division is 2Ψ1/(σ_i+σ_j). Where Ψ1 vanishes identically on
//! σ_i + σ_j = 0 the singularity is removable: for a sign-symmetric energy
//! whose representation still uses I1 (e.g. 3D Symmetric Dirichlet, eq. 32)
//! the individual terms blow up while their sum stays finite, and within the
//! switch band of [`crate::divided`] the twist is the limit
//! (a_ii + a_jj)/2 + a_ij; without sign symmetry (2D I1²·e^{I1}) the compiler
//! supplies the corrected limit ([`TwistRule::Removable`]). Otherwise the
//! pole is genuine: +∞ exactly on it ([`TwistRule::Pole`]).

use crate::divided::{TwistRule, twist_by_rule};
use crate::spectral::{PAIRS_3D, ScaleBlock, Spectral};

/// Ψ's stretch-space description from its invariant derivatives.
///
/// `d1 = [Ψ1, Ψ2, Ψ3]`, `d2 = [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23]`; `decoupled`
/// declares a_ij ≡ 0 (diagonal scaling block); `sign_symmetric` declares
/// Ψ(…σ_i…σ_j…) = Ψ(…−σ_j…−σ_i…) (see the module docs). `psi = +∞` yields
/// [`Spectral::infinite`]. D must be 2 or 3 (checked at compile time).
/// [`spectral_from_invariants_with`] takes a [`TwistRule`] per pair instead.
pub fn spectral_from_invariants<const D: usize>(
    sigma: &[f64; D],
    psi: f64,
    d1: [f64; 3],
    d2: [f64; 6],
    decoupled: bool,
    sign_symmetric: bool,
) -> Spectral<D> {
    let rule = if sign_symmetric {
        TwistRule::SignSymmetric
    } else {
        TwistRule::Regular
    };
    spectral_from_invariants_with(sigma, psi, d1, d2, decoupled, [rule; 3])
}

/// [`spectral_from_invariants`] with the twist of pair slot k resolved by
/// `twist[k]` (what the compiler proved about σ_i + σ_j = 0; 2D uses slot 0).
pub fn spectral_from_invariants_with<const D: usize>(
    sigma: &[f64; D],
    psi: f64,
    d1: [f64; 3],
    d2: [f64; 6],
    decoupled: bool,
    twist: [TwistRule; 3],
) -> Spectral<D> {
    const {
        assert!(
            D == 2 || D == 3,
            "spectral_from_invariants supports D = 2 or 3"
        )
    };
    if psi == f64::INFINITY {
        return Spectral::infinite();
    }
    let mut s3 = [0.0; 3];
    s3[..D].copy_from_slice(sigma);
    let (grad, a, twist, flip) = if D == 2 {
        invariants_2d([s3[0], s3[1]], d1, d2, decoupled, twist[0])
    } else {
        invariants_3d(s3, d1, d2, decoupled, twist)
    };
    let scale = if decoupled {
        ScaleBlock::Diagonal(std::array::from_fn(|i| a[i][i]))
    } else {
        ScaleBlock::Full(std::array::from_fn(|i| std::array::from_fn(|j| a[i][j])))
    };
    Spectral {
        psi,
        grad: std::array::from_fn(|i| grad[i]),
        scale,
        twist,
        flip,
    }
}

/// The twist 2Ψ1/(σ_i+σ_j) + `base` under `rule`. The limit comes first: on
/// σ_i = −σ_j a removable Ψ1 is 0 while 2Ψ1/(σ_i + σ_j) tends to a non-zero
/// limit; Ψ1 == 0 elsewhere drops the (then exactly zero) quotient.
fn twist_inv(si: f64, sj: f64, p1: f64, base: f64, sym_limit: f64, rule: TwistRule) -> f64 {
    let direct = || {
        if p1 == 0.0 {
            base
        } else {
            2.0 * p1 / (si + sj) + base
        }
    };
    twist_by_rule(si, sj, || sym_limit, direct, rule)
}

type Parts = ([f64; 3], [[f64; 3]; 3], [f64; 3], [f64; 3]);

fn invariants_2d(
    s: [f64; 2],
    d1: [f64; 3],
    d2: [f64; 6],
    decoupled: bool,
    rule: TwistRule,
) -> Parts {
    let [p1, p2, p3] = d1;
    let [p11, p22, p33, p12, p13, p23] = d2;
    let i1 = s[0] + s[1];
    let i2 = s[0] * s[0] + s[1] * s[1];
    let i3 = s[0] * s[1];
    let grad = [
        p1 + 2.0 * s[0] * p2 + s[1] * p3,
        p1 + 2.0 * s[1] * p2 + s[0] * p3,
        0.0,
    ];
    let aii = |si: f64, sj: f64| {
        2.0 * p2
            + p11
            + 4.0 * si * si * p22
            + sj * sj * p33
            + 4.0 * si * p12
            + 4.0 * i3 * p23
            + 2.0 * sj * p13
    };
    let mut a = [[0.0; 3]; 3];
    a[0][0] = aii(s[0], s[1]);
    a[1][1] = aii(s[1], s[0]);
    if !decoupled {
        let a01 = p3 + p11 + 4.0 * i3 * p22 + i3 * p33 + 2.0 * i1 * p12 + 2.0 * i2 * p23 + i1 * p13;
        a[0][1] = a01;
        a[1][0] = a01;
    }
    let sym_limit = 0.5 * (a[0][0] + a[1][1]) + a[0][1];
    let twist0 = twist_inv(s[0], s[1], p1, 2.0 * p2 + p3, sym_limit, rule);
    (grad, a, [twist0, 0.0, 0.0], [2.0 * p2 - p3, 0.0, 0.0])
}

fn invariants_3d(
    s: [f64; 3],
    d1: [f64; 3],
    d2: [f64; 6],
    decoupled: bool,
    rules: [TwistRule; 3],
) -> Parts {
    let [p1, p2, p3] = d1;
    let [p11, p22, p33, p12, p13, p23] = d2;
    let i1 = s[0] + s[1] + s[2];
    let i2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    let i3 = s[0] * s[1] * s[2];
    // Π_{j≠i} σ_j without dividing by σ_i.
    let cof = [s[1] * s[2], s[2] * s[0], s[0] * s[1]];
    let grad: [f64; 3] = std::array::from_fn(|i| p1 + 2.0 * s[i] * p2 + cof[i] * p3);
    let mut a = [[0.0; 3]; 3];
    for i in 0..3 {
        a[i][i] = 2.0 * p2
            + p11
            + 4.0 * s[i] * s[i] * p22
            + cof[i] * cof[i] * p33
            + 4.0 * s[i] * p12
            + 4.0 * i3 * p23
            + 2.0 * cof[i] * p13;
    }
    if !decoupled {
        for (k, &(i, j)) in PAIRS_3D.iter().enumerate() {
            let sk = s[k];
            let aij = sk * p3
                + p11
                + 4.0 * s[i] * s[j] * p22
                + sk * i3 * p33
                + 2.0 * (i1 - sk) * p12
                + 2.0 * sk * (i2 - sk * sk) * p23
                + sk * (i1 - sk) * p13;
            a[i][j] = aij;
            a[j][i] = aij;
        }
    }
    let mut twist = [0.0; 3];
    let mut flip = [0.0; 3];
    for (k, &(i, j)) in PAIRS_3D.iter().enumerate() {
        let base = 2.0 * p2 + s[k] * p3;
        let sym_limit = 0.5 * (a[i][i] + a[j][j]) + a[i][j];
        twist[k] = twist_inv(s[i], s[j], p1, base, sym_limit, rules[k]);
        flip[k] = 2.0 * p2 - s[k] * p3;
    }
    (grad, a, twist, flip)
}
