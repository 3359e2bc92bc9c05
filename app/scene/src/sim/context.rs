//! What a run is given and what it returns: the options, the shared
//! context of one run (scene, options, clock, mesh), the final state and
//! report, and the pieces of the summary common to every mode.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use ecc_fem::{Term, TermTiming};
use ecc_mesh::TriMesh;
use ecc_runtime::{Energy, FibreEnergy};

use crate::error::SceneError;
use crate::output::OutputDir;
use crate::setup::mesh::LoadedMesh;
use crate::spec::{FrameFormat, SceneFile};
use crate::summary::{EnergyStats, MeshStats, Summary, TermStats};

/// How to run.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Output folder (overrides `output.dir`; `ecc sim --out`).
    pub out_dir: Option<PathBuf>,
    /// Write nothing at all (no folder, frames, pictures or summary).
    pub dry_run: bool,
    /// Override `output.pictures`.
    pub pictures: Option<bool>,
}

/// The final positions, for callers that check physics.
#[derive(Clone, Debug)]
pub enum FinalState {
    /// A planar triangle body.
    Planar {
        /// Rest positions.
        rest: Vec<[f64; 2]>,
        /// Final positions.
        x: Vec<[f64; 2]>,
        /// Triangles.
        triangles: Vec<[usize; 3]>,
    },
    /// A tet body.
    Volume {
        /// Rest positions.
        rest: Vec<[f64; 3]>,
        /// Final positions.
        x: Vec<[f64; 3]>,
        /// Tets.
        tets: Vec<[usize; 4]>,
    },
    /// A parameterisation.
    Param {
        /// The surface (positions scaled to unit area).
        mesh: TriMesh,
        /// Final uv per vertex.
        uv: Vec<[f64; 2]>,
    },
}

/// What a run produced.
#[derive(Clone, Debug)]
pub struct RunReport {
    /// The summary (also written as `summary.json`).
    pub summary: Summary,
    /// The output folder (`None` for a dry run).
    pub out_dir: Option<PathBuf>,
    /// Final positions.
    pub state: FinalState,
    /// Handle vertex sets.
    pub handles: Vec<Vec<usize>>,
}

/// The output folder for a scene: the override, else `output.dir`
/// (relative to the scene file), else `ecc-out/<name>` in the current folder.
pub fn output_folder(file: &SceneFile, opts: &RunOptions) -> PathBuf {
    if let Some(d) = &opts.out_dir {
        return d.clone();
    }
    match &file.scene.output.dir {
        Some(d) => file.resolve(d),
        None => PathBuf::from("ecc-out").join(file.name()),
    }
}

/// Shared run context.
pub(crate) struct Context<'a> {
    pub file: &'a SceneFile,
    pub opts: &'a RunOptions,
    pub t0: Instant,
    pub loaded: &'a LoadedMesh,
}

impl Context<'_> {
    pub(crate) fn pictures_on(&self) -> bool {
        self.opts
            .pictures
            .unwrap_or(self.file.scene.output.pictures.unwrap_or(true))
    }

    pub(crate) fn formats(&self) -> Vec<FrameFormat> {
        self.file
            .scene
            .output
            .formats
            .clone()
            .unwrap_or(vec![FrameFormat::Obj, FrameFormat::Vtk])
    }

    pub(crate) fn image_size(&self) -> (usize, usize) {
        match &self.file.scene.output.image_size {
            Some(s) => (s[0], s[1]),
            None => (960, 720),
        }
    }

    pub(crate) fn mesh_stats(&self, rest_measure: f64) -> MeshStats {
        let (v, e) = self.loaded.counts();
        MeshStats {
            source: self.loaded.source.clone(),
            kind: self.loaded.kind_name().to_string(),
            vertices: v,
            elements: e,
            rest_measure,
        }
    }

    pub(crate) fn effects(&self) -> Vec<String> {
        let fx = &self.file.scene.effects;
        let mut v = Vec::new();
        let mut on = |name: &str, b: bool| {
            if b {
                v.push(name.to_string());
            }
        };
        on("gravity", fx.gravity.is_some());
        on("inertia", fx.inertia.is_some());
        on("damping", fx.damping.is_some());
        on("ground", fx.ground.is_some());
        on("handles", !fx.handles.is_empty());
        on("interpolate", fx.interpolate.is_some());
        on("parameterize", fx.parameterize.is_some());
        v
    }
}

/// The energy's name, parameters and barrier flag.
pub(crate) fn energy_stats<const D: usize>(e: &dyn Energy<D>) -> EnergyStats {
    EnergyStats {
        name: e.name().to_string(),
        params: e.params().into_iter().collect::<BTreeMap<_, _>>(),
        barrier: e.info().barrier,
    }
}

/// The fibre energy's name and parameters.
pub(crate) fn fibre_stats<const D: usize>(e: &dyn FibreEnergy<D>) -> EnergyStats {
    EnergyStats {
        name: e.name().to_string(),
        params: e.fibre_params().into_iter().collect::<BTreeMap<_, _>>(),
        barrier: false,
    }
}

/// Per-term stencils, passes and seconds from the solver's timings.
pub(crate) fn term_stats<const D: usize>(
    terms: &[Box<dyn Term<D>>],
    timings: &[TermTiming],
) -> Vec<TermStats> {
    terms
        .iter()
        .map(|t| {
            let timing = timings.iter().find(|a| a.name == t.name());
            TermStats {
                name: t.name().to_string(),
                stencils: t.n_stencils(),
                value_passes: timing.map_or(0, |a| a.value_passes),
                assembly_passes: timing.map_or(0, |a| a.assembly_passes),
                seconds: timing.map_or(0.0, |a| a.value_seconds + a.assembly_seconds),
            }
        })
        .collect()
}

/// Fill in the totals, write `summary.json` and build the report.
pub(crate) fn finish(
    ctx: &Context<'_>,
    mut summary: Summary,
    out: &mut Option<OutputDir>,
    state: FinalState,
    handles: Vec<Vec<usize>>,
) -> Result<RunReport, SceneError> {
    if let Some(o) = out.as_mut() {
        let mut outputs: Vec<String> = o.written().to_vec();
        outputs.push("summary.json".into());
        summary.outputs = outputs;
        summary.wall_seconds = ctx.t0.elapsed().as_secs_f64();
        let json = serde_json::to_vec_pretty(&summary).map_err(|e| SceneError::Write {
            path: "summary.json".into(),
            source: e.into(),
        })?;
        o.write("summary.json", &json)?;
    } else {
        summary.wall_seconds = ctx.t0.elapsed().as_secs_f64();
    }
    Ok(RunReport {
        summary,
        out_dir: out.as_ref().map(|o| o.path().to_path_buf()),
        state,
        handles,
    })
}
