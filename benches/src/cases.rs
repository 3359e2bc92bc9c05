//! Deformation gradients for the accuracy study: random F and the hard
//! classes that break naive formulas, each F = U diag(σ) Vᵀ with random
//! rotations U, V (except the first "rest" sample, F = I exactly).
//!
//! | class | σ (3D) | σ (2D) | what it stresses |
//! |---|---|---|---|
//! | random | I + U(−½, ½)⁹, ⅛ inverted | same | typical elements |
//! | rest | (1, 1, 1) | (1, 1) | all flips 0/0 |
//! | uniform scale | (1.3, 1.3, 1.3) | (1.3, 1.3) | repeated σ away from rest |
//! | repeated σ | (1.5, 0.8, 0.8) | (0.8, 0.8) | one repeated pair |
//! | σ gap 1e-9 | (1.1+10⁻⁹, 1.1, 0.8) | (1.1+10⁻⁹, 1.1) | catastrophic cancellation in (Ψi−Ψj)/(σi−σj) |
//! | σi+σj ≈ 0 | (1.2, 0.7, −0.7+10⁻⁷) | (0.7, −0.7+10⁻⁷) | twist denominators (ARAP: a genuine pole) |
//! | σ = 1e-6 | (1, 1, 10⁻⁶) | (1, 10⁻⁶) | near-degenerate, barrier blow-up |
//! | inverted | (1.2, 0.9, −0.8) | (1.2, −0.8) | det F < 0 |
//! | σ = 1e3 | (10³, 2, 0.5) | (10³, 0.5) | large stretch, scale |
//!
//! Barrier energies skip the classes with det F ≤ 0 (Ψ = +∞ there). The σ
//! come from the one hard-case table (`ecc_runtime::reference::cases`); the
//! rotations are drawn here as before (axis–angle), so the recorded report's
//! samples are reproduced exactly.

use ecc_runtime::reference::cases as table;
use nalgebra::{Matrix2, Matrix3, Rotation2, Rotation3, Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A hard-case class: "random", or a named case of the one table
/// (`ecc_runtime::reference::cases::BENCH`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CaseClass {
    /// The report's class name.
    pub name: &'static str,
    /// The table's case ("" for random).
    pub case: &'static str,
    /// det F ≤ 0 somewhere in the class (skipped for barrier energies).
    pub inverted: bool,
    pub random: bool,
}

impl CaseClass {
    /// σ in 3D (zeros for random).
    pub fn sigma3(&self) -> [f64; 3] {
        table::sigma::<3>(self.case).unwrap_or([0.0; 3])
    }

    /// σ in 2D (zeros for random).
    pub fn sigma2(&self) -> [f64; 2] {
        table::sigma::<2>(self.case).unwrap_or([0.0; 2])
    }
}

const fn class(name: &'static str, case: &'static str, inverted: bool) -> CaseClass {
    CaseClass {
        name,
        case,
        inverted,
        random: false,
    }
}

/// All classes, random first (the named ones as in `table::BENCH`).
pub const CLASSES: &[CaseClass] = &[
    CaseClass {
        name: "random",
        case: "",
        inverted: true,
        random: true,
    },
    class("rest", "rest", false),
    class("uniform scale", "uniform scale 1.3", false),
    class("repeated σ", "repeated low 0.8", false),
    class("σ gap 1e-9", "1e-9 gap at 1.1", false),
    class("σi+σj≈0", "antipodal +1e-7", true),
    class("σ=1e-6", "sigma 1e-6 at 1", false),
    class("inverted", "inverted 0.8", true),
    class("σ=1e3", "large stretch 2", false),
];

/// `n` deformation gradients of class `c` in 3D (row-major), seeded by `seed`.
pub fn samples3(c: &CaseClass, n: usize, barrier: bool, seed: u64) -> Vec<[f64; 9]> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    let mut k = 0usize;
    while out.len() < n {
        k += 1;
        let f: Matrix3<f64> = if c.random {
            let mut f = Matrix3::identity() + Matrix3::from_fn(|_, _| r.gen_range(-0.5..0.5));
            if k.is_multiple_of(8) {
                f.column_mut(2).neg_mut();
            }
            f
        } else if k == 1 && !c.inverted && c.sigma3() == [1.0; 3] {
            Matrix3::identity()
        } else {
            let rot = |r: &mut ChaCha8Rng| {
                let axis = Vector3::new(
                    r.gen_range(-1.0..1.0),
                    r.gen_range(-1.0..1.0),
                    r.gen_range(-1.0..1.0),
                );
                Rotation3::from_axis_angle(
                    &Unit::new_normalize(axis),
                    r.gen_range(0.0..std::f64::consts::TAU),
                )
            };
            let (u, v) = (rot(&mut r), rot(&mut r));
            u.matrix() * Matrix3::from_diagonal(&Vector3::from(c.sigma3())) * v.matrix().transpose()
        };
        if barrier && f.determinant() <= 0.0 {
            continue;
        }
        out.push(std::array::from_fn(|i| f[(i / 3, i % 3)]));
    }
    out
}

/// `n` deformation gradients of class `c` in 2D (row-major).
pub fn samples2(c: &CaseClass, n: usize, barrier: bool, seed: u64) -> Vec<[f64; 4]> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    let mut k = 0usize;
    while out.len() < n {
        k += 1;
        let f: Matrix2<f64> = if c.random {
            let mut f = Matrix2::identity() + Matrix2::from_fn(|_, _| r.gen_range(-0.5..0.5));
            if k.is_multiple_of(8) {
                f.column_mut(1).neg_mut();
            }
            f
        } else if k == 1 && c.sigma2() == [1.0; 2] {
            Matrix2::identity()
        } else {
            let u = Rotation2::new(r.gen_range(0.0..std::f64::consts::TAU));
            let v = Rotation2::new(r.gen_range(0.0..std::f64::consts::TAU));
            u.matrix()
                * Matrix2::new(c.sigma2()[0], 0.0, 0.0, c.sigma2()[1])
                * v.matrix().transpose()
        };
        if barrier && f.determinant() <= 0.0 {
            continue;
        }
        out.push(std::array::from_fn(|i| f[(i / 2, i % 2)]));
    }
    out
}

/// The fixed rest triangle: Dm = [[1, ½], [0, 1]], Dm⁻¹ exact in binary.
pub const REST_TRI: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]];
/// The fixed rest tetrahedron: Dm upper triangular with dyadic entries, Dm⁻¹ exact.
pub const REST_TET: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.5, 1.0, 0.0],
    [0.25, 0.5, 2.0],
];

/// Deformed nodes x_n = F p_n of the rest element `p` (d-dim, row-major F).
pub fn deform<const D: usize, const K: usize>(f: &[f64], p: &[[f64; D]; K]) -> [[f64; D]; K] {
    std::array::from_fn(|n| std::array::from_fn(|i| (0..D).map(|j| f[i * D + j] * p[n][j]).sum()))
}
