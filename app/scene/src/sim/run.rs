//! Running a scene end to end: check, prepare the output folder, load the
//! mesh and the energy, then hand over to the mode — parameterisation
//! ([`super::param`]) or the frame loop ([`super::frames`]).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use ecc_mesh::{boundary_loops, tet_boundary_faces};
use ecc_runtime::Energy;

use super::build;
use super::context::{Context, RunOptions, RunReport, output_folder};
use super::frames::run_frames;
use super::observer::Observer;
use super::param::run_parameterization;
use super::target::{second_rest_2d, second_rest_3d};
use crate::body::Body;
use crate::energy::{EnergyError, EnergyRequest, EnergySource};
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::setup::mesh::{MeshKind, load};
use crate::spec::{SceneFile, validate};
use crate::terms::fibre;

fn energy_error(file: &SceneFile, e: EnergyError) -> SceneError {
    let key = match (&e, file.scene.energy.psi.is_some()) {
        (EnergyError::Param(_), _) => "energy.params",
        (_, true) => "energy.psi",
        (_, false) => "energy.name",
    };
    let message = match &e {
        EnergyError::UnknownName { name, known } => {
            let refs: Vec<&str> = known.iter().map(String::as_str).collect();
            match crate::spec::suggest_name(name, &refs) {
                Some(s) => format!("{e}; did you mean `{s}`?"),
                None => e.to_string(),
            }
        }
        _ => e.to_string(),
    };
    SceneError::invalid(key, message)
}

/// Ask the provider for the scene's energy in dimension `D`.
fn request<'a>(
    file: &'a SceneFile,
    psi: &'a Option<PathBuf>,
    params: &'a [(String, f64)],
) -> EnergyRequest<'a> {
    EnergyRequest {
        name: file.scene.energy.name.as_deref(),
        psi: psi.as_deref(),
        params,
    }
}

/// Run a scene (see the module docs). Errors name the scene key at fault.
pub fn run_scene(
    file: &SceneFile,
    source: &dyn EnergySource,
    opts: &RunOptions,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError> {
    run_inner(file, source, opts, obs).map_err(|e| file.locate(e))
}

fn run_inner(
    file: &SceneFile,
    source: &dyn EnergySource,
    opts: &RunOptions,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError> {
    let t0 = Instant::now();
    validate::check(&file.scene)?;
    let folder = output_folder(file, opts);
    let mut out = if opts.dry_run {
        None
    } else {
        Some(OutputDir::prepare(&folder)?)
    };
    let param = file.scene.effects.parameterize.is_some();
    let loaded = load(file, param)?;
    let psi = file.scene.energy.psi.as_ref().map(|p| file.resolve(p));
    let params: Vec<(String, f64)> = file
        .scene
        .energy
        .params
        .iter()
        .map(|(k, v)| (k.clone(), *v))
        .collect();
    let req = request(file, &psi, &params);
    let ctx = Context {
        file,
        opts,
        t0,
        loaded: &loaded,
    };
    match &loaded.kind {
        MeshKind::Surface(mesh) => {
            let be = source.body2(&req).map_err(|e| energy_error(file, e))?;
            fibre::refuse_in_parameterisation(file, be.fibre.is_some())?;
            run_parameterization(&ctx, mesh, be.energy.into(), &mut out, obs)
        }
        MeshKind::Planar(mesh) => {
            let be = source.body2(&req).map_err(|e| energy_error(file, e))?;
            let fibre = fibre::fibre_energy::<2>(file, source, be.fibre)?;
            let e: Arc<dyn Energy<2>> = be.energy.into();
            let rest: Vec<[f64; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
            let body = Body::planar(rest, &mesh.triangles, e)
                .with_projection(build::deformation_projection(&file.scene.solver, 2));
            let boundary = boundary_loops(&mesh.triangles)
                .map(|l| l.into_iter().flatten().collect())
                .unwrap_or_else(|_| (0..mesh.positions.len()).collect());
            let rest2 = second_rest_2d(file, &body, &loaded)?;
            run_frames(&ctx, body, boundary, rest2, fibre, &mut out, obs)
        }
        MeshKind::Volume(mesh) => {
            let be = source.body3(&req).map_err(|e| energy_error(file, e))?;
            let fibre = fibre::fibre_energy::<3>(file, source, be.fibre)?;
            let e: Arc<dyn Energy<3>> = be.energy.into();
            let body = Body::volume(mesh.positions.clone(), &mesh.tets, e)
                .with_projection(build::deformation_projection(&file.scene.solver, 3));
            let mut boundary: Vec<usize> = tet_boundary_faces(&mesh.tets)
                .into_iter()
                .flatten()
                .collect();
            boundary.sort_unstable();
            boundary.dedup();
            let rest2 = second_rest_3d(file, &body, &loaded)?;
            run_frames(&ctx, body, boundary, rest2, fibre, &mut out, obs)
        }
    }
}
