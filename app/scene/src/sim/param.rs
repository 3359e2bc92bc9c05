//! Surface parameterisation (Smith et al. 2019 §6.1): minimise
//! Σ_q |q| Ψ(J_q) over uv for a disk-topology surface.
//!
//! Each triangle is expressed in its own isometric 2D rest frame, the
//! surface is scaled to unit total area (energies such as symmetric
//! Dirichlet are not scale invariant; with unit area the objective is the
//! area-weighted mean, 2 for an isometry under SD), the start is a Tutte
//! embedding (uniform or mean-value weights, boundary on a circle, bijective)
//! rescaled to the same area, and projected Newton runs with no fixed
//! vertex (the solver's diagonal shift handles the translation null space).
//! Frame 0 is the Tutte start, frame 1 the result.

use std::sync::Arc;
use std::time::Instant;

use ecc_fem::{Elastic, NewtonSolver, Term, Tri};
use ecc_mesh::{TriMesh, TutteWeights, tutte_embedding};
use ecc_runtime::Energy;

use super::build::newton_params;
use super::engine::status_name;
use super::observer::Observer;
use super::run::{Context, FinalState, RunReport, energy_stats, finish};
use crate::counters::Counters;
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::pictures;
use crate::spec::{FrameFormat, TutteKind};
use crate::summary::{FrameStats, SolveLog, SolvePoint, Summary, TermStats};

fn signed_area(uv: &[[f64; 2]], t: &[usize; 3]) -> f64 {
    let (a, b, c) = (uv[t[0]], uv[t[1]], uv[t[2]]);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

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

fn stats(frame: usize, elastic: &dyn Term<2>, uv: &[[f64; 2]], tris: &[[usize; 3]]) -> FrameStats {
    let e: f64 = (0..elastic.n_stencils())
        .map(|s| elastic.value(s, uv))
        .sum();
    let areas: Vec<f64> = tris.iter().map(|t| signed_area(uv, t)).collect();
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

/// Run a parameterisation scene.
pub(crate) fn run_parameterization(
    ctx: &Context<'_>,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
    out: &mut Option<OutputDir>,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError> {
    let file = ctx.file;
    let setup = |e: ecc_fem::FemError| SceneError::setup("the parameterisation", e);
    let e0 =
        Elastic::<dyn Energy<2>, Tri>::surface(energy.clone(), &mesh.positions, &mesh.triangles)
            .map_err(setup)?;
    let scale = 1.0 / e0.total_measure().sqrt();
    let mut scaled = mesh.clone();
    for p in &mut scaled.positions {
        *p = p.map(|c| c * scale);
    }
    let elastic =
        Elastic::<dyn Energy<2>, Tri>::surface(energy.clone(), &scaled.positions, &mesh.triangles)
            .map_err(setup)?
            .named("elastic");
    let area = elastic.total_measure();
    let params = newton_params(&file.scene.solver, 1.0 / area);
    let tol = params.tol_abs;
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(elastic)];
    let n = mesh.positions.len();
    let mut solver = NewtonSolver::new(n, terms, &[], params).map_err(setup)?;

    let weights = match file.scene.effects.parameterize.as_ref().map(|p| p.tutte) {
        Some(TutteKind::MeanValue) => TutteWeights::MeanValue,
        _ => TutteWeights::Uniform,
    };
    let key = if file.scene.mesh.file.is_some() {
        "mesh.file"
    } else {
        "mesh"
    };
    let mut uv = tutte_embedding(mesh, weights)
        .map_err(|e| SceneError::invalid(key, format!("cannot parameterise this mesh: {e}")))?;
    let uv_area: f64 = mesh.triangles.iter().map(|t| signed_area(&uv, t)).sum();
    let s = (area / uv_area).sqrt();
    for p in &mut uv {
        *p = [p[0] * s, p[1] * s];
    }
    let setup_seconds = ctx.t0.elapsed().as_secs_f64();
    let formats = ctx.formats();
    let mut output_seconds = 0.0;
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        write_uv_frame(o, "frame_0000", mesh, &uv, &formats)?;
        output_seconds += t.elapsed().as_secs_f64();
    }
    let tris = mesh.triangles.clone();
    let mut frames = vec![stats(0, solver.terms()[0].as_ref(), &uv, &tris)];
    let start = uv.clone();

    obs.start(&file.name(), 1);
    let clock = Instant::now();
    let t_solve = Instant::now();
    let mut points = Vec::new();
    // each record is plotted at the time its step began
    let mut began = 0.0;
    let result = solver
        .solve_with(&mut uv, |rec, _| {
            points.push(SolvePoint {
                grad_inf: rec.grad_inf,
                energy: rec.energy,
                seconds: began,
            });
            began = clock.elapsed().as_secs_f64();
            obs.iteration(1, rec);
            std::ops::ControlFlow::Continue(())
        })
        .map_err(setup)?;
    points.push(SolvePoint {
        grad_inf: result.grad_inf,
        energy: result.energy,
        seconds: began,
    });
    let log = SolveLog {
        frame: 1,
        status: status_name(&result.status),
        iterations: result.iterations,
        points,
        times: result.times,
    };
    let mut f1 = stats(1, solver.terms()[0].as_ref(), &uv, &tris);
    f1.solves = 1;
    f1.iterations = result.iterations;
    f1.statuses = vec![log.status.clone()];
    f1.converged = result.converged();
    f1.grad_inf = result.grad_inf;
    f1.seconds = t_solve.elapsed().as_secs_f64();
    obs.frame_done(&f1);
    frames.push(f1);
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        write_uv_frame(o, "frame_0001", mesh, &uv, &formats)?;
        output_seconds += t.elapsed().as_secs_f64();
    }

    let t = &result.terms;
    let terms = solver
        .terms()
        .iter()
        .map(|term| {
            let timing = t.iter().find(|a| a.name == term.name());
            TermStats {
                name: term.name().to_string(),
                stencils: term.n_stencils(),
                value_passes: timing.map_or(0, |a| a.value_passes),
                assembly_passes: timing.map_or(0, |a| a.assembly_passes),
                seconds: timing.map_or(0.0, |a| a.value_seconds + a.assembly_seconds),
            }
        })
        .collect();
    let mut warnings = ctx.loaded.warnings.clone();
    if !result.converged() {
        warnings.push(format!("the solve stopped with {}", log.status));
    }
    let mut summary = Summary {
        scene: file.name(),
        scene_file: file.display.clone(),
        mode: "parameterization".into(),
        mesh: ctx.mesh_stats(e0.total_measure()),
        energy: energy_stats::<2>(energy.as_ref()),
        effects: ctx.effects(),
        terms,
        counters: Counters::default().values(),
        handles: Vec::new(),
        newton_iterations: result.iterations,
        converged_frames: usize::from(result.converged()),
        frames,
        solves: vec![log],
        stopped: None,
        final_energy: result.energy,
        setup_seconds,
        newton: result.times,
        output_seconds,
        wall_seconds: 0.0,
        outputs: Vec::new(),
        warnings,
    };
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        if ctx.pictures_on() {
            obs.note("drawing pictures");
            let pic =
                pictures::parameterization(&scaled, &start, &uv, &summary.scene, ctx.image_size());
            o.write("result.png", &pic.to_png())?;
            let plot =
                pictures::convergence(&summary.solves, tol, &summary.scene, ctx.image_size());
            o.write("convergence.png", &plot.to_png())?;
        }
        summary.output_seconds += t.elapsed().as_secs_f64();
    }
    obs.finish();
    finish(
        ctx,
        summary,
        out,
        FinalState::Param { mesh: scaled, uv },
        Vec::new(),
    )
}
