//! Hand-written reference energies in their specialised closed forms.
//!
//! They are the correctness references and the speed baselines for the
//! generated code: each returns its [`Spectral`](crate::Spectral) directly
//! from the paper's eigenvalue formulas (no invariant-path detour).
//!
//! | energy | Ψ(σ) | notes |
//! |---|---|---|
//! | [`Arap`] | Σ(σ_i − 1)² = I2 − 2I1 + d | Smith et al. 2019 eqs. 28–30; twist pole at σ_i + σ_j = 0 |
//! | [`SymmetricDirichlet`] | ½ Σ(σ_i² + σ_i⁻²) = ½(‖F‖² + ‖F⁻¹‖²) | eqs. 31–35; barrier, +∞ at det F = 0 |
//! | [`FibreArap`], [`FibreStvk`], [`FibreFung`] | fibre energies ψ(I4, I5) | see [`crate::fibre`]; [`fibre_by_name`] |
//! | [`StableNeoHookean`] | μ/2 (I2 − d) + λ/2 (J − α)² − μ/2 log(I2 + 1) | Smith et al. 2018, α = 1 + μ/λ − μ/((d+1)λ) |

mod arap;
mod fibre;
mod sd;
mod snh;

pub use arap::Arap;
pub use fibre::{FIBRE_NAMES, FibreArap, FibreFung, FibreStvk, fibre_by_name};
pub use sd::SymmetricDirichlet;
pub use snh::StableNeoHookean;

use crate::energy::ParamError;

/// The standard `set_param` failure for an unknown name or a non-finite value.
pub(crate) fn param_error(name: &str, value: f64, known: &[&str]) -> ParamError {
    if !value.is_finite() {
        ParamError::NotFinite {
            name: name.to_string(),
            value,
        }
    } else {
        ParamError::Unknown {
            name: name.to_string(),
            known: known.iter().map(|s| s.to_string()).collect(),
        }
    }
}
