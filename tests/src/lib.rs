//! # ecc-tests: cross-crate tests
//!
//! The tests in `tests/` check generated code (from `ecc-energies` and from
//! the `energy!` macro) against central differences, nalgebra's symmetric
//! eigensolver, the hand-written runtime energies and the paper's closed
//! forms; the `energy!` macro in both forms; and compile-fail cases
//! (`ui/*.rs`, via trybuild). This library holds the shared helpers:
//!
//! * [`cases`]: the hard cases (rest, uniform scale, repeated σ, σ differing
//!   by 1e-9, σi + σj ≈ 0, σ = 1e-6, inverted, σ = 1e3) under random
//!   rotations, and random F;
//! * [`fcheck`]: F-space checks of one energy at one F (gradient and raw
//!   Hessian vs central differences, eigenpairs vs `SymmetricEigen`,
//!   filtered Hessians finite/symmetric/PSD and equal to the numeric
//!   projection);
//! * [`library`]: the standard library's generated types with their sources;
//! * [`dd`] and [`real`]: double-double arithmetic and a small real-number
//!   trait over f32, f64 and it, the number types of the independent
//!   high-precision references (here and in `ecc-benches`).

// The one hard-case table, shared with the runtime's own tests and `ecc check`.
pub use ecc_runtime::reference::cases;
pub mod dd;
pub mod fcheck;
pub mod library;
pub mod real;

/// |a − b| ≤ tol · max(1, |a|, |b|), with equal non-finite values (same
/// infinity, or both NaN) accepted.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    if !a.is_finite() || !b.is_finite() {
        return a == b || (a.is_nan() && b.is_nan());
    }
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}
