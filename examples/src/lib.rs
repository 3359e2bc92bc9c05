//! # ecc-examples: the paper's applications as runnable scenes
//!
//! Each example is a scene file in `scenes/` (runnable as
//! `ecc sim scenes/<name>.toml`) plus a library function here that runs it
//! at a chosen [`Size`] and returns the [`RunReport`] (summary, final
//! positions, handles), a small `main` in `examples/examples/<name>.rs`,
//! and a test in `examples/tests/` that runs it at [`Size::Reduced`] and
//! checks the physics:
//!
//! | example | scene | paper | the test asserts |
//! |---|---|---|---|
//! | [`camelhead_sd`] | parameterise `camelhead.off` with symmetric Dirichlet | §6.1 | energy decreases from the Tutte start, SD ≥ 2, no flipped triangle |
//! | [`hand`] (`arap`, `snh`) | pin the wrist of `hand.mesh`, turn the fingertips | §6.2 | handles reached exactly, energy grows with the motion, no inverted tet |
//! | [`bar_interpolation`] | symmetric ARAP between a straight and a twisted, bent bar | §6.3 | no inverted tet (barrier), E = 0 at t = 0 and 1, E > 0 between |
//! | [`falling_bar`] | Stable Neo-Hookean bar dropped on a barrier ground | §6.5 | nothing below the ground, it falls then rests, total energy never grows |
//!
//! Energies come from the generated library (`ecc-energies`) through
//! [`GeneratedEnergies`]. Meshes are read from `$ECC_DATA_DIR` (default: the
//! repository's `data/`).
//!
//! ```no_run
//! use ecc_examples::{Size, falling_bar, Output};
//! let report = falling_bar(Size::Full, &Output::Folder("ecc-out/falling_bar".into()))?;
//! println!("{}", report.summary.stats_table());
//! # Ok::<(), ecc_scene::SceneError>(())
//! ```

use std::path::PathBuf;

use ecc_runtime::Energy;
use ecc_scene::energy::apply_params;
use ecc_scene::spec::{BoxSelect, HandleSpec, KeySpec};
use ecc_scene::{
    EnergyError, EnergyRequest, EnergySource, FrameLines, RunOptions, RunReport, SceneError,
    SceneFile, Silent, run_scene,
};

/// How big a run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Size {
    /// The scene as written in `scenes/` (the paper's setting).
    Full,
    /// A few seconds in the dev profile: a patch, a finger, a coarse bar.
    Reduced,
}

/// Where results go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Output {
    /// Nothing is written (tests).
    Nowhere,
    /// Frames, pictures and `summary.json` in this folder, a progress line per frame on stderr.
    Folder(PathBuf),
}

/// The generated energies (`ecc_energies::by_name::<D>`) as an [`EnergySource`].
#[derive(Clone, Copy, Debug, Default)]
pub struct GeneratedEnergies;

impl GeneratedEnergies {
    fn get<const D: usize>(req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<D>>, EnergyError> {
        if let Some(p) = req.psi {
            return Err(EnergyError::File(format!(
                "`{}`: the examples use the built-in energies (run .psi files with `ecc sim`)",
                p.display()
            )));
        }
        let name = req.name.unwrap_or_default();
        let mut e = ecc_energies::by_name::<D>(name).ok_or_else(|| EnergyError::UnknownName {
            name: name.to_string(),
            known: ecc_energies::names()
                .iter()
                .map(|s| s.to_string())
                .collect(),
        })?;
        apply_params(e.as_mut(), req.params)?;
        Ok(e)
    }
}

impl EnergySource for GeneratedEnergies {
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError> {
        Self::get::<2>(req)
    }

    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError> {
        Self::get::<3>(req)
    }

    fn names(&self) -> Vec<String> {
        ecc_energies::names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
}

/// The repository's `scenes/` folder.
pub fn scenes_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"))
}

/// Read `scenes/<name>.toml`.
pub fn scene(name: &str) -> Result<SceneFile, SceneError> {
    SceneFile::read(scenes_dir().join(format!("{name}.toml")))
}

/// Run a scene with the generated energies.
pub fn run(file: &SceneFile, out: &Output) -> Result<RunReport, SceneError> {
    match out {
        Output::Nowhere => {
            let opts = RunOptions {
                dry_run: true,
                ..Default::default()
            };
            run_scene(file, &GeneratedEnergies, &opts, &mut Silent)
        }
        Output::Folder(dir) => {
            let opts = RunOptions {
                out_dir: Some(dir.clone()),
                ..Default::default()
            };
            run_scene(file, &GeneratedEnergies, &opts, &mut FrameLines::default())
        }
    }
}

fn bbox(min: [f64; 3], max: [f64; 3]) -> BoxSelect {
    BoxSelect {
        min: min.to_vec(),
        max: max.to_vec(),
    }
}

/// §6.1: parameterise `camelhead.off` with symmetric Dirichlet from a Tutte
/// start. Reduced: the 20 % of the surface with the largest x (3.3k
/// triangles, still a disk).
pub fn camelhead_sd(size: Size, out: &Output) -> Result<RunReport, SceneError> {
    let mut f = scene("camelhead_sd")?;
    if size == Size::Reduced {
        // camelhead spans x ∈ [−0.262, 0.262]
        f.scene.mesh.crop = Some(bbox([0.157, -1.0, -1.0], [1.0, 1.0, 1.0]));
        f.scene.name = Some("camelhead_sd_reduced".into());
    }
    run(&f, out)
}

/// §6.2: pin the wrist of `hand.mesh` and turn the fingertips towards the
/// palm, with `energy` = `"arap"` or `"snh"` (scenes `hand_arap` /
/// `hand_snh`). Reduced: the middle finger only (2k tets), its base pinned
/// and its tip turned, over 2 frames.
pub fn hand(energy: &str, size: Size, out: &Output) -> Result<RunReport, SceneError> {
    let mut f = scene(&format!("hand_{energy}"))?;
    if size == Size::Reduced {
        let s = &mut f.scene;
        s.name = Some(format!("hand_{energy}_reduced"));
        s.frames = Some(2);
        s.mesh.crop = Some(bbox([-0.2, 0.25, -1.0], [0.02, 1.0, 1.0]));
        s.effects.handles = vec![
            HandleSpec {
                name: Some("base".into()),
                bbox: Some(bbox([-1.0, -1.0, -1.0], [1.0, 0.3, 1.0])),
                ..Default::default()
            },
            HandleSpec {
                name: Some("tip".into()),
                bbox: Some(bbox([-1.0, 0.62, -1.0], [1.0, 1.0, 1.0])),
                center: Some(vec![-0.09, 0.45, 0.0]),
                keys: vec![KeySpec {
                    frame: 2.0,
                    rotate: Some(vec![-50.0, 0.0, 0.0]),
                    translate: Some(vec![0.0, -0.05, 0.0]),
                }],
                ..Default::default()
            },
        ];
    }
    run(&f, out)
}

/// §6.3: interpolate between a straight bar and a twisted, bent copy with
/// symmetric ARAP. Reduced: resolution 1 (24 tets), 4 steps.
pub fn bar_interpolation(size: Size, out: &Output) -> Result<RunReport, SceneError> {
    let mut f = scene("bar_interpolation")?;
    if size == Size::Reduced {
        f.scene.name = Some("bar_interpolation_reduced".into());
        f.scene.mesh.resolution = Some(1);
        if let Some(i) = f.scene.effects.interpolate.as_mut() {
            i.steps = Some(4);
        }
    }
    run(&f, out)
}

/// §6.5: a Stable Neo-Hookean bar dropped at an angle onto a barrier
/// ground (BDF2, lumped mass, Rayleigh damping). Reduced: resolution 1,
/// 40 frames.
pub fn falling_bar(size: Size, out: &Output) -> Result<RunReport, SceneError> {
    let mut f = scene("falling_bar")?;
    if size == Size::Reduced {
        f.scene.name = Some("falling_bar_reduced".into());
        f.scene.mesh.resolution = Some(1);
        f.scene.frames = Some(40);
    }
    run(&f, out)
}

/// Parse the command line of the example binaries: `[--reduced] [OUT_DIR]`
/// (default `ecc-out/<name>`).
pub fn cli_args(name: &str) -> (Size, Output) {
    let mut size = Size::Full;
    let mut dir = PathBuf::from("ecc-out").join(name);
    for a in std::env::args().skip(1) {
        if a == "--reduced" {
            size = Size::Reduced;
        } else {
            dir = PathBuf::from(a);
        }
    }
    (size, Output::Folder(dir))
}

/// Print a run's outcome (the example binaries' epilogue); exits 1 on error.
pub fn report(result: Result<RunReport, SceneError>) {
    match result {
        Ok(r) => {
            let s = &r.summary;
            println!(
                "{}: {} frame(s), {} Newton iterations, {} s",
                s.scene,
                s.frames.len().saturating_sub(1),
                s.newton_iterations,
                s.wall_seconds
            );
            print!("{}", s.stats_table());
            if let Some(d) = r.out_dir {
                println!("wrote {}", d.display());
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
