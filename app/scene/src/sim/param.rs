//! Surface parameterisation scenes (Smith et al. 2019 §6.1): minimise
//! Σ_q |q| Ψ(J_q) over uv for a disk-topology surface with the library's
//! [`ecc_fem::param`] (isometric rest frames, unit total area, mean energy,
//! Tutte start rescaled to the same area, projected Newton with no fixed
//! vertex). This module only adds the scene's side: frame 0 is the Tutte
//! start, frame 1 the result; the per-iteration callback feeds the progress
//! observer and the convergence plot; then the summary and pictures.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::param::{ParamOptions, ParamProblem, Parameterization, prepare};
use ecc_fem::quality::tri_signed_area;
use ecc_fem::{FemError, NewtonResult, NewtonStatus, Term};
use ecc_mesh::{TriMesh, TutteWeights};
use ecc_runtime::Energy;

use super::build::{param_newton_params, projection};
use super::context::{Context, FinalState, RunReport, energy_stats, finish, term_stats};
use super::journal::status_name;
use super::observer::{INTERRUPTED, Observer};
use crate::counters::Counters;
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::pictures;
use crate::spec::{FrameFormat, TutteKind};
use crate::summary::{FrameStats, LinearWork, RunStatus, SolveLog, SolvePoint, Summary};

fn write_uv_frame(
    out: &mut OutputDir,
    name: &str,
    mesh: &TriMesh,
    uv: &[[f64; 2]],
    formats: &[FrameFormat],
) -> Result<(), SceneError> {
    let mut m = mesh.clone();
    m.uvs = Some(uv.to_vec());
    for f in formats {
        match f {
            FrameFormat::Obj => out.obj(&format!("{name}.obj"), &m)?,
            FrameFormat::Vtk => {
                let flat: Vec<f64> = uv.iter().flat_map(|p| [p[0], p[1]]).collect();
                m.uvs = None;
                out.vtk_tri(&format!("{name}.vtk"), &m, &[("uv", &flat, 2)])?
            }
        }
    }
    Ok(())
}

/// Energy and orientation of a uv layout.
fn stats(frame: usize, elastic: &dyn Term<2>, uv: &[[f64; 2]], tris: &[[usize; 3]]) -> FrameStats {
    let e: f64 = (0..elastic.n_stencils())
        .map(|s| elastic.value(s, uv))
        .sum();
    let areas: Vec<f64> = tris.iter().map(|&t| tri_signed_area(uv, t)).collect();
    FrameStats {
        frame,
        time: None,
        t: None,
        solves: 0,
        iterations: 0,
        statuses: Vec::new(),
        converged: true,
        grad_inf: f64::NAN,
        elastic_energy: e,
        gravity_potential: None,
        contact_energy: None,
        kinetic_energy: None,
        total_energy: e,
        min_measure: areas.iter().copied().fold(f64::INFINITY, f64::min),
        inverted: areas.iter().filter(|a| !(**a > 0.0)).count(),
        min_ground_distance: None,
        handle_error: None,
        seconds: 0.0,
    }
}

/// The library's problem for the scene: `[solver]`, the Tutte weights; a
/// surface that cannot be parameterised is an error of the mesh key.
fn problem(
    ctx: &Context<'_>,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
) -> Result<ParamProblem, SceneError> {
    let scene = &ctx.file.scene;
    let opts = ParamOptions {
        normalize_area: true,
        mean_energy: true,
        tutte: match scene.effects.parameterize.as_ref().map(|p| p.tutte) {
            Some(TutteKind::MeanValue) => TutteWeights::MeanValue,
            _ => TutteWeights::Uniform,
        },
        newton: param_newton_params(&scene.solver, 1.0),
        projection: projection(&scene.solver),
    };
    let key = if scene.mesh.file.is_some() {
        "mesh.file"
    } else {
        "mesh"
    };
    prepare(mesh, energy, &opts).map_err(|e| match e {
        FemError::Tutte(e) => {
            SceneError::invalid(key, format!("cannot parameterise this mesh: {e}"))
        }
        FemError::TutteArea(a) => SceneError::invalid(
            key,
            format!("cannot parameterise this mesh: the Tutte start has total signed area {a}"),
        ),
        e => SceneError::setup("the parameterisation", e),
    })
}

/// Solve, logging every accepted step for the plot (each record at the
/// time its step began) and the observer.
fn solve(
    problem: &mut ParamProblem,
    obs: &mut dyn Observer,
) -> Result<(Parameterization, SolveLog), SceneError> {
    let clock = Instant::now();
    let mut points = Vec::new();
    let mut began = 0.0;
    let p = problem
        .solve_with(|rec, _| {
            points.push(SolvePoint {
                grad_inf: rec.grad_inf,
                energy: rec.energy,
                seconds: began,
            });
            began = clock.elapsed().as_secs_f64();
            obs.iteration(1, rec)
        })
        .map_err(|e| SceneError::setup("the parameterisation", e))?;
    let r = &p.result;
    points.push(SolvePoint {
        grad_inf: r.grad_inf,
        energy: r.energy,
        seconds: began,
    });
    let log = SolveLog {
        frame: 1,
        status: status_name(&r.status),
        iterations: r.iterations,
        points,
        times: r.times,
        linear: LinearWork::of_solve(r),
    };
    Ok((p, log))
}

/// Frame 1's statistics from the solve.
fn result_stats(
    problem: &ParamProblem,
    r: &NewtonResult,
    uv: &[[f64; 2]],
    log: &SolveLog,
    seconds: f64,
) -> FrameStats {
    let mut f1 = stats(
        1,
        problem.solver.terms()[0].as_ref(),
        uv,
        &problem.triangles,
    );
    f1.solves = 1;
    f1.iterations = r.iterations;
    f1.statuses = vec![log.status.clone()];
    f1.converged = r.converged();
    f1.grad_inf = r.grad_inf;
    f1.seconds = seconds;
    f1
}

/// Run a parameterisation scene.
pub(crate) fn run_parameterization(
    ctx: &Context<'_>,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
    out: &mut Option<OutputDir>,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError> {
    let file = ctx.file;
    let estats = energy_stats::<2>(energy.as_ref());
    let mut problem = problem(ctx, mesh, energy)?;
    let setup_seconds = ctx.t0.elapsed().as_secs_f64();
    let formats = ctx.formats();
    let mut output_seconds = 0.0;
    let mut write = |out: &mut Option<OutputDir>, name: &str, uv: &[[f64; 2]]| {
        if let Some(o) = out.as_mut() {
            let t = Instant::now();
            write_uv_frame(o, name, mesh, uv, &formats)?;
            output_seconds += t.elapsed().as_secs_f64();
        }
        Ok::<(), SceneError>(())
    };
    write(out, "frame_0000", &problem.start)?;
    let f0 = stats(
        0,
        problem.solver.terms()[0].as_ref(),
        &problem.start,
        &problem.triangles,
    );

    obs.start(&file.name(), 1);
    let t_solve = Instant::now();
    let (p, log) = solve(&mut problem, obs)?;
    let f1 = result_stats(
        &problem,
        &p.result,
        &p.uv,
        &log,
        t_solve.elapsed().as_secs_f64(),
    );
    obs.frame_done(&f1);
    write(out, "frame_0001", &p.uv)?;

    let r = &p.result;
    let stopped = (r.status == NewtonStatus::Interrupted).then(|| INTERRUPTED.to_string());
    let mut warnings = ctx.loaded.warnings.clone();
    if !r.converged() {
        warnings.push(format!("the solve stopped with {}", log.status));
    }
    let mut summary = Summary {
        scene: file.name(),
        scene_file: file.display.clone(),
        mode: "parameterization".into(),
        projection: projection(&file.scene.solver).name().into(),
        mesh: ctx.mesh_stats(problem.input_area),
        energy: estats,
        fibre_energy: None,
        effects: ctx.effects(),
        terms: term_stats(problem.solver.terms(), &r.terms),
        counters: Counters::default().values(),
        handles: Vec::new(),
        newton_iterations: r.iterations,
        linear: LinearWork::of_run(std::slice::from_ref(&log), r.symbolic_analyses)
            .with_factor(problem.solver.linear_system()),
        converged_frames: usize::from(r.converged()),
        frames: vec![f0, f1],
        solves: vec![log],
        status: RunStatus::of(stopped.is_some(), usize::from(r.converged()), 1),
        stopped,
        final_energy: r.energy,
        setup_seconds,
        newton: r.times,
        output_seconds,
        wall_seconds: 0.0,
        outputs: Vec::new(),
        warnings,
    };
    let mut scaled = mesh.clone();
    for q in &mut scaled.positions {
        *q = q.map(|c| c * problem.position_scale);
    }
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        if ctx.pictures_on() {
            obs.note("drawing pictures");
            let size = ctx.image_size();
            let pic =
                pictures::parameterization(&scaled, &problem.start, &p.uv, &summary.scene, size);
            o.write("result.png", &pic.to_png())?;
            let tol = problem.solver.params.tol_abs;
            let plot = pictures::convergence(&summary.solves, tol, &summary.scene, size);
            o.write("convergence.png", &plot.to_png())?;
        }
        summary.output_seconds += t.elapsed().as_secs_f64();
    }
    obs.finish();
    let state = FinalState::Param {
        mesh: scaled,
        uv: p.uv,
    };
    finish(ctx, summary, out, state, Vec::new())
}
