//! The frame loop of deformation, interpolation and dynamics scenes: build
//! the engine, step the frames (writing every `output.every`-th one), then
//! the summary, the pictures and `summary.json`.

use std::sync::Arc;
use std::time::Instant;

use ecc_runtime::FibreEnergy;

use super::build::{EngineInput, build_engine, frame_count};
use super::context::{Context, RunReport, energy_stats, fibre_stats, finish, term_stats};
use super::engine::Engine;
use super::observer::Observer;
use super::view::{camera, ground_plane, up_direction};
use super::writers::{Dim, Dims, FrameWriter};
use crate::body::Body;
use crate::counters::Counters;
use crate::error::SceneError;
use crate::output::OutputDir;
use crate::pictures;
use crate::summary::{EnergyStats, FrameStats, HandleStats, LinearWork, RunStatus, Summary};

/// Which frames to keep for the picture: up to `keep`, evenly spread, always the last.
fn keep_for_picture(frame: usize, frames: usize, keep: usize) -> bool {
    if frame == frames || frames <= keep {
        return true;
    }
    let stride = frames.div_ceil(keep.max(1));
    frame.is_multiple_of(stride)
}

/// What the loop produced besides the engine's state.
struct Stepped<const D: usize> {
    stats: Vec<FrameStats>,
    shots: Vec<(usize, Vec<[f64; D]>)>,
    output_seconds: f64,
}

/// Run the frames of a body (see the module docs).
pub(crate) fn run_frames<const D: usize>(
    ctx: &Context<'_>,
    body: Body<D>,
    boundary: Vec<usize>,
    rest2: Option<Vec<[f64; D]>>,
    fibre: Option<Arc<dyn FibreEnergy<D>>>,
    out: &mut Option<OutputDir>,
    obs: &mut dyn Observer,
) -> Result<RunReport, SceneError>
where
    Dims: Dim<D>,
{
    let counters = Arc::new(Counters::default());
    let energy = energy_stats::<D>(body.energy.as_ref());
    let fibre_energy = fibre.as_deref().map(fibre_stats::<D>);
    let rest_measure = body.total_rest_measure();
    let writer = <Dims as Dim<D>>::writer(&body);
    let mut engine: Engine<D> = build_engine(EngineInput {
        file: ctx.file,
        body,
        vertex_map: &ctx.loaded.vertex_map,
        boundary,
        rest2,
        counters: counters.clone(),
        fibre,
    })?;
    let setup_seconds = ctx.t0.elapsed().as_secs_f64();
    let stepped = step_frames(ctx, &mut engine, writer.as_ref(), out, obs)?;
    let mut summary = summarize(ctx, &engine, &counters, energy, rest_measure, stepped.stats);
    summary.fibre_energy = fibre_energy;
    summary.setup_seconds = setup_seconds;
    summary.output_seconds = stepped.output_seconds;
    let handles: Vec<Vec<usize>> = engine.handles.iter().map(|h| h.vertices.clone()).collect();
    if let Some(o) = out.as_mut() {
        let t = Instant::now();
        if ctx.pictures_on() {
            obs.note("drawing pictures");
            draw_pictures(ctx, o, &engine, &handles, &stepped.shots, &summary)?;
        }
        summary.output_seconds += t.elapsed().as_secs_f64();
    }
    obs.finish();
    let state = <Dims as Dim<D>>::state(&engine.body, engine.x.clone());
    finish(ctx, summary, out, state, handles)
}

/// Frame 0, then frames 1..=n until the last or a stop.
fn step_frames<const D: usize>(
    ctx: &Context<'_>,
    engine: &mut Engine<D>,
    writer: &dyn FrameWriter<D>,
    out: &mut Option<OutputDir>,
    obs: &mut dyn Observer,
) -> Result<Stepped<D>, SceneError> {
    let file = ctx.file;
    let frames = frame_count(file, &engine.handles);
    let formats = ctx.formats();
    let every = file.scene.output.every.unwrap_or(1);
    let mut output_seconds = 0.0;
    let mut write = |out: &mut Option<OutputDir>, name: &str, x: &[[f64; D]]| {
        if let Some(o) = out.as_mut() {
            let t = Instant::now();
            writer.write(o, name, x, &formats)?;
            output_seconds += t.elapsed().as_secs_f64();
        }
        Ok::<(), SceneError>(())
    };
    let mut stats: Vec<FrameStats> = vec![engine.frame_stats(0)];
    let mut shots = vec![(0, engine.x.clone())];
    write(out, "frame_0000", &engine.x)?;
    obs.start(&file.name(), frames);
    for frame in 1..=frames {
        let s = engine.step_frame(frame, obs);
        obs.frame_done(&s);
        stats.push(s);
        let last = frame == frames || engine.journal.stopped.is_some();
        if frame % every == 0 || last {
            write(out, &format!("frame_{frame:04}"), &engine.x)?;
        }
        if keep_for_picture(frame, frames, 5) || last {
            shots.push((frame, engine.x.clone()));
        }
        if engine.journal.stopped.is_some() {
            break;
        }
    }
    Ok(Stepped {
        stats,
        shots,
        output_seconds,
    })
}

/// The loaded mesh's warnings, gravity without a minimiser, unconverged frames.
fn warnings(ctx: &Context<'_>, stats: &[FrameStats]) -> Vec<String> {
    let mut warnings = ctx.loaded.warnings.clone();
    let fx = &ctx.file.scene.effects;
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
    warnings
}

/// The summary of a frame run (times and outputs are filled in later).
fn summarize<const D: usize>(
    ctx: &Context<'_>,
    engine: &Engine<D>,
    counters: &Counters,
    energy: EnergyStats,
    rest_measure: f64,
    stats: Vec<FrameStats>,
) -> Summary {
    let mode = if engine.dynamics.is_some() {
        "dynamic"
    } else if engine.interp_steps.is_some() {
        "interpolation"
    } else {
        "quasi_static"
    };
    let final_energy = engine
        .journal
        .log
        .last()
        .and_then(|l| l.points.last())
        .map_or(f64::NAN, |p| p.energy);
    Summary {
        scene: ctx.file.name(),
        scene_file: ctx.file.display.clone(),
        mode: mode.to_string(),
        projection: super::build::projection(&ctx.file.scene.solver)
            .name()
            .into(),
        mesh: ctx.mesh_stats(rest_measure),
        energy,
        fibre_energy: None,
        effects: ctx.effects(),
        terms: term_stats(engine.solver.terms(), &engine.journal.timings),
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
        linear: LinearWork::of_run(
            &engine.journal.log,
            engine.solver.linear_system().symbolic_analyses(),
        )
        .with_factor(engine.solver.linear_system()),
        converged_frames: stats.iter().skip(1).filter(|s| s.converged).count(),
        status: RunStatus::of(
            engine.journal.stopped.is_some(),
            stats.iter().skip(1).filter(|s| s.converged).count(),
            stats.len().saturating_sub(1),
        ),
        warnings: warnings(ctx, &stats),
        frames: stats,
        solves: engine.journal.log.clone(),
        stopped: engine.journal.stopped.clone(),
        final_energy,
        setup_seconds: 0.0,
        newton: Summary::newton_split(&engine.journal.log),
        output_seconds: 0.0,
        wall_seconds: 0.0,
        outputs: Vec::new(),
    }
}

/// `result.png` (the kept frames) and `convergence.png`.
fn draw_pictures<const D: usize>(
    ctx: &Context<'_>,
    o: &mut OutputDir,
    engine: &Engine<D>,
    handles: &[Vec<usize>],
    shots: &[(usize, Vec<[f64; D]>)],
    summary: &Summary,
) -> Result<(), SceneError>
where
    Dims: Dim<D>,
{
    let file = ctx.file;
    let highlight = handle_mask(engine.body.n_vertices(), handles);
    let view = pictures::View {
        title: &summary.scene,
        size: ctx.image_size(),
        camera: camera(file),
        highlight: &highlight,
        ground: ground_plane(file),
        up: up_direction(file),
    };
    let fibres = if file.scene.output.draw_fibers.unwrap_or(true) {
        crate::terms::fibre::picture_directions::<D>(file, &engine.body)?
    } else {
        None
    };
    let pic = match fibres.as_deref() {
        Some(dirs) => <Dims as Dim<D>>::picture_fibres(&engine.body, shots, &view, dirs),
        None => <Dims as Dim<D>>::picture(&engine.body, shots, &view),
    };
    o.write("result.png", &pic.to_png())?;
    let plot = pictures::convergence(
        &summary.solves,
        engine.solver.params.tol_abs,
        &summary.scene,
        ctx.image_size(),
    );
    o.write("convergence.png", &plot.to_png())
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
