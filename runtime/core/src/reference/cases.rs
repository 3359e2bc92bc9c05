//! Hard cases, rotations and random deformation gradients (seeded), behind
//! the `cases` feature (it adds `rand`; the runtime itself needs nalgebra only).
//!
//! One home for the runtime's own tests, the cross-crate tests
//! (`ecc_tests::cases` re-exports this module) and every other checker:
//! named signed singular values σ that break naive formulas (repeated and
//! nearly repeated σ, σi + σj ≈ 0, tiny σ, inversion, huge stretch), turned
//! into F = U diag(σ) Vᵀ by [`compose`] with seeded rotations.

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

/// One named hard case: σ in 3D and/or 2D (`None` where it has no analogue).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Entry {
    /// Unique name.
    pub name: &'static str,
    /// σ in 3D.
    pub sigma3: Option<[f64; 3]>,
    /// σ in 2D.
    pub sigma2: Option<[f64; 2]>,
}

const fn e(name: &'static str, sigma3: Option<[f64; 3]>, sigma2: Option<[f64; 2]>) -> Entry {
    Entry {
        name,
        sigma3,
        sigma2,
    }
}

/// The one table: every hard case any checker visits (the union of what the
/// runtime's tests, `ecc check` and the benchmarks' accuracy study used).
/// Checkers pick a named subset ([`TESTS`], [`CHECK`], the benchmarks' `CLASSES`); σ need not be in
/// the signed SVD's order (F = U diag(σ) Vᵀ is composed as written).
pub const TABLE: &[Entry] = &[
    e("rest", Some([1.0, 1.0, 1.0]), Some([1.0, 1.0])),
    e("uniform scale up", Some([1.7, 1.7, 1.7]), Some([1.7, 1.7])),
    e(
        "uniform scale down",
        Some([0.45, 0.45, 0.45]),
        Some([0.45, 0.45]),
    ),
    e("repeated pair", Some([1.6, 0.7, 0.7]), None),
    e("repeated top pair", Some([1.3, 1.3, 0.6]), None),
    e("repeated top 0.8", Some([1.3, 1.3, 0.8]), Some([1.3, 1.3])),
    e(
        "near-repeated 1e-9",
        Some([1.4, 1.4 * (1.0 - 1e-9), 0.8]),
        Some([1.4, 1.4 * (1.0 - 1e-9)]),
    ),
    e(
        "near-repeated 1e-9 low",
        Some([1.4, 0.8, 0.8 * (1.0 - 1e-9)]),
        None,
    ),
    e(
        "1e-9 apart",
        Some([1.3, 1.3 + 1e-9, 0.8]),
        Some([1.3, 1.3 + 1e-9]),
    ),
    e(
        "antipodal 1e-9",
        Some([1.2, 0.9, -0.9 * (1.0 - 1e-9)]),
        Some([0.9, -0.9 * (1.0 - 1e-9)]),
    ),
    e(
        "antipodal +1e-9",
        Some([1.2, 0.7, -0.7 + 1e-9]),
        Some([0.7, -0.7 + 1e-9]),
    ),
    e("antipodal exact", Some([1.2, 0.9, -0.9]), Some([0.9, -0.9])),
    e("sigma 1e-6", Some([1.1, 0.8, 1e-6]), Some([1.1, 1e-6])),
    e(
        "sigma 1e-6 near 1",
        Some([1.0, 0.9, 1e-6]),
        Some([1.0, 1e-6]),
    ),
    e("inverted", Some([1.3, 0.9, -0.6]), Some([1.3, -0.6])),
    e("inverted 0.8", Some([1.2, 0.9, -0.8]), Some([1.2, -0.8])),
    e("inverted all equal", Some([0.8, 0.8, -0.8]), None),
    e("large stretch", Some([1e3, 1.2, 0.9]), Some([1e3, 0.9])),
    e("large stretch 2", Some([1e3, 2.0, 0.5]), Some([1e3, 0.5])),
    e("generic", Some([1.9, 1.1, 0.35]), Some([1.9, 0.35])),
    e("uniform scale 1.3", Some([1.3, 1.3, 1.3]), Some([1.3, 1.3])),
    e("repeated low 0.8", Some([1.5, 0.8, 0.8]), Some([0.8, 0.8])),
    e(
        "1e-9 gap at 1.1",
        Some([1.1 + 1e-9, 1.1, 0.8]),
        Some([1.1 + 1e-9, 1.1]),
    ),
    e(
        "antipodal +1e-7",
        Some([1.2, 0.7, -0.7 + 1e-7]),
        Some([0.7, -0.7 + 1e-7]),
    ),
    e("sigma 1e-6 at 1", Some([1.0, 1.0, 1e-6]), Some([1.0, 1e-6])),
];

/// The cases the runtime's and the cross-crate tests visit.
pub const TESTS: &[&str] = &[
    "rest",
    "uniform scale up",
    "uniform scale down",
    "repeated pair",
    "repeated top pair",
    "near-repeated 1e-9",
    "near-repeated 1e-9 low",
    "antipodal 1e-9",
    "antipodal exact",
    "sigma 1e-6",
    "inverted",
    "inverted all equal",
    "large stretch",
    "generic",
];

/// `ecc check`'s rows after "rest" and "rotation": (report label, case).
pub const CHECK: &[(&str, &str)] = &[
    ("uniform scale", "uniform scale up"),
    ("repeated sigma", "repeated top 0.8"),
    ("sigma 1e-9 apart", "1e-9 apart"),
    ("sigma_i+sigma_j~0", "antipodal +1e-9"),
    ("sigma = 1e-6", "sigma 1e-6 near 1"),
    ("inverted", "inverted 0.8"),
    ("sigma = 1e3", "large stretch 2"),
];

/// σ of the case called `name` in dimension `D` (2 or 3), if it has one.
pub fn sigma<const D: usize>(name: &str) -> Option<[f64; D]> {
    let entry = TABLE.iter().find(|c| c.name == name)?;
    let s: &[f64] = match D {
        2 => entry.sigma2.as_ref()?,
        3 => entry.sigma3.as_ref()?,
        _ => return None,
    };
    Some(std::array::from_fn(|i| s[i]))
}

/// The named cases that exist in dimension `D`, with their flags.
pub fn select<const D: usize>(names: &[&'static str]) -> Vec<Case<D>> {
    names
        .iter()
        .filter_map(|&name| {
            let sigma = sigma::<D>(name)?;
            let smax = sigma.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let antipodal =
                (0..D).any(|i| (i + 1..D).any(|j| (sigma[i] + sigma[j]).abs() <= 1e-6 * smax));
            let positive = sigma.iter().all(|&x| x > 0.0);
            Some(c(name, sigma, antipodal, positive))
        })
        .collect()
}

/// The hard cases in 3D ([`TESTS`]).
pub fn hard_cases_3d() -> Vec<Case<3>> {
    select(TESTS)
}

/// The hard cases in 2D ([`TESTS`] that exist in 2D).
pub fn hard_cases_2d() -> Vec<Case<2>> {
    select(TESTS)
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

/// A uniformly random rotation in SO(D) for D = 2 ([`rot2`]) or 3 ([`rot3`]).
pub fn rotation<const D: usize>(r: &mut ChaCha8Rng) -> SMatrix<f64, D, D> {
    if D == 2 {
        let m = rot2(r);
        SMatrix::from_fn(|i, j| m[(i, j)])
    } else {
        let m = rot3(r);
        SMatrix::from_fn(|i, j| m[(i, j)])
    }
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

/// Random D×D F: alternately general (entries in ±1.5, may be inverted) and
/// near the identity.
pub fn random_f<const D: usize>(r: &mut ChaCha8Rng, n: usize) -> Vec<SMatrix<f64, D, D>> {
    (0..n)
        .map(|k| {
            if k % 2 == 0 {
                SMatrix::from_fn(|_, _| r.gen_range(-1.5..1.5))
            } else {
                SMatrix::identity() + SMatrix::from_fn(|_, _| r.gen_range(-0.3..0.3))
            }
        })
        .collect()
}

/// [`random_f`] in 3D.
pub fn random_f3(r: &mut ChaCha8Rng, n: usize) -> Vec<Matrix3<f64>> {
    random_f::<3>(r, n)
}

/// [`random_f`] in 2D.
pub fn random_f2(r: &mut ChaCha8Rng, n: usize) -> Vec<Matrix2<f64>> {
    random_f::<2>(r, n)
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
