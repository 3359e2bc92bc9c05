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
    let name = energy_name(file_name);
    let module = compile_module(source, file_name, &name)?;
    energy_from_module(&module, file_name, params)
}

/// Read and compile the `.psi` file at `path` for dimension `D` (see
/// [`load_source`]); the energy is named after the file stem.
pub fn load_psi<const D: usize>(
    path: impl AsRef<Path>,
    params: &[(String, f64)],
) -> Result<Box<dyn Energy<D>>, LoadError> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let source = read_source(path)?;
    Ok(Box::new(load_source::<D>(&source, &shown, params)?))
}

/// Read a `.psi` file as UTF-8 text.
pub fn read_source(path: &Path) -> Result<String, LoadError> {
    std::fs::read_to_string(path).map_err(|e| LoadError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The energy name for a file: its stem (`energies/psi/snh.psi` → `snh`).
pub fn energy_name(file_name: &str) -> String {
    Path::new(file_name)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("energy")
        .to_string()
}

/// Compile source text with every diagnostic rendered against `file_name`.
pub fn compile_module(source: &str, file_name: &str, name: &str) -> Result<Module, LoadError> {
    ecc_dsl::compile(source, name).map_err(|d| LoadError::Syntax {
        path: file_name.to_string(),
        rendered: d.render(file_name, source),
    })
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
pub fn energy_from_module<const D: usize>(
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
