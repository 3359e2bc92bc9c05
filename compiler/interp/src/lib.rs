//! # ecc-interp: run-time evaluation of a compiled energy
//!
//! Turns an energy written in the `.psi` language into an
//! [`ecc_runtime::Energy`] *without generating or compiling Rust code*: the
//! CAS graph of the compiled [`ecc_dsl::DimIr`] is lowered once into a flat
//! register [`Tape`] (integer powers as multiplications, parameter-only
//! subexpressions hoisted into a prelude, no allocation per evaluation), and
//! each point feeds the tape's generic derivatives into the runtime's generic
//! formulas:
//!
//! | IR path | tape outputs | runtime formula |
//! |---|---|---|
//! | invariant | Ψ, [Ψ1, Ψ2, Ψ3], [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23] | [`ecc_runtime::spectral_from_invariants`] (Smith et al. 2019) |
//! | stretch | Ψ, ∂Ψ/∂σᵢ, ∂²Ψ/∂σᵢ∂σⱼ | [`ecc_runtime::spectral_from_stretch`] (Zhu 2020) |
//!
//! This is a different route from generated code (which evaluates the
//! CAS-specialised eigenvalue expressions), so the two check each other.
//!
//! ```no_run
//! use ecc_runtime::Energy;
//! let snh = ecc_interp::load_psi::<3>("energies/psi/snh.psi", &[("mu".into(), 2.0)])?;
//! let psi = snh.psi(&[1.1, 0.9, 1.0]);
//! # Ok::<(), ecc_interp::LoadError>(())
//! ```
//!
//! An energy with `fiber a` has a second part ψ(I4, I5)
//! ([`ecc_dsl::FibreIr`]): [`InterpFibre`] implements
//! [`ecc_runtime::FibreEnergy`] for it ([`fibre_from_module`]), while
//! [`InterpEnergy`] is the isotropic part Ψ_iso. [`load_parts`] loads both
//! parts of a file and [`load_fibre_part`] ψ alone (refused when Ψ_iso ≠ 0):
//! the scene providers of the CLI and the Python package use them.
//!
//! Conventions: Ψ = NaN (outside the domain, e.g. log of a negative
//! determinant) is reported as +∞ and [`ecc_runtime::Spectral::infinite`];
//! [`Energy::info`](ecc_runtime::Energy::info) reports the IR's `barrier`
//! flag and `svd_free` (only if Ψ provably reads neither I1 nor σ);
//! `set_param` rejects unknown names and non-finite values with
//! [`ecc_runtime::ParamError`].

mod energy;
mod error;
mod fibre;
mod load;
mod parts;
pub mod tape;

pub use energy::InterpEnergy;
pub use error::{BuildError, LoadError};
pub use fibre::{InterpFibre, fibre_from_module, fibre_use};
pub use load::{
    compile_module, energy_from_module, energy_name, iso_part_from_module, load_psi, load_source,
    param_values,
};
pub use parts::{PsiParts, iso_part_is_zero, load_fibre_part, load_parts};
pub use tape::Tape;
