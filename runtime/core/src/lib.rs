//! # ecc-runtime: the eigensystem core
//!
//! Everything generated code plugs into. An isotropic energy density Ψ(F) depends
//! on F only through its *signed* singular values σ (F = U diag(σ) Vᵀ with
//! U, V ∈ SO(d); the reflection, if any, is moved into the smallest σ).
//! An energy therefore describes itself in stretch space ([`Energy`] →
//! [`Spectral`]), and this crate lifts that description back to F-space
//! (gradient, raw and PSD-filtered Hessian, eigenpairs) and to element
//! (x-space) Hessians.
//!
//! The maths, with d = 2 or 3 and column-major `vec` (Smith et al. 2019, eq. 1):
//!
//! * gradient: ∂Ψ/∂F = U diag(∂Ψ/∂σ) Vᵀ;
//! * Hessian: ∂²Ψ/∂f² = Σ_ij A_ij d_i d_jᵀ + Σ_pairs λ_twist t tᵀ + λ_flip l lᵀ,
//!   with scaling modes d_i = vec(U e_i e_iᵀ Vᵀ), A = ∂²Ψ/∂σ² (Smith App. D,
//!   Zhu §4), and for each pair (i, j) the twist t = vec(U (e_j e_iᵀ − e_i e_jᵀ) Vᵀ)/√2
//!   and flip l = vec(U (e_j e_iᵀ + e_i e_jᵀ) Vᵀ)/√2 with eigenvalues
//!   λ_twist = (Ψ_i + Ψ_j)/(σ_i + σ_j) and λ_flip = (Ψ_i − Ψ_j)/(σ_i − σ_j)
//!   (Zhu eq. 28; Smith eqs. 22–23 in invariant form).
//!
//! Crate-level dependencies are deliberately tiny (nalgebra only): this crate
//! never depends on the compiler crates (`ecc-dsl`, `ecc-codegen`).

// Index loops mirror the maths (u_a[r]·w_b[n], pair slots) more clearly than iterators.
#![allow(clippy::needless_range_loop)]

mod assemble;
pub mod divided;
pub mod element;
pub mod energies;
pub mod energy;
pub mod filter;
pub mod invariants;
mod modes;
pub mod point;
pub mod reference;
pub mod spectral;
pub mod stretch;
pub mod svd;
pub mod sym;

pub use element::{
    ElementEval, RestError, TetRest, TriRest, tet_eval, tet_f, tet_psi, tri_eval, tri_f, tri_psi,
};
pub use energy::{Energy, EnergyInfo, ParamError};
pub use filter::Filter;
pub use invariants::spectral_from_invariants;
pub use point::{eigen_f2, eigen_f3, gradient_f2, gradient_f3, hessian_f2, hessian_f3};
pub use spectral::{PAIRS_2D, PAIRS_3D, ScaleBlock, Spectral, pair_indices};
pub use stretch::spectral_from_stretch;
pub use svd::{Svd, signed_svd, signed_svd2, signed_svd3};
