//! Loading `.psi` files (or source text) into boxed energies, without rebuilding.

use std::path::Path;

use ecc_dsl::Module;
use ecc_runtime::{Energy, ParamError};

use crate::energy::InterpEnergy;
use crate::error::LoadError;

/// Compile `source` (named `file_name` in diagnostics and in the energy's
/// name) for dimension `D` and apply the parameter overrides `params`
/// (unknown names and non-finite values are errors).
pub fn load_source<const D: usize>(
    source: &str,
    file_name: &str,
    params: &[(String, f64)],
) -> Result<InterpEnergy<D>, LoadError> {
    let loaded = ecc_dsl::load_text(source, file_name)?;
    energy_from_module(&loaded.module, file_name, params)
}

/// Read and compile the `.psi` file at `path` for dimension `D`
/// ([`ecc_dsl::load_file`], then [`energy_from_module`]); the energy is
/// named after the file stem.
pub fn load_psi<const D: usize>(
    path: impl AsRef<Path>,
    params: &[(String, f64)],
) -> Result<Box<dyn Energy<D>>, LoadError> {
    let loaded = ecc_dsl::load_file(path)?;
    Ok(Box::new(energy_from_module::<D>(
        &loaded.module,
        &loaded.shown,
        params,
    )?))
}

/// The energy name for a file: its stem (`energies/psi/snh.psi` → `snh`).
pub use ecc_dsl::energy_name;

/// Compile source text as the energy `name` with every diagnostic rendered
/// against `file_name` ([`ecc_dsl::load::compile_text`]).
pub fn compile_module(source: &str, file_name: &str, name: &str) -> Result<Module, LoadError> {
    Ok(ecc_dsl::load::compile_text(source, file_name, name)?)
}

/// The loader's errors keep their shape in [`LoadError`] (the OS message of
/// an unreadable file, the rendered diagnostics).
impl From<ecc_dsl::LoadError> for LoadError {
    fn from(e: ecc_dsl::LoadError) -> Self {
        match e {
            ecc_dsl::LoadError::Io { path, source } => LoadError::Io {
                path,
                message: source.to_string(),
            },
            ecc_dsl::LoadError::Syntax { path, rendered } => LoadError::Syntax { path, rendered },
        }
    }
}

/// Parameter values for `module`: its defaults with `overrides` applied.
pub fn param_values(module: &Module, overrides: &[(String, f64)]) -> Result<Vec<f64>, ParamError> {
    let mut values = module.param_defaults();
    for (name, value) in overrides {
        let Some(k) = module.params.iter().position(|p| &p.name == name) else {
            return Err(ParamError::Unknown {
                name: name.clone(),
                known: module.params.iter().map(|p| p.name.clone()).collect(),
            });
        };
        if !value.is_finite() {
            return Err(ParamError::NotFinite {
                name: name.clone(),
                value: *value,
            });
        }
        values[k] = *value;
    }
    Ok(values)
}

/// The `D`-dimensional energy of a compiled module with parameter overrides.
/// A module with a fibre part (`fiber a`) is refused
/// ([`LoadError::FibrePart`]): this is the whole energy only when it is
/// isotropic. [`iso_part_from_module`] is the explicit isotropic part.
pub fn energy_from_module<const D: usize>(
    module: &Module,
    file_name: &str,
    params: &[(String, f64)],
) -> Result<InterpEnergy<D>, LoadError> {
    if let Some(f) = module.dims.iter().find_map(|d| d.fibre.as_ref()) {
        return Err(LoadError::FibrePart {
            path: file_name.to_string(),
            direction: f.direction.clone(),
        });
    }
    iso_part_from_module(module, file_name, params)
}

/// The isotropic part Ψ_iso of a compiled module (the whole energy when it
/// declares no `fiber`); pair it with [`crate::fibre_from_module`] for ψ(I4, I5).
pub fn iso_part_from_module<const D: usize>(
    module: &Module,
    file_name: &str,
    params: &[(String, f64)],
) -> Result<InterpEnergy<D>, LoadError> {
    let values = param_values(module, params).map_err(|source| LoadError::Param {
        path: file_name.to_string(),
        source,
    })?;
    let Some(ir) = u8::try_from(D).ok().and_then(|d| module.dim(d)) else {
        let reason = module
            .skipped
            .iter()
            .find(|(d, _)| usize::from(*d) == D)
            .map(|(_, why)| why.clone())
            .unwrap_or_else(|| {
                let dims: Vec<String> = module.dims.iter().map(|d| format!("{}D", d.dim)).collect();
                format!("it compiles only for {}", dims.join(" and "))
            });
        return Err(LoadError::NoSuchDim {
            path: file_name.to_string(),
            dim: D,
            reason,
        });
    };
    InterpEnergy::new(&module.name, ir, &values).map_err(|source| LoadError::Build {
        path: file_name.to_string(),
        source,
    })
}
