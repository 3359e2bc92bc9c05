//! Fibre (anisotropic) energy densities ψ(I4, I5).
//!
//! A fibre energy is attached to a unit rest-space direction `a` per element
//! and depends on F only through the fibre invariants
//!
//! * I4 = aᵀ S a, with F = R S the polar decomposition built from the signed
//!   SVD (S = V Σ Vᵀ, R = U Vᵀ), and
//! * I5 = aᵀ Fᵀ F a = ‖F a‖².
//!
//! (Kim, de Goes & Iben 2019, *Anisotropic Elasticity for Inversion-Safety
//! and Element Rehabilitation*, SIGGRAPH; Kim & Eberle, *Dynamic
//! Deformables* course and its HOBAK code.) An energy file may mix an
//! isotropic part Ψ(I1, I2, I3 | σ) with a fibre part ψ(I4, I5)
//! *additively*; the isotropic part implements [`crate::Energy`], the fibre
//! part this trait, and a solver adds the two (each projected to PSD on its
//! own, as HOBAK does).
//!
//! The runtime side ([`frame`], [`point`], [`fibre_f`],
//! [`fibre_element_eval`]) lifts ψ's partials to F-space and element
//! gradients and PSD-filtered Hessians: a closed form when ψ has no I4
//! derivative (eqs. P3–P5 of [`point`]), else the analytic I4 Hessian on its
//! range and the smallest eigensolve that remains (`fibre/reduced.rs`:
//! 7 × 7 for ψ(I4) in 3D, d² × d² for ψ(I4, I5)).
//!
//! **Citations** (checked against the text, not from memory). Of Kim, de
//! Goes & Iben 2019 only §4.1, "The Eigensystem of I5", was available
//! here (as transcribed with its numbering in the I❤LA case-study gallery,
//! `heartdown/CaseStudies/.../Anisotropic`): eq. 5 I5 = tr(C A), eq. 6
//! ∂I5/∂F = 2 F A, eq. 7 ∂²I5/∂f² = 2 [A_ij I] with the unnumbered
//! eigenvalues λ_{0,1,2} = 2‖a‖² (2D: λ_{0,1}) on Q_i = e_i aᵀ and a
//! rank-six null space. Those are cited by number in [`frame`] (eq. F3).
//! The paper's later equation numbers (anisotropic ARAP, the I4 analysis)
//! and *Dynamic Deformables*' section numbers could not be checked here
//! and are not given; the energies and clamped eigenvalues are instead
//! checked against HOBAK's sources (`src/Hyperelastic/Volume/
//! ANISOTROPIC_{ARAP,STVK,FUNG}.cpp`, read for this purpose).
//!
//! This file is the contract between the compiler's back ends (generated
//! code, the interpreter) and the runtime's fibre eigensystems.

use crate::energy::ParamError;

mod dim;
mod element;
pub mod frame;
pub mod point;
mod reduced;

pub use dim::{FibreDim, FibrePoint, fibre_element_eval, fibre_element_psi, fibre_f, unit_fibre};
pub use frame::{invariant4, invariant5};
pub use point::{FibrePath, i5_eigenvalues};

/// ψ and its partial derivatives with respect to (I4, I5) at one point.
///
/// `psi` is `+∞` outside the energy's domain and never NaN; the derivatives
/// are then unspecified (solvers never take a step there).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FibreDerivs {
    /// ψ(I4, I5).
    pub psi: f64,
    /// ∂ψ/∂I4.
    pub d4: f64,
    /// ∂ψ/∂I5.
    pub d5: f64,
    /// ∂²ψ/∂I4².
    pub d44: f64,
    /// ∂²ψ/∂I4∂I5.
    pub d45: f64,
    /// ∂²ψ/∂I5².
    pub d55: f64,
}

/// Which fibre invariants ψ depends on. Decided by the compiler (or by hand
/// for hand-written energies); lets the runtime pick a closed-form
/// eigensystem (I5 alone, I4 alone) or fall back to the smallest numeric
/// eigensolve (both).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FibreUse {
    /// ψ is constant in both (no fibre term).
    None,
    /// ψ depends on I4 only.
    I4,
    /// ψ depends on I5 only.
    I5,
    /// ψ depends on I4 and I5.
    Both,
}

/// A fibre energy density ψ(I4, I5) in dimension `D` (2 or 3).
pub trait FibreEnergy<const D: usize>: Send + Sync {
    /// A short human-readable name.
    fn name(&self) -> &str;

    /// ψ and its partials at (I4, I5).
    fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs;

    /// Which invariants ψ depends on.
    fn uses(&self) -> FibreUse;

    /// ψ alone (a line-search fast path); defaults to `fibre(..).psi`.
    fn fibre_psi(&self, i4: f64, i5: f64) -> f64 {
        self.fibre(i4, i5).psi
    }

    /// The energy's parameters and their current values.
    fn fibre_params(&self) -> Vec<(String, f64)> {
        Vec::new()
    }

    /// Set a parameter by name.
    fn set_fibre_param(&mut self, name: &str, _value: f64) -> Result<(), ParamError> {
        Err(ParamError::Unknown {
            name: name.to_string(),
            known: self.fibre_params().into_iter().map(|(n, _)| n).collect(),
        })
    }
}
