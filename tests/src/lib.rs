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
/// The one F-space checker (`ecc_runtime::reference::check`).
pub use ecc_runtime::reference::check as fcheck;
pub mod library;
pub mod real;

pub use ecc_runtime::reference::check::close;
