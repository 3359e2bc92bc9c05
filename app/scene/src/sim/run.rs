//! Running a scene end to end: check, prepare the output folder, load the
//! mesh and the energy, build the objective, step the frames, write frames,
//! pictures and `summary.json`.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use ecc_mesh::{TetMesh, TriMesh, boundary_loops, tet_boundary_faces};
use ecc_runtime::Energy;

use super::build::{EngineInput, build_engine, frame_count};
use super::engine::Engine;
use super::observer::Observer;
use super::param::run_parameterization;
use crate::body::Body;
use crate::counters::Counters;
use crate::energy::{EnergyError, EnergyRequest, EnergySource};
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::pictures::{self, Picture};
use crate::setup::mesh::{LoadedMesh, MeshKind, load, read_file};
use crate::setup::shape::{axis_index, twist_bend};
use crate::spec::{FrameFormat, SceneFile, validate};
use crate::summary::{EnergyStats, FrameStats, HandleStats, MeshStats, Summary, TermStats};

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
            let e: Arc<dyn Energy<2>> = source
                .energy2(&req)
                .map_err(|e| energy_error(file, e))?
                .into();
            run_parameterization(&ctx, mesh, e, &mut out, obs)
        }
        MeshKind::Planar(mesh) => {
            let e: Arc<dyn Energy<2>> = source
                .energy2(&req)
                .map_err(|e| energy_error(file, e))?
                .into();
            let rest: Vec<[f64; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
            let body = Body::planar(rest, &mesh.triangles, e);
            let boundary = boundary_loops(&mesh.triangles)
                .map(|l| l.into_iter().flatten().collect())
                .unwrap_or_else(|_| (0..mesh.positions.len()).collect());
            let rest2 = second_rest_2d(file, &body, &loaded)?;
            run_frames(&ctx, body, boundary, rest2, &mut out, obs)
        }
        MeshKind::Volume(mesh) => {
            let e: Arc<dyn Energy<3>> = source
                .energy3(&req)
                .map_err(|e| energy_error(file, e))?
                .into();
            let body = Body::volume(mesh.positions.clone(), &mesh.tets, e);
            let mut boundary: Vec<usize> = tet_boundary_faces(&mesh.tets)
                .into_iter()
                .flatten()
                .collect();
            boundary.sort_unstable();
            boundary.dedup();
            let rest2 = second_rest_3d(file, &body, &loaded)?;
            run_frames(&ctx, body, boundary, rest2, &mut out, obs)
        }
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

/// Read an interpolation target mesh with the same transform and elements.
fn target_positions(
    file: &SceneFile,
    loaded: &LoadedMesh,
    written: &str,
) -> Result<Vec<[f64; 3]>, SceneError> {
    let key = "effects.interpolate.target";
    let (mesh, _) = read_file(file, key, written)?;
    let m = &file.scene.mesh;
    let s = m.scale.unwrap_or(1.0);
    let t = m.translate.clone().unwrap_or_default();
    let tr = |p: [f64; 3]| {
        std::array::from_fn::<f64, 3, _>(|c| p[c] * s + t.get(c).copied().unwrap_or(0.0))
    };
    let same = |n: usize, elements_equal: bool| -> Result<(), SceneError> {
        let (nv, _) = loaded.counts();
        if n != nv || !elements_equal {
            return Err(SceneError::invalid(
                key,
                "the target must have the same vertices and elements as the mesh",
            ));
        }
        Ok(())
    };
    match (mesh, &loaded.kind) {
        (ecc_mesh::AnyMesh::Tet(tm), MeshKind::Volume(b)) => {
            same(tm.positions.len(), tm.tets == b.tets)?;
            Ok(tm.positions.into_iter().map(tr).collect())
        }
        (ecc_mesh::AnyMesh::Tri(tm), MeshKind::Planar(b)) => {
            same(tm.positions.len(), tm.triangles == b.triangles)?;
            Ok(tm.positions.into_iter().map(tr).collect())
        }
        (other, _) => Err(SceneError::invalid(
            key,
            format!(
                "the target is a {} mesh, the body is {}",
                other.kind(),
                loaded.kind_name()
            ),
        )),
    }
}

fn second_rest_3d(
    file: &SceneFile,
    body: &Body<3>,
    loaded: &LoadedMesh,
) -> Result<Option<Vec<[f64; 3]>>, SceneError> {
    let Some(i) = &file.scene.effects.interpolate else {
        return Ok(None);
    };
    if let Some(t) = &i.target {
        return target_positions(file, loaded, t).map(Some);
    }
    twist_bend::<3>(&body.rest, axis_index(i.axis.as_deref()), i.twist, i.bend).map(Some)
}

fn second_rest_2d(
    file: &SceneFile,
    body: &Body<2>,
    loaded: &LoadedMesh,
) -> Result<Option<Vec<[f64; 2]>>, SceneError> {
    let Some(i) = &file.scene.effects.interpolate else {
        return Ok(None);
    };
    if let Some(t) = &i.target {
        let p = target_positions(file, loaded, t)?;
        if p.iter().any(|q| q[2] != 0.0) {
            return Err(SceneError::invalid(
                "effects.interpolate.target",
                "the target of a planar mesh must be planar (z = 0)",
            ));
        }
        return Ok(Some(p.into_iter().map(|q| [q[0], q[1]]).collect()));
    }
    twist_bend::<2>(&body.rest, axis_index(i.axis.as_deref()), i.twist, i.bend).map(Some)
}

/// Writes frames of a D-dimensional body.
pub(crate) trait FrameWriter<const D: usize> {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; D]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError>;
}

struct TriWriter {
    mesh: TriMesh,
    rest: Vec<[f64; 2]>,
}

impl FrameWriter<2> for TriWriter {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; 2]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError> {
        let mut m = self.mesh.clone();
        m.positions = x.iter().map(|p| [p[0], p[1], 0.0]).collect();
        for f in formats {
            match f {
                FrameFormat::Obj => out.obj(&format!("{name}.obj"), &m)?,
                FrameFormat::Vtk => {
                    let disp: Vec<f64> = x
                        .iter()
                        .zip(&self.rest)
                        .flat_map(|(p, r)| [p[0] - r[0], p[1] - r[1], 0.0])
                        .collect();
                    out.vtk_tri(&format!("{name}.vtk"), &m, &[("displacement", &disp, 3)])?
                }
            }
        }
        Ok(())
    }
}

struct TetWriter {
    tets: Vec<[usize; 4]>,
    rest: Vec<[f64; 3]>,
    /// Boundary faces in compact numbering and the vertex each compact id came from.
    faces: Vec<[usize; 3]>,
    surface_vertices: Vec<usize>,
}

impl TetWriter {
    fn new(tets: &[[usize; 4]], rest: &[[f64; 3]]) -> Self {
        let faces = tet_boundary_faces(tets);
        let mut index = vec![usize::MAX; rest.len()];
        let mut surface_vertices = Vec::new();
        let faces = faces
            .into_iter()
            .map(|f| {
                f.map(|v| {
                    if index[v] == usize::MAX {
                        index[v] = surface_vertices.len();
                        surface_vertices.push(v);
                    }
                    index[v]
                })
            })
            .collect();
        TetWriter {
            tets: tets.to_vec(),
            rest: rest.to_vec(),
            faces,
            surface_vertices,
        }
    }
}

impl FrameWriter<3> for TetWriter {
    fn write(
        &self,
        out: &mut OutputDir,
        name: &str,
        x: &[[f64; 3]],
        formats: &[FrameFormat],
    ) -> Result<(), SceneError> {
        for f in formats {
            match f {
                FrameFormat::Obj => {
                    let m = TriMesh {
                        positions: self.surface_vertices.iter().map(|&v| x[v]).collect(),
                        triangles: self.faces.clone(),
                        uvs: None,
                    };
                    out.obj(&format!("{name}.obj"), &m)?
                }
                FrameFormat::Vtk => {
                    let m = TetMesh {
                        positions: x.to_vec(),
                        tets: self.tets.clone(),
                    };
                    let disp: Vec<f64> = x
                        .iter()
                        .zip(&self.rest)
                        .flat_map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]])
                        .collect();
                    out.vtk_tet(&format!("{name}.vtk"), &m, &[("displacement", &disp, 3)])?
                }
            }
        }
        Ok(())
    }
}

/// A body kind that can be written and pictured.
pub(crate) trait Dim<const D: usize> {
    fn writer(body: &Body<D>) -> Box<dyn FrameWriter<D>>;
    fn picture(
        body: &Body<D>,
        shots: &[(usize, Vec<[f64; D]>)],
        view: &pictures::View<'_>,
    ) -> Picture;
    fn state(body: &Body<D>, x: Vec<[f64; D]>) -> FinalState;
}

pub(crate) struct Dims;

impl Dim<2> for Dims {
    fn writer(body: &Body<2>) -> Box<dyn FrameWriter<2>> {
        let (tris, _) = body.elements.as_chunks::<3>();
        Box::new(TriWriter {
            mesh: TriMesh {
                positions: body.rest.iter().map(|p| [p[0], p[1], 0.0]).collect(),
                triangles: tris.to_vec(),
                uvs: None,
            },
            rest: body.rest.clone(),
        })
    }

    fn picture(
        body: &Body<2>,
        shots: &[(usize, Vec<[f64; 2]>)],
        view: &pictures::View<'_>,
    ) -> Picture {
        let (tris, _) = body.elements.as_chunks::<3>();
        pictures::planar(tris, &body.rest, shots, view)
    }

    fn state(body: &Body<2>, x: Vec<[f64; 2]>) -> FinalState {
        let (tris, _) = body.elements.as_chunks::<3>();
        FinalState::Planar {
            rest: body.rest.clone(),
            x,
            triangles: tris.to_vec(),
        }
    }
}

impl Dim<3> for Dims {
    fn writer(body: &Body<3>) -> Box<dyn FrameWriter<3>> {
        let (tets, _) = body.elements.as_chunks::<4>();
        Box::new(TetWriter::new(tets, &body.rest))
    }

    fn picture(
        body: &Body<3>,
        shots: &[(usize, Vec<[f64; 3]>)],
        view: &pictures::View<'_>,
    ) -> Picture {
        let (tets, _) = body.elements.as_chunks::<4>();
        pictures::volume(tets, shots, view)
    }

    fn state(body: &Body<3>, x: Vec<[f64; 3]>) -> FinalState {
        let (tets, _) = body.elements.as_chunks::<4>();
        FinalState::Volume {
            rest: body.rest.clone(),
            x,
            tets: tets.to_vec(),
        }
    }
}

/// Which frames to keep for the picture: up to `keep`, evenly spread, always the last.
fn keep_for_picture(frame: usize, frames: usize, keep: usize) -> bool {
    if frame == frames || frames <= keep {
        return true;
    }
    let stride = frames.div_ceil(keep.max(1));
    frame.is_multiple_of(stride)
}

fn run_frames<const D: usize>(
    ctx: &Context<'_>,
    body: Body<D>,
    boundary: Vec<usize>,
    rest2: Option<Vec<[f64; D]>>,
    out: &mut Option<OutputDir>,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError>
where
    Dims: Dim<D>,
{
    let file = ctx.file;
    let counters = Arc::new(Counters::default());
    let energy = energy_stats::<D>(body.energy.as_ref());
    let rest_measure = body.total_rest_measure();
    let writer = <Dims as Dim<D>>::writer(&body);
    let mut engine: Engine<D> = build_engine(EngineInput {
        file,
        body,
        vertex_map: &ctx.loaded.vertex_map,
        boundary,
        rest2,
        counters: counters.clone(),
    })?;
    let frames = frame_count(file, &engine.handles);
    let setup_seconds = ctx.t0.elapsed().as_secs_f64();
    let formats = ctx.formats();
    let every = file.scene.output.every.unwrap_or(1);
    let mut output_seconds = 0.0;
    let mut shots: Vec<(usize, Vec<[f64; D]>)> = Vec::new();
    let mut stats: Vec<FrameStats> = vec![engine.frame_stats(0)];
    shots.push((0, engine.x.clone()));
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        writer.write(o, "frame_0000", &engine.x, &formats)?;
        output_seconds += t.elapsed().as_secs_f64();
    }
    obs.start(&file.name(), frames);
    for frame in 1..=frames {
        let s = engine.step_frame(frame, obs);
        obs.frame_done(&s);
        stats.push(s);
        let last = frame == frames || engine.stopped.is_some();
        if let Some(o) = out.as_mut()
            && (frame % every == 0 || last)
        {
            let t = Instant::now();
            writer.write(o, &format!("frame_{frame:04}"), &engine.x, &formats)?;
            output_seconds += t.elapsed().as_secs_f64();
        }
        if keep_for_picture(frame, frames, 5) || last {
            shots.push((frame, engine.x.clone()));
        }
        if engine.stopped.is_some() {
            break;
        }
    }
    let mut warnings = ctx.loaded.warnings.clone();
    let fx = &file.scene.effects;
    if fx.gravity.is_some() && fx.handles.is_empty() && fx.ground.is_none() && fx.inertia.is_none()
    {
        warnings.push(
            "gravity without handles, a ground or inertia has no minimiser: the body falls forever"
                .into(),
        );
    }
    let bad: Vec<String> = stats
        .iter()
        .filter(|s| !s.converged)
        .map(|s| format!("frame {}: {}", s.frame, s.statuses.join(", ")))
        .collect();
    if !bad.is_empty() {
        warnings.push(format!(
            "{} frame(s) did not converge: {}",
            bad.len(),
            bad.join("; ")
        ));
    }
    let handles: Vec<Vec<usize>> = engine.handles.iter().map(|h| h.vertices.clone()).collect();
    let terms = term_stats(&engine);
    let mode = if engine.dynamics.is_some() {
        "dynamic"
    } else if engine.interp_steps.is_some() {
        "interpolation"
    } else {
        "quasi_static"
    };
    let final_energy = engine
        .log
        .last()
        .and_then(|l| l.points.last())
        .map_or(f64::NAN, |p| p.energy);
    let mut summary = Summary {
        scene: file.name(),
        scene_file: file.display.clone(),
        mode: mode.to_string(),
        mesh: ctx.mesh_stats(rest_measure),
        energy,
        effects: ctx.effects(),
        terms,
        counters: counters.values(),
        handles: engine
            .handles
            .iter()
            .map(|h| HandleStats {
                name: h.name.clone(),
                vertices: h.vertices.len(),
                keys: h.keys.len(),
            })
            .collect(),
        newton_iterations: stats.iter().map(|s| s.iterations).sum(),
        converged_frames: stats.iter().skip(1).filter(|s| s.converged).count(),
        frames: stats,
        solves: engine.log.clone(),
        stopped: engine.stopped.clone(),
        final_energy,
        setup_seconds,
        newton: Summary::newton_split(&engine.log),
        output_seconds,
        wall_seconds: 0.0,
        outputs: Vec::new(),
        warnings,
    };
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        if ctx.pictures_on() {
            obs.note("drawing pictures");
            let highlight = handle_mask(engine.body.n_vertices(), &handles);
            let view = pictures::View {
                title: &summary.scene,
                size: ctx.image_size(),
                camera: camera(file),
                highlight: &highlight,
                ground: ground_plane(file),
                up: up_direction(file),
            };
            let pic = <Dims as Dim<D>>::picture(&engine.body, &shots, &view);
            o.write("result.png", &pic.to_png())?;
            let plot = pictures::convergence(
                &summary.solves,
                engine.solver.params.tol_abs,
                &summary.scene,
                ctx.image_size(),
            );
            o.write("convergence.png", &plot.to_png())?;
        }
        summary.output_seconds = output_seconds + t.elapsed().as_secs_f64();
    }
    obs.finish();
    let state = <Dims as Dim<D>>::state(&engine.body, engine.x.clone());
    finish(ctx, summary, out, state, handles)
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
            message: e.to_string(),
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

fn handle_mask(n: usize, handles: &[Vec<usize>]) -> Vec<bool> {
    let mut m = vec![false; n];
    for h in handles {
        for &v in h {
            m[v] = true;
        }
    }
    m
}

fn term_stats<const D: usize>(engine: &Engine<D>) -> Vec<TermStats> {
    engine
        .solver
        .terms()
        .iter()
        .map(|t| {
            let timing = engine.timings.iter().find(|a| a.name == t.name());
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

fn camera(file: &SceneFile) -> (f64, f64) {
    match &file.scene.output.camera {
        Some(c) => (c[0], c[1]),
        None => (35.0, 25.0),
    }
}

/// Up for pictures: −gravity, else the ground normal, else +y.
fn up_direction(file: &SceneFile) -> [f64; 3] {
    let fx = &file.scene.effects;
    let pad = |v: &Vec<f64>| [v[0], v[1], v.get(2).copied().unwrap_or(0.0)];
    if let Some(g) = &fx.gravity
        && g.iter().any(|c| *c != 0.0)
    {
        let p = pad(g);
        return [-p[0], -p[1], -p[2]];
    }
    if let Some(n) = fx.ground.as_ref().and_then(|g| g.normal.as_ref()) {
        return pad(n);
    }
    [0.0, 1.0, 0.0]
}

fn ground_plane(file: &SceneFile) -> Option<([f64; 3], f64)> {
    let g = file.scene.effects.ground.as_ref()?;
    let n = match &g.normal {
        Some(v) => [v[0], v[1], v.get(2).copied().unwrap_or(0.0)],
        None => [0.0, 1.0, 0.0],
    };
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    Some((n.map(|c| c / len), g.height))
}
