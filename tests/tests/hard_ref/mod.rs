//! An independent high-precision reference for Ψ(F), its gradient and its
//! Hessian: double-double arithmetic ([`dd`], from the
//! `ecc-tests` library), a double-double one-sided
//! Jacobi SVD ([`svd`]), Ψ(σ) evaluated from the CAS graph of the `.psi`
//! source in double-double ([`graph`]) and fourth-order central
//! differences of Ψ(F) in double-double ([`fd`]). Shared by the `hard_*`
//! test files (`mod hard_ref;`).
#![allow(dead_code)]

pub mod check;
pub use ecc_tests::dd;
pub mod energies;
pub mod fd;
pub mod graph;
pub mod svd;
