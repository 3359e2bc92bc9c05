//! Both parts of a `.psi` file, Ψ = Ψ_iso + ψ(I4, I5), for the callers that
//! place each part where it belongs (scenes: Ψ_iso is the body's energy, ψ
//! the `[fibers]` term). No part is ever dropped: [`load_parts`] returns
//! both, and [`load_fibre_part`] refuses a file whose Ψ_iso is not 0.

use std::path::Path;

use ecc_dsl::Module;
use num_traits::Zero;

use crate::energy::InterpEnergy;
use crate::error::LoadError;
use crate::fibre::{InterpFibre, fibre_from_module};
use crate::load::iso_part_from_module;

/// The two parts of one `.psi` energy in dimension `D`, sharing its parameters.
#[derive(Clone, Debug)]
pub struct PsiParts<const D: usize> {
    /// Ψ_iso (the whole energy when the file declares no `fiber`).
    pub iso: InterpEnergy<D>,
    /// ψ(I4, I5), present exactly when the file declares `fiber a`.
    pub fibre: Option<InterpFibre<D>>,
}

/// Whether the isotropic part Ψ_iso of `module` in dimension `dim` is
/// identically 0 (the CAS folded it to the number 0: a pure fibre energy
/// such as `energies/psi/fibre_stvk.psi`). `false` for a missing dimension.
pub fn iso_part_is_zero(module: &Module, dim: usize) -> bool {
    u8::try_from(dim)
        .ok()
        .and_then(|d| module.dim(d))
        .is_some_and(|ir| ir.graph.as_num(ir.psi).is_some_and(|r| r.is_zero()))
}

/// Read and compile the `.psi` file at `path` for dimension `D` and build
/// both of its parts with the parameter overrides `params` (shared by the
/// parts, as in the file). Errors as [`crate::load_psi`]'s, except that a
/// `fiber` declaration is not one.
pub fn load_parts<const D: usize>(
    path: impl AsRef<Path>,
    params: &[(String, f64)],
) -> Result<PsiParts<D>, LoadError> {
    let loaded = ecc_dsl::load_file(path)?;
    Ok(PsiParts {
        iso: iso_part_from_module::<D>(&loaded.module, &loaded.shown, params)?,
        fibre: fibre_from_module::<D>(&loaded.module, &loaded.shown, params)?,
    })
}

/// The fibre part ψ(I4, I5) of the `.psi` file at `path` as a fibre energy
/// on its own (a scene's `[fibers] energy = "x.psi"`), with the parameter
/// overrides `params`. Refused: a file without `fiber`
/// ([`LoadError::NoFibrePart`]) and one whose Ψ_iso is not identically 0
/// ([`LoadError::IsoBesideFibre`]: taking ψ alone would drop Ψ_iso).
pub fn load_fibre_part<const D: usize>(
    path: impl AsRef<Path>,
    params: &[(String, f64)],
) -> Result<InterpFibre<D>, LoadError> {
    let loaded = ecc_dsl::load_file(path)?;
    let (module, shown) = (&loaded.module, &loaded.shown);
    let fibre =
        fibre_from_module::<D>(module, shown, params)?.ok_or_else(|| LoadError::NoFibrePart {
            path: shown.clone(),
            dim: D,
        })?;
    if !iso_part_is_zero(module, D) {
        return Err(LoadError::IsoBesideFibre {
            path: shown.clone(),
            direction: module
                .dims
                .iter()
                .find_map(|d| d.fibre.as_ref())
                .map(|f| f.direction.clone())
                .unwrap_or_default(),
        });
    }
    Ok(fibre)
}
