//! `simulate(scene.toml, …)`: a scene file run by ecc-scene (as `ecc sim`),
//! its summary returned as a dict. Energies by name are the standard `.psi`
//! files evaluated by the interpreter (the numbers of `ecc eval`), `.psi`
//! paths are loaded with `ecc_interp::load_parts` (the fibre part of a file
//! with `fiber a` goes on the `[fibers]` directions). Fibre energies
//! (`[fibers] energy`) by name are the generated library's
//! (`ecc_energies::fibre_by_name`, as `ecc sim`), `.psi` paths their fibre
//! part (`ecc_interp::load_fibre_part`).

use std::ops::ControlFlow;
use std::path::PathBuf;

use ecc_fem::IterationRecord;
use ecc_interp::LoadError;
use ecc_runtime::{Dim, Energy, FibreEnergy, Space};
use ecc_scene::energy::apply_fibre_params;
use ecc_scene::{
    BodyEnergy, EnergyError, EnergyRequest, EnergySource, Observer, RunOptions, SceneFile,
    run_scene,
};
use pyo3::prelude::*;

use crate::builtin;
use crate::errors::scene_error;
use crate::hook::Hook;

/// The Python package's energy provider for scenes.
struct PyEnergies;

fn load_error(e: LoadError) -> EnergyError {
    match e {
        LoadError::Param { source, .. } => EnergyError::Param(source.to_string()),
        LoadError::NoSuchDim { .. } => EnergyError::Dimension(e.to_string()),
        LoadError::Syntax { rendered, .. } => {
            EnergyError::File(format!("\n{}", rendered.trim_end()))
        }
        other => EnergyError::File(other.to_string()),
    }
}

/// The body's energy: both parts of a `.psi` file, or a built-in by name.
fn body<const D: usize>(req: &EnergyRequest<'_>) -> Result<BodyEnergy<D>, EnergyError>
where
    Space<D>: Dim<D>,
{
    let Some(p) = req.psi else {
        return provide::<D>(req).map(BodyEnergy::isotropic);
    };
    let parts = ecc_interp::load_parts::<D>(p, req.params).map_err(load_error)?;
    Ok(BodyEnergy {
        energy: Box::new(parts.iso),
        fibre: parts.fibre.map(|f| Box::new(f) as Box<dyn FibreEnergy<D>>),
    })
}

/// A fibre energy: the fibre part of a `.psi` file, or the library's by name.
fn fibre<const D: usize>(req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<D>>, EnergyError> {
    if let Some(p) = req.psi {
        let f = ecc_interp::load_fibre_part::<D>(p, req.params).map_err(load_error)?;
        return Ok(Box::new(f));
    }
    let name = req.name.unwrap_or_default();
    let mut e = ecc_energies::fibre_by_name::<D>(name).ok_or_else(|| match ecc_energies::entry(
        name,
    ) {
        Some(entry) if !entry.fibre => EnergyError::File(format!(
            "`{}` is an isotropic energy, not a fibre energy ψ(I4, I5) (it belongs in [energy])",
            entry.name
        )),
        _ => EnergyError::UnknownName {
            name: name.to_string(),
            known: PyEnergies.fibre_names(),
        },
    })?;
    apply_fibre_params(e.as_mut(), req.params)?;
    Ok(e)
}

/// A built-in isotropic energy by name (a `.psi` path through [`body`]).
fn provide<const D: usize>(req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<D>>, EnergyError>
where
    Space<D>: Dim<D>,
{
    if let Some(p) = req.psi {
        return ecc_interp::load_psi::<D>(p, req.params).map_err(load_error);
    }
    let name = req.name.unwrap_or_default();
    let unknown = || EnergyError::UnknownName {
        name: name.to_string(),
        known: PyEnergies.names(),
    };
    let canon = builtin::canonical(name).ok_or_else(unknown)?;
    for stem in builtin::stems(canon, D) {
        let Some(src) = builtin::compiled(&stem) else {
            continue;
        };
        let src = src.map_err(|e| EnergyError::File(e.to_string()))?;
        if src.module.dim(D as u8).is_some() {
            let e = ecc_interp::energy_from_module::<D>(&src.module, &src.shown, req.params)
                .map_err(load_error)?;
            return Ok(Box::new(e));
        }
    }
    Err(EnergyError::Dimension(format!(
        "`{canon}` has no {D}D version"
    )))
}

impl EnergySource for PyEnergies {
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError> {
        provide::<2>(req)
    }

    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError> {
        provide::<3>(req)
    }

    fn names(&self) -> Vec<String> {
        builtin::names().iter().map(|s| s.to_string()).collect()
    }

    fn body2(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<2>, EnergyError> {
        body::<2>(req)
    }

    fn body3(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<3>, EnergyError> {
        body::<3>(req)
    }

    fn fibre2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<2>>, EnergyError> {
        fibre::<2>(req)
    }

    fn fibre3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<3>>, EnergyError> {
        fibre::<3>(req)
    }

    fn fibre_names(&self) -> Vec<String> {
        ecc_energies::fibre_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
}

/// Progress and Ctrl-C for scenes: the observer cannot stop a scene, so
/// the first error (KeyboardInterrupt, or one raised by the callback) is
/// re-raised when the run returns; later calls are skipped.
struct PyObserver(Hook);

impl Observer for PyObserver {
    /// Ctrl-C, an exception in the callback or a `False` return stops the
    /// run (the scene ends early with what it computed; the error is raised
    /// once the run has returned).
    fn iteration(&mut self, _frame: usize, rec: &IterationRecord) -> ControlFlow<()> {
        if self.0.error.is_some() {
            return ControlFlow::Break(());
        }
        self.0.step(rec)
    }
}

/// Low-level scene run (use `ecc.simulate`): returns the summary as JSON text.
#[pyfunction]
#[pyo3(signature = (scene, out, frames, pictures, progress))]
pub fn simulate(
    py: Python<'_>,
    scene: PathBuf,
    out: Option<PathBuf>,
    frames: Option<usize>,
    pictures: Option<bool>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let mut file = SceneFile::read(&scene).map_err(scene_error)?;
    if let Some(n) = frames {
        if n == 0 {
            return Err(scene_error("frames must be at least 1"));
        }
        file.scene.frames = Some(n);
    }
    let opts = RunOptions {
        out_dir: out,
        dry_run: false,
        pictures,
    };
    let mut obs = PyObserver(Hook::new(progress));
    let report = py.detach(|| run_scene(&file, &PyEnergies, &opts, &mut obs));
    obs.0.finish()?;
    let report = report.map_err(scene_error)?;
    serde_json::to_string(&report.summary).map_err(scene_error)
}
