//! # ecc-scene: scenes, effects, dynamics and pictures
//!
//! A scene file (TOML) says what to simulate; ecc builds an objective out
//! of exactly those effects — no mass matrix without inertia, no contact
//! evaluation without a ground, no gravity term without gravity — and
//! minimises it frame by frame with the projected Newton solver of
//! `ecc-fem` (Smith, de Goes & Kim 2019, Algorithm 1). This is how the
//! paper's applications (§6) reach users:
//!
//! | application | scene | paper |
//! |---|---|---|
//! | surface parameterisation (2D energy, Tutte start) | `[effects.parameterize]` | §6.1 |
//! | volume deformation with keyframed handles | `[[effects.handles]]` | §6.2 |
//! | shape interpolation Ψt = (1−t)Ψ₁ + tΨ₂ | `[effects.interpolate]` | §6.3 |
//! | dynamics (implicit Euler / BDF2), damping, ground | `[effects.inertia]`, `damping`, `ground` | §6.5 |
//!
//! ## A scene file
//!
//! ```toml
//! name = "twist"
//! frames = 24                       # output frames after the initial one
//!
//! [mesh]
//! generate = "bar"                  # or file = "hand.mesh" / "data:hand.mesh"
//! resolution = 3
//!
//! [energy]
//! name = "snh"                      # a built-in energy, or psi = "my.psi"
//! params = { mu = 1.0, lambda = 10.0 }
//!
//! [effects]
//! density = 1.0
//! gravity = [0.0, -9.81, 0.0]
//! inertia = { dt = 0.01, integrator = "bdf2", mass = "lumped" }
//! damping = { alpha = 0.0, beta = 0.01 }
//! ground = { height = -1.0, kind = "barrier" }
//!
//! [[effects.handles]]
//! box = { min = [-2.1, -1, -1], max = [-1.9, 1, 1] }   # or ids = [..] / plane = {..}
//!
//! [[effects.handles]]
//! plane = { point = [1.9, 0, 0], normal = [1, 0, 0] }
//! keys = [ { frame = 24, rotate = [360, 0, 0], translate = [-0.5, 0, 0] } ]
//!
//! [solver]
//! tol = 1e-4                       # on ‖∇E‖∞ of E/Σ|q|
//! filter = "clamp"                 # clamp | abs | adaptive
//!
//! [output]
//! formats = ["obj", "vtk"]
//! ```
//!
//! Every table rejects unknown keys; errors name the file, line, column
//! and key ("scene.toml:12:1: unknown key `gravty` in \[effects\]; did you
//! mean `gravity`?"). Paths are relative to the scene file; `data:NAME`
//! refers to the public mesh folder (`$ECC_DATA_DIR`, default
//! the repository's `data/`). See [`spec`] for every key and [`spec::validate`]
//! for the checks.
//!
//! ## Terms
//!
//! Each effect is an `ecc_fem::Term` ([`terms`]), with its maths in its doc
//! comment: [`terms::Gravity`], [`terms::MassQuadratic`] (inertia and α M
//! damping), [`terms::StiffnessDamping`] (β K damping with K the projected
//! Hessian at the start of the step), [`terms::Ground`] (IPC log-barrier or
//! penalty, with an exact step bound), [`terms::Blend`] (interpolation).
//! Handles are exact Dirichlet constraints ([`handles`]). The time
//! integrators are incremental potentials ([`dynamics`]). Per-run
//! [`Counters`] prove what ran; `summary.json` lists the terms with their
//! passes and times.
//!
//! ## Running
//!
//! ```no_run
//! use ecc_scene::{RunOptions, RuntimeEnergies, SceneFile, Silent, run_scene};
//! let file = SceneFile::read("scenes/demo.toml")?;
//! let report = run_scene(&file, &RuntimeEnergies, &RunOptions::default(), &mut Silent)?;
//! println!("{}", report.summary.stats_table());
//! # Ok::<(), ecc_scene::SceneError>(())
//! ```
//!
//! Energies come from an injected [`EnergySource`] (this crate must not
//! depend on the compiler crates): the `ecc` CLI passes one over the
//! built-in generated energies and the `.psi` interpreter;
//! [`RuntimeEnergies`] serves the runtime's hand-written ARAP, symmetric
//! Dirichlet and Stable Neo-Hookean.
//!
//! Outputs (in `ecc-out/<name>/` by default): `frame_NNNN.obj|vtk` per
//! frame, `result.png`, `convergence.png` and `summary.json`, each written
//! atomically; the folder is checked for writability before any work.

// Index loops mirror the maths (node a, coordinate c) more clearly than iterators.
#![allow(clippy::needless_range_loop)]
// `!(x > 0.0)` deliberately counts NaN as "not positive".
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod body;
pub mod counters;
pub mod dynamics;
pub mod energy;
pub mod error;
pub mod handles;
pub mod output;
pub mod pictures;
pub mod setup;
pub mod sim;
pub mod spec;
pub mod summary;
pub mod terms;

pub use body::Body;
pub use counters::{Counter, CounterValues, Counters};
pub use energy::{BodyEnergy, EnergyError, EnergyRequest, EnergySource, RuntimeEnergies};
pub use error::{Location, OutputFailure, SceneError, WriteFailure};
pub use sim::{FinalState, FrameLines, Observer, RunOptions, RunReport, Silent, run_scene};
pub use spec::{Scene, SceneFile};
pub use summary::{RunStatus, Summary};
