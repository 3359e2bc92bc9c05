//! # The C++ back end: one self-contained C++17 header per energy
//!
//! Printed from the *same* plan as the Rust back end (`crate::plan::Plan`:
//! folded constants, shared subexpressions with readable names, lazily
//! evaluated guarded branches), so both languages compute the same
//! expressions in the same order. Only the syntax differs:
//! `expr` prints the plan's expressions, `energy` the struct.
//!
//! The emitted header defines, in `namespace ecc::energies`, one struct whose
//! public `double` members are the parameters (with the file's defaults) and
//! which has, for every compiled dimension D:
//!
//! * `psi(σ)`: Ψ, +∞ outside the domain (never NaN);
//! * `spectral(σ)` → `ecc::Spectral<D>`: Ψ, ∂Ψ/∂σ, the scaling block
//!   (flagged diagonal where the CAS proved it decoupled: no eigensolve) and
//!   the twist/flip eigenvalue of each pair slot, with the same limit forms
//!   near σi = ±σj as the Rust code (`ecc::LIMIT_TOL`);
//! * `eval(F, filter)` → `ecc::PointEval<D>`: Ψ, vec(∂Ψ/∂F) and the filtered
//!   d²×d² Hessian; `eval_tri(x, Dm⁻¹, area, filter)` (2D, 6×6) or
//!   `eval_tet(x, Dm⁻¹, volume, filter)` (3D, 12×12): the element versions;
//! * for an energy with `fiber a`, the fibre part ψ(I4, I5) (`fibre`):
//!   `fibre<D>(i4, i5)` → `ecc::FibreDerivs`, `fibre_eval(F, a, filter)` →
//!   `ecc::FibreEval<D>` (ψ, I4, I5, vec(∂ψ/∂F), filtered d²×d² Hessian),
//!   `fibre_eval_tri` / `fibre_eval_tet` and `fibre_psi_f`. As in Rust the
//!   isotropic part (`eval`) and the fibre part are separate terms, each
//!   projected on its own; a solver adds them.
//!
//! The runtime they call ([`CPP_RUNTIME`], `compiler/codegen/cpp/ecc_runtime.hpp`:
//! signed SVD, modes, filters, chain rule, the fibre eigensystems) is written once, not generated.
//! By default it is inlined into the header behind its include guard, so the
//! header is self-contained and several headers can be included together;
//! [`CppRuntime::Include`] emits an `#include` instead.

mod energy;
mod expr;
mod fibre;

use crate::error::CodegenError;

/// The header-only C++ runtime every emitted header uses (see the module docs).
pub const CPP_RUNTIME: &str = include_str!("../../cpp/ecc_runtime.hpp");

/// The optional adapter from Eigen matrices to the runtime's arrays.
pub const CPP_EIGEN_ADAPTER: &str = include_str!("../../cpp/ecc_eigen.hpp");

/// How an emitted header gets the runtime.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub enum CppRuntime {
    /// Paste [`CPP_RUNTIME`] into the header (self-contained; the default).
    #[default]
    Inline,
    /// `#include "<path>"` (e.g. `ecc_runtime.hpp` written next to the header).
    Include(String),
}

/// What to emit and how to name it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CppOptions {
    /// Name of the struct (a C++ identifier, e.g. `Snh`).
    pub type_name: String,
    /// The energy's name (`name` member); `None` uses the module's name.
    pub energy_name: Option<String>,
    /// Where the runtime comes from.
    pub runtime: CppRuntime,
}

impl CppOptions {
    /// Options with the struct named `type_name` and the runtime inlined.
    pub fn named(type_name: impl Into<String>) -> Self {
        CppOptions {
            type_name: type_name.into(),
            energy_name: None,
            runtime: CppRuntime::Inline,
        }
    }
}

/// The C++17 header of `module` (see the module docs). Pure: no I/O.
pub fn generate_cpp(module: &ecc_dsl::Module, opts: &CppOptions) -> Result<String, CodegenError> {
    energy::header(module, opts)
}
