//! `ecc sim [SCENE.toml]`: run a scene file (see `ecc_scene` for the format).
//!
//! Energies come from the built-in generated library (`energy.name`) or
//! from a `.psi` file evaluated by the interpreter without rebuilding
//! (`energy.psi`); fibre energies likewise (`fibers.energy`: a name of
//! `ecc_energies::fibre_by_name`, or the fibre part of a `.psi`; the fibre
//! part of `energy.psi` goes on the `[fibers]` directions, see
//! `ecc_scene::terms::fibre`). Without a scene file, runs the built-in demo
//! (`ecc demo`).
//! Writes per-frame OBJ/VTK, `result.png`, `convergence.png` and
//! `summary.json` into the output folder; a progress bar shows frames and
//! Newton iterations on stderr (hidden with `--quiet` or when stderr is not
//! a terminal).

use std::path::PathBuf;

use clap::Args;
use ecc_interp::{LoadError, load_fibre_part, load_parts, load_psi};
use ecc_runtime::{Energy, FibreEnergy};
use ecc_scene::energy::{apply_fibre_params, apply_params};
use ecc_scene::{
    BodyEnergy, EnergyError, EnergyRequest, EnergySource, RunOptions, RunStatus, SceneFile,
    run_scene,
};

use crate::error::CliError;
use crate::output::print_stdout;
use crate::progress::Progress;

/// `ecc sim` arguments.
#[derive(Args, Debug, Clone, Default)]
pub struct SimArgs {
    /// The scene file (TOML). Without one, runs the built-in demo scene.
    pub scene: Option<PathBuf>,
    /// Output folder (default: the scene's `output.dir`, else `./ecc-out/<scene name>`).
    #[arg(long, short = 'o', value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Override the number of frames (e.g. a quick preview).
    #[arg(long, value_name = "N")]
    pub frames: Option<usize>,
    /// No progress bar.
    #[arg(long, short = 'q')]
    pub quiet: bool,
    /// Print the terms evaluated (passes and seconds), the counters and the time split.
    #[arg(long)]
    pub stats: bool,
    /// Print the JSON summary on standard output.
    #[arg(long)]
    pub json: bool,
    /// Do not draw result.png and convergence.png.
    #[arg(long)]
    pub no_pictures: bool,
    /// Exit 0 even when some frames did not converge (by default such a
    /// run writes all its files and exits 3).
    #[arg(long)]
    pub allow_unconverged: bool,
}

/// Energies for scenes: the generated library and the `.psi` interpreter.
pub struct CliEnergies;

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

impl CliEnergies {
    fn by_name<const D: usize>(req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<D>>, EnergyError> {
        let name = req.name.unwrap_or_default();
        let mut e = match ecc_energies::by_name::<D>(name) {
            Some(e) => e,
            None => {
                return Err(match ecc_energies::entry(name) {
                    Some(entry) => EnergyError::Dimension(format!(
                        "`{}` has no {D}D version (it exists in {})",
                        entry.name,
                        if entry.d2 { "2D" } else { "3D" }
                    )),
                    None => EnergyError::UnknownName {
                        name: name.to_string(),
                        known: ecc_energies::names()
                            .iter()
                            .map(|s| s.to_string())
                            .collect(),
                    },
                });
            }
        };
        apply_params(e.as_mut(), req.params)?;
        Ok(e)
    }

    /// The body's energy: a `.psi` file's two parts, or a library energy.
    fn body<const D: usize>(req: &EnergyRequest<'_>) -> Result<BodyEnergy<D>, EnergyError> {
        let Some(p) = req.psi else {
            return Self::by_name::<D>(req).map(BodyEnergy::isotropic);
        };
        let parts = load_parts::<D>(p, req.params).map_err(load_error)?;
        Ok(BodyEnergy {
            energy: Box::new(parts.iso),
            fibre: parts.fibre.map(|f| Box::new(f) as Box<dyn FibreEnergy<D>>),
        })
    }

    /// A fibre energy: the fibre part of a `.psi` file, or a library one by name.
    fn fibre<const D: usize>(
        req: &EnergyRequest<'_>,
    ) -> Result<Box<dyn FibreEnergy<D>>, EnergyError> {
        if let Some(p) = req.psi {
            let f = load_fibre_part::<D>(p, req.params).map_err(load_error)?;
            return Ok(Box::new(f));
        }
        let name = req.name.unwrap_or_default();
        let mut e =
            ecc_energies::fibre_by_name::<D>(name).ok_or_else(|| {
                match ecc_energies::entry(name) {
                    Some(entry) if !entry.fibre => EnergyError::File(format!(
                        "`{}` is an isotropic energy, not a fibre energy ψ(I4, I5) (it belongs in \
                     [energy])",
                        entry.name
                    )),
                    _ => EnergyError::UnknownName {
                        name: name.to_string(),
                        known: fibre_names(),
                    },
                }
            })?;
        apply_fibre_params(e.as_mut(), req.params)?;
        Ok(e)
    }
}

/// The library's fibre energy names.
fn fibre_names() -> Vec<String> {
    ecc_energies::fibre_names()
        .iter()
        .map(|s| s.to_string())
        .collect()
}

impl EnergySource for CliEnergies {
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError> {
        match req.psi {
            Some(p) => load_psi::<2>(p, req.params).map_err(load_error),
            None => Self::by_name::<2>(req),
        }
    }

    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError> {
        match req.psi {
            Some(p) => load_psi::<3>(p, req.params).map_err(load_error),
            None => Self::by_name::<3>(req),
        }
    }

    fn names(&self) -> Vec<String> {
        ecc_energies::names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    fn body2(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<2>, EnergyError> {
        Self::body::<2>(req)
    }

    fn body3(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<3>, EnergyError> {
        Self::body::<3>(req)
    }

    fn fibre2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<2>>, EnergyError> {
        Self::fibre::<2>(req)
    }

    fn fibre3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<3>>, EnergyError> {
        Self::fibre::<3>(req)
    }

    fn fibre_names(&self) -> Vec<String> {
        fibre_names()
    }
}

/// Run a parsed scene with the CLI's options.
pub fn run_file(mut file: SceneFile, args: &SimArgs) -> Result<(), CliError> {
    if let Some(n) = args.frames {
        if n == 0 {
            return Err(CliError::Usage("--frames must be at least 1".into()));
        }
        file.scene.frames = Some(n);
    }
    let opts = RunOptions {
        out_dir: args.out.clone(),
        dry_run: false,
        pictures: args.no_pictures.then_some(false),
    };
    let mut progress = Progress::new(args.quiet);
    let report = run_scene(&file, &CliEnergies, &opts, &mut progress)?;
    let s = &report.summary;
    if args.json {
        let json = serde_json::to_string_pretty(s)?;
        print_stdout(&json)?;
    } else {
        let frames = s.frames.len().saturating_sub(1);
        let mut text = format!(
            "{}: {} frame(s), {} Newton iterations, {}/{} frames converged, {:.2} s",
            s.scene, frames, s.newton_iterations, s.converged_frames, frames, s.wall_seconds
        );
        if let Some(dir) = &report.out_dir {
            text += &format!("\nwrote {} files to {}", s.outputs.len(), dir.display());
        }
        print_stdout(&text)?;
    }
    if args.stats {
        eprint!("{}", s.stats_table());
    }
    for w in &s.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(why) = &s.stopped {
        return Err(CliError::Stopped { why: why.clone() });
    }
    if s.status == RunStatus::Unconverged && !args.allow_unconverged {
        return Err(CliError::Unconverged {
            frames: s.frames.len().saturating_sub(1) - s.converged_frames,
            total: s.frames.len().saturating_sub(1),
        });
    }
    Ok(())
}

/// `ecc sim SCENE.toml` (without a scene, `main` runs the demo instead).
pub fn run(path: &std::path::Path, args: &SimArgs) -> Result<(), CliError> {
    run_file(SceneFile::read(path)?, args)
}
