//! Hard cases, rotations and random deformation gradients (seeded).
//!
//! One file for two crates: the runtime's own tests (`mod common`) and the
//! cross-crate tests' library (`ecc_tests::cases`, included by path), so
//! both check the same hard cases without the runtime depending on the
//! compiler crates.

use nalgebra::{Matrix2, Matrix3, SMatrix, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A seeded generator.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A named signed singular value vector.
#[derive(Clone, Copy, Debug)]
pub struct Case<const D: usize> {
    /// What the case is.
    pub name: &'static str,
    /// σ, ordered as the signed SVD returns it.
    pub sigma: [f64; D],
    /// Some pair has σi + σj ≈ 0: a genuine pole for energies that are not
    /// sign-symmetric (central differences are meaningless across it).
    pub antipodal: bool,
    /// Every σ > 0 (inside log-type energies' domain).
    pub positive: bool,
}

const fn c<const D: usize>(
    name: &'static str,
    sigma: [f64; D],
    antipodal: bool,
    positive: bool,
) -> Case<D> {
    Case {
        name,
        sigma,
        antipodal,
        positive,
    }
}

/// The hard cases in 3D.
pub fn hard_cases_3d() -> Vec<Case<3>> {
    vec![
        c("rest", [1.0, 1.0, 1.0], false, true),
        c("uniform scale up", [1.7, 1.7, 1.7], false, true),
        c("uniform scale down", [0.45, 0.45, 0.45], false, true),
        c("repeated pair", [1.6, 0.7, 0.7], false, true),
        c("repeated top pair", [1.3, 1.3, 0.6], false, true),
        c(
            "near-repeated 1e-9",
            [1.4, 1.4 * (1.0 - 1e-9), 0.8],
            false,
            true,
        ),
        c(
            "near-repeated 1e-9 low",
            [1.4, 0.8, 0.8 * (1.0 - 1e-9)],
            false,
            true,
        ),
        c(
            "antipodal 1e-9",
            [1.2, 0.9, -0.9 * (1.0 - 1e-9)],
            true,
            false,
        ),
        c("antipodal exact", [1.2, 0.9, -0.9], true, false),
        c("sigma 1e-6", [1.1, 0.8, 1e-6], false, true),
        c("inverted", [1.3, 0.9, -0.6], false, false),
        c("inverted all equal", [0.8, 0.8, -0.8], true, false),
        c("large stretch", [1e3, 1.2, 0.9], false, true),
        c("generic", [1.9, 1.1, 0.35], false, true),
    ]
}

/// The hard cases in 2D.
pub fn hard_cases_2d() -> Vec<Case<2>> {
    vec![
        c("rest", [1.0, 1.0], false, true),
        c("uniform scale up", [1.7, 1.7], false, true),
        c("uniform scale down", [0.45, 0.45], false, true),
        c("near-repeated 1e-9", [1.4, 1.4 * (1.0 - 1e-9)], false, true),
        c("antipodal 1e-9", [0.9, -0.9 * (1.0 - 1e-9)], true, false),
        c("antipodal exact", [0.9, -0.9], true, false),
        c("sigma 1e-6", [1.1, 1e-6], false, true),
        c("inverted", [1.3, -0.6], false, false),
        c("large stretch", [1e3, 0.9], false, true),
        c("generic", [1.9, 0.35], false, true),
    ]
}

/// A uniformly random rotation in SO(3).
pub fn rot3(r: &mut ChaCha8Rng) -> Matrix3<f64> {
    let q = nalgebra::Quaternion::new(
        r.gen_range(-1.0..1.0),
        r.gen_range(-1.0..1.0),
        r.gen_range(-1.0..1.0),
        r.gen_range(-1.0..1.0),
    );
    if q.norm() < 1e-3 {
        return Matrix3::identity();
    }
    UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .into_inner()
}

/// A uniformly random rotation in SO(2).
pub fn rot2(r: &mut ChaCha8Rng) -> Matrix2<f64> {
    let a: f64 = r.gen_range(-std::f64::consts::PI..std::f64::consts::PI);
    Matrix2::new(a.cos(), -a.sin(), a.sin(), a.cos())
}

/// F = U diag(σ) Vᵀ.
pub fn compose<const D: usize>(
    u: &SMatrix<f64, D, D>,
    sigma: &[f64; D],
    v: &SMatrix<f64, D, D>,
) -> SMatrix<f64, D, D> {
    let s = SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { sigma[i] } else { 0.0 });
    u * s * v.transpose()
}

/// (U, V) pairs: the identity first, then `n` random rotation pairs.
pub fn rotations3(r: &mut ChaCha8Rng, n: usize) -> Vec<(Matrix3<f64>, Matrix3<f64>)> {
    let mut out = vec![(Matrix3::identity(), Matrix3::identity())];
    out.extend((0..n).map(|_| (rot3(r), rot3(r))));
    out
}

/// (U, V) pairs in 2D: the identity first, then `n` random rotation pairs.
pub fn rotations2(r: &mut ChaCha8Rng, n: usize) -> Vec<(Matrix2<f64>, Matrix2<f64>)> {
    let mut out = vec![(Matrix2::identity(), Matrix2::identity())];
    out.extend((0..n).map(|_| (rot2(r), rot2(r))));
    out
}

/// Random 3×3 F: alternately general (entries in ±1.5, may be inverted) and
/// near the identity.
pub fn random_f3(r: &mut ChaCha8Rng, n: usize) -> Vec<Matrix3<f64>> {
    (0..n)
        .map(|k| {
            if k % 2 == 0 {
                Matrix3::from_fn(|_, _| r.gen_range(-1.5..1.5))
            } else {
                Matrix3::identity() + Matrix3::from_fn(|_, _| r.gen_range(-0.3..0.3))
            }
        })
        .collect()
}

/// Random 2×2 F (as [`random_f3`]).
pub fn random_f2(r: &mut ChaCha8Rng, n: usize) -> Vec<Matrix2<f64>> {
    (0..n)
        .map(|k| {
            if k % 2 == 0 {
                Matrix2::from_fn(|_, _| r.gen_range(-1.5..1.5))
            } else {
                Matrix2::identity() + Matrix2::from_fn(|_, _| r.gen_range(-0.3..0.3))
            }
        })
        .collect()
}

/// Random signed singular values in the runtime's order (|σ0| ≥ |σ1| ≥ |σ2|,
/// only the last may be negative), magnitudes in [0.2, 2.5].
pub fn random_sigma<const D: usize>(r: &mut ChaCha8Rng) -> [f64; D] {
    let mut s: [f64; D] = std::array::from_fn(|_| r.gen_range(0.2..2.5));
    s.sort_by(|a, b| b.total_cmp(a));
    if r.gen_bool(0.25) {
        s[D - 1] = -s[D - 1];
    }
    s
}
