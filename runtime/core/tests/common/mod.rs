//! Shared test helpers: seeded randomness, hard cases, test-only energies.
#![allow(dead_code)]

pub mod energies;

use nalgebra::{DMatrix, Matrix2, Matrix3, SMatrix, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
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

/// A named set of signed singular values.
#[derive(Clone, Copy, Debug)]
pub struct Case<const D: usize> {
    pub name: &'static str,
    pub sigma: [f64; D],
    /// Some pair has σ_i + σ_j ≈ 0 (a genuine pole for non-sign-symmetric energies).
    pub antipodal: bool,
    /// Some σ ≤ 0 or tiny (outside log-type energies' comfortable domain).
    pub positive: bool,
}

const fn c3(name: &'static str, sigma: [f64; 3], antipodal: bool, positive: bool) -> Case<3> {
    Case {
        name,
        sigma,
        antipodal,
        positive,
    }
}
const fn c2(name: &'static str, sigma: [f64; 2], antipodal: bool, positive: bool) -> Case<2> {
    Case {
        name,
        sigma,
        antipodal,
        positive,
    }
}

/// The hard cases of the brief, 3D.
pub fn hard_cases_3d() -> Vec<Case<3>> {
    vec![
        c3("rest", [1.0, 1.0, 1.0], false, true),
        c3("uniform scale up", [1.7, 1.7, 1.7], false, true),
        c3("uniform scale down", [0.45, 0.45, 0.45], false, true),
        c3("repeated pair", [1.6, 0.7, 0.7], false, true),
        c3("repeated top pair", [1.3, 1.3, 0.6], false, true),
        c3(
            "near-repeated 1e-9",
            [1.4, 1.4 * (1.0 - 1e-9), 0.8],
            false,
            true,
        ),
        c3(
            "near-repeated 1e-9 low",
            [1.4, 0.8, 0.8 * (1.0 - 1e-9)],
            false,
            true,
        ),
        c3(
            "antipodal 1e-9",
            [1.2, 0.9, -0.9 * (1.0 - 1e-9)],
            true,
            false,
        ),
        c3("antipodal exact", [1.2, 0.9, -0.9], true, false),
        c3("sigma 1e-6", [1.1, 0.8, 1e-6], false, true),
        c3("inverted", [1.3, 0.9, -0.6], false, false),
        c3("inverted all equal", [0.8, 0.8, -0.8], true, false),
        c3("large stretch", [1e3, 1.2, 0.9], false, true),
        c3("generic", [1.9, 1.1, 0.35], false, true),
    ]
}

/// The hard cases of the brief, 2D.
pub fn hard_cases_2d() -> Vec<Case<2>> {
    vec![
        c2("rest", [1.0, 1.0], false, true),
        c2("uniform scale up", [1.7, 1.7], false, true),
        c2("uniform scale down", [0.45, 0.45], false, true),
        c2("near-repeated 1e-9", [1.4, 1.4 * (1.0 - 1e-9)], false, true),
        c2("antipodal 1e-9", [0.9, -0.9 * (1.0 - 1e-9)], true, false),
        c2("antipodal exact", [0.9, -0.9], true, false),
        c2("sigma 1e-6", [1.1, 1e-6], false, true),
        c2("inverted", [1.3, -0.6], false, false),
        c2("large stretch", [1e3, 0.9], false, true),
        c2("generic", [1.9, 0.35], false, true),
    ]
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

/// Rotation pairs to apply to each case: identity first, then `n` random ones.
pub fn rotations3(r: &mut ChaCha8Rng, n: usize) -> Vec<(Matrix3<f64>, Matrix3<f64>)> {
    let mut out = vec![(Matrix3::identity(), Matrix3::identity())];
    for _ in 0..n {
        out.push((rot3(r), rot3(r)));
    }
    out
}

pub fn rotations2(r: &mut ChaCha8Rng, n: usize) -> Vec<(Matrix2<f64>, Matrix2<f64>)> {
    let mut out = vec![(Matrix2::identity(), Matrix2::identity())];
    for _ in 0..n {
        out.push((rot2(r), rot2(r)));
    }
    out
}

/// Random matrices: Gaussian-ish entries, plus near-identity ones.
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

/// max |a_ij − b_ij|.
pub fn max_diff<const R: usize, const C: usize>(
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
) -> f64 {
    (a - b).abs().max()
}

/// max |a_ij|, at least `floor`.
pub fn max_abs<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, floor: f64) -> f64 {
    a.abs().max().max(floor)
}

pub fn vec3(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// A dynamic copy (for nalgebra routines that need concrete dimensions).
pub fn dynm<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>) -> DMatrix<f64> {
    DMatrix::from_fn(R, C, |i, j| a[(i, j)])
}
