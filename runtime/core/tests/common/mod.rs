//! Shared test helpers: seeded randomness, hard cases, test-only energies.
#![allow(dead_code)]

pub mod energies;
pub mod fibre_energies;

pub use ecc_runtime::reference::cases::*;

use nalgebra::{DMatrix, SMatrix, Vector3};

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
