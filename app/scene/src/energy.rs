//! Where energies come from: an injected provider.
//!
//! ecc-scene lives under `runtime/` and must not depend on the compiler
//! crates, so it asks an [`EnergySource`] for the energy a scene names. The
//! `ecc` CLI provides one over the built-in generated energies and the
//! `.psi` interpreter; [`RuntimeEnergies`] is the small provider over the
//! runtime's hand-written energies (ARAP, symmetric Dirichlet, Stable
//! Neo-Hookean), used by this crate's tests and as a fallback.

use std::path::Path;

use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, ParamError};

/// What a scene asks for.
#[derive(Clone, Copy, Debug)]
pub struct EnergyRequest<'a> {
    /// A built-in energy name (`energy.name`).
    pub name: Option<&'a str>,
    /// A resolved `.psi` path (`energy.psi`).
    pub psi: Option<&'a Path>,
    /// Parameter overrides (`energy.params`), sorted by name.
    pub params: &'a [(String, f64)],
}

/// Why an energy could not be provided (mapped to the scene key at fault).
#[derive(Clone, Debug, PartialEq)]
pub enum EnergyError {
    /// No built-in energy of that name; `known` lists the provider's names.
    UnknownName {
        /// The name asked for.
        name: String,
        /// The names the provider knows.
        known: Vec<String>,
    },
    /// The `.psi` file cannot be read or compiled (message rendered by the provider).
    File(String),
    /// The energy has no variant in the mesh's dimension.
    Dimension(String),
    /// A parameter is unknown or not finite.
    Param(String),
}

impl std::fmt::Display for EnergyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EnergyError::UnknownName { name, known } => {
                write!(f, "unknown energy `{name}` (known: {})", known.join(", "))
            }
            EnergyError::File(m) | EnergyError::Dimension(m) | EnergyError::Param(m) => {
                write!(f, "{m}")
            }
        }
    }
}

/// Provides 2D and 3D energies by name or `.psi` file.
pub trait EnergySource {
    /// A 2D energy (triangles: planar deformation, parameterisation).
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError>;
    /// A 3D energy (tets).
    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError>;
    /// The built-in names (for messages and `--help`).
    fn names(&self) -> Vec<String>;
}

/// Apply parameter overrides through [`Energy::set_param`].
pub fn apply_params<const D: usize>(
    energy: &mut dyn Energy<D>,
    params: &[(String, f64)],
) -> Result<(), EnergyError> {
    for (name, value) in params {
        energy
            .set_param(name, *value)
            .map_err(|e: ParamError| EnergyError::Param(e.to_string()))?;
    }
    Ok(())
}

/// The runtime's hand-written energies: `arap`, `sd` (symmetric Dirichlet)
/// and `snh` (Stable Neo-Hookean, μ = 1, λ = 10 by default). `.psi` files
/// are not supported by this provider.
#[derive(Clone, Copy, Debug, Default)]
pub struct RuntimeEnergies;

impl RuntimeEnergies {
    fn pick<const D: usize>(req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<D>>, EnergyError>
    where
        Arap: Energy<D>,
        SymmetricDirichlet: Energy<D>,
        StableNeoHookean: Energy<D>,
    {
        if let Some(p) = req.psi {
            return Err(EnergyError::File(format!(
                "`{}`: this program has no .psi interpreter (use the `ecc` CLI)",
                p.display()
            )));
        }
        let name = req.name.unwrap_or_default();
        let mut e: Box<dyn Energy<D>> = match name {
            "arap" => Box::new(Arap),
            "sd" | "symmetric_dirichlet" => Box::new(SymmetricDirichlet),
            "snh" | "stable_neo_hookean" => Box::new(StableNeoHookean::new(1.0, 10.0)),
            _ => {
                return Err(EnergyError::UnknownName {
                    name: name.to_string(),
                    known: RuntimeEnergies.names(),
                });
            }
        };
        apply_params(e.as_mut(), req.params)?;
        Ok(e)
    }
}

impl EnergySource for RuntimeEnergies {
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError> {
        Self::pick::<2>(req)
    }

    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError> {
        Self::pick::<3>(req)
    }

    fn names(&self) -> Vec<String> {
        vec!["arap".into(), "sd".into(), "snh".into()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runtime_energies_by_name_with_params() {
        let params = vec![("mu".to_string(), 2.0)];
        let req = EnergyRequest {
            name: Some("snh"),
            psi: None,
            params: &params,
        };
        let e = RuntimeEnergies.energy3(&req).unwrap();
        assert!(e.params().contains(&("mu".to_string(), 2.0)));
        let bad = EnergyRequest {
            name: Some("arap"),
            psi: None,
            params: &params,
        };
        assert!(matches!(
            RuntimeEnergies.energy2(&bad),
            Err(EnergyError::Param(_))
        ));
        let unknown = EnergyRequest {
            name: Some("nope"),
            psi: None,
            params: &[],
        };
        assert!(matches!(
            RuntimeEnergies.energy2(&unknown),
            Err(EnergyError::UnknownName { .. })
        ));
    }
}
