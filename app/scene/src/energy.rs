//! Where energies come from: an injected provider.
//!
//! ecc-scene lives under `runtime/` and must not depend on the compiler
//! crates, so it asks an [`EnergySource`] for the energy a scene names. The
//! `ecc` CLI provides one over the built-in generated energies and the
//! `.psi` interpreter; [`RuntimeEnergies`] is the small provider over the
//! runtime's hand-written energies (ARAP, symmetric Dirichlet, Stable
//! Neo-Hookean), used by this crate's tests and as a fallback.

use std::path::Path;

use ecc_runtime::energies::{Arap, FIBRE_NAMES, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, FibreEnergy, ParamError};

/// What a scene asks for: the body's energy (`[energy]`: `name`, `psi`,
/// `params`) or the fibre energy (`[fibers]`: `energy` as a name or a
/// `.psi` path, `params`).
#[derive(Clone, Copy, Debug)]
pub struct EnergyRequest<'a> {
    /// A built-in energy name (`energy.name`, or `fibers.energy`).
    pub name: Option<&'a str>,
    /// A resolved `.psi` path (`energy.psi`, or a `fibers.energy` ending in `.psi`).
    pub psi: Option<&'a Path>,
    /// Parameter overrides (`energy.params` or `fibers.params`), sorted by name.
    pub params: &'a [(String, f64)],
}

/// The body's energy (`[energy]`): the isotropic energy and, for a `.psi`
/// file declaring `fiber a`, its fibre part ψ(I4, I5), which the scene
/// places on the `[fibers]` directions (it needs them). Both parts carry
/// the file's parameters with `energy.params` applied.
pub struct BodyEnergy<const D: usize> {
    /// Ψ (Ψ_iso for a file with a fibre part).
    pub energy: Box<dyn Energy<D>>,
    /// ψ(I4, I5) of a `.psi` with `fiber a`; `None` otherwise.
    pub fibre: Option<Box<dyn FibreEnergy<D>>>,
}

impl<const D: usize> BodyEnergy<D> {
    /// An energy without a fibre part.
    pub fn isotropic(energy: Box<dyn Energy<D>>) -> Self {
        BodyEnergy {
            energy,
            fibre: None,
        }
    }
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
///
/// Scenes ask [`EnergySource::body2`]/[`EnergySource::body3`] for the
/// body's energy and [`EnergySource::fibre2`]/[`EnergySource::fibre3`] for
/// `[fibers] energy`. The defaults serve providers that only implement
/// `energy2`/`energy3`: no fibre part for the body (such a provider must
/// refuse a `.psi` with `fiber a` in `energy2`/`energy3`, as
/// `ecc_interp::load_psi` does, never drop it), and the runtime's
/// hand-written fibre energies ([`runtime_fibre`]).
pub trait EnergySource {
    /// A 2D energy (triangles: planar deformation, parameterisation).
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError>;
    /// A 3D energy (tets).
    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError>;
    /// The built-in names (for messages and `--help`).
    fn names(&self) -> Vec<String>;

    /// The body's 2D energy with the fibre part of a `.psi` (default:
    /// [`EnergySource::energy2`], no fibre part).
    fn body2(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<2>, EnergyError> {
        self.energy2(req).map(BodyEnergy::isotropic)
    }
    /// The body's 3D energy with the fibre part of a `.psi` (default:
    /// [`EnergySource::energy3`], no fibre part).
    fn body3(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<3>, EnergyError> {
        self.energy3(req).map(BodyEnergy::isotropic)
    }
    /// A 2D fibre energy ψ(I4, I5) by name or `.psi` file (default: [`runtime_fibre`]).
    fn fibre2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<2>>, EnergyError> {
        runtime_fibre::<2>(req)
    }
    /// A 3D fibre energy ψ(I4, I5) by name or `.psi` file (default: [`runtime_fibre`]).
    fn fibre3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<3>>, EnergyError> {
        runtime_fibre::<3>(req)
    }
    /// The fibre energies' names (default: the runtime's, [`FIBRE_NAMES`]).
    fn fibre_names(&self) -> Vec<String> {
        FIBRE_NAMES.iter().map(|s| s.to_string()).collect()
    }
}

/// Apply parameter overrides through [`FibreEnergy::set_fibre_param`].
pub fn apply_fibre_params<const D: usize>(
    energy: &mut dyn FibreEnergy<D>,
    params: &[(String, f64)],
) -> Result<(), EnergyError> {
    for (name, value) in params {
        energy
            .set_fibre_param(name, *value)
            .map_err(|e: ParamError| EnergyError::Param(e.to_string()))?;
    }
    Ok(())
}

/// The runtime's hand-written fibre energies
/// ([`ecc_runtime::energies::fibre_by_name`]: `fibre-stvk`, `fibre-arap`,
/// `fibre-fung`) with parameter overrides; `.psi` files are refused (no
/// interpreter here).
pub fn runtime_fibre<const D: usize>(
    req: &EnergyRequest<'_>,
) -> Result<Box<dyn FibreEnergy<D>>, EnergyError> {
    if let Some(p) = req.psi {
        return Err(EnergyError::File(format!(
            "`{}`: this program has no .psi interpreter for fibre energies (the `ecc` CLI and the \
             Python package have one); use one of {FIBRE_NAMES:?}",
            p.display()
        )));
    }
    let name = req.name.unwrap_or_default();
    let mut e = ecc_runtime::energies::fibre_by_name::<D>(name).ok_or_else(|| {
        EnergyError::UnknownName {
            name: name.to_string(),
            known: FIBRE_NAMES.iter().map(|s| s.to_string()).collect(),
        }
    })?;
    apply_fibre_params(e.as_mut(), req.params)?;
    Ok(e)
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
