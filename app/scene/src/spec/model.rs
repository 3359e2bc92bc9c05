//! The scene file's data model (serde, unknown keys rejected everywhere).
//!
//! Vectors are plain arrays whose length must match the mesh dimension
//! (2 for planar triangle meshes, 3 for tet meshes); this is checked by
//! [`super::validate`], which also checks every value's range.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A whole scene: what to simulate and what to write.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// A label for reports (default: the scene file's stem).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Number of output frames after the initial one (default: the last
    /// handle key frame, the interpolation steps, or 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frames: Option<usize>,
    /// The body.
    pub mesh: MeshSpec,
    /// The material / distortion energy.
    pub energy: EnergySpec,
    /// A fibre term ψ(I4, I5) added to the body (`[fibers]` or `[fibres]`).
    #[serde(default, alias = "fibres", skip_serializing_if = "Option::is_none")]
    pub fibers: Option<super::FibreSpec>,
    /// What acts on the body. Only what is listed here is assembled.
    #[serde(default)]
    pub effects: Effects,
    /// Newton options.
    #[serde(default)]
    pub solver: SolverSpec,
    /// Files and pictures.
    #[serde(default)]
    pub output: OutputSpec,
}

/// The body: a mesh file or a generated shape, optionally scaled and moved.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Mesh file (`.obj .off .mesh .msh .vtk`), relative to the scene file;
    /// `data:NAME` means `$ECC_DATA_DIR/NAME` (default: the repository's `data/`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// A built-in shape instead of a file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generate: Option<Shape>,
    /// `bar`: cubes across the bar's 1 × 1 section (24 r³ tets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resolution: Option<usize>,
    /// `box` / `grid`: cells per axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cells: Option<Vec<usize>>,
    /// `box` / `grid`: extent per axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Vec<f64>>,
    /// `disk`: rings (6 rings² triangles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rings: Option<usize>,
    /// `disk`: radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Uniform scale applied to the positions (before `translate`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// Rotation (a rotation vector, axis × degrees; `[angle]` for planar
    /// meshes) about the bounding-box centre, applied after `scale`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<Vec<f64>>,
    /// Translation applied to the positions (after `rotate`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<Vec<f64>>,
    /// Keep only the elements whose vertices all lie in this box (after
    /// `scale` and `translate`): work on part of a large mesh.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crop: Option<BoxSelect>,
    /// Drop vertices that no element uses (renumbering the rest; handle
    /// `ids` keep referring to the file's vertex ids) instead of refusing
    /// the mesh. Default false. Vertices left without an element by `crop`
    /// are always dropped.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drop_unreferenced: Option<bool>,
    /// Refuse elements whose quality (rest area ÷ longest edge², volume ÷
    /// longest edge³) is below this (the error names them). Default 0:
    /// only degenerate elements are refused; slivers below 1e-5 are kept
    /// with a warning.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_quality: Option<f64>,
}

/// Built-in generated shapes (ecc-mesh generators).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// `[-2, 2] × [-0.5, 0.5]²` tet bar.
    Bar,
    /// `[0, sx] × [0, sy] × [0, sz]` tet box.
    Box,
    /// Planar triangle disk centred at the origin.
    Disk,
    /// Planar triangle grid `[0, w] × [0, h]`.
    Grid,
}

/// The energy: a built-in generated energy or a `.psi` file, with parameters.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergySpec {
    /// A built-in energy (see `ecc sim --help` or the provider's `names()`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// A `.psi` file, evaluated at run time (relative to the scene file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub psi: Option<String>,
    /// Parameter values, e.g. `{ mu = 1.0, lambda = 10.0 }`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, f64>,
}

/// The effects. Each is assembled only when present.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Effects {
    /// Mass density ρ used by gravity and inertia (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// Gravitational acceleration vector g (e.g. `[0, -9.81, 0]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<Vec<f64>>,
    /// Dynamics (time stepping); without it every frame is quasi-static.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<InertiaSpec>,
    /// Rayleigh damping (needs inertia).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
    /// A ground half-space.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundSpec>,
    /// Pinned or keyframed vertex sets.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub handles: Vec<HandleSpec>,
    /// Shape interpolation Ψt = (1−t)Ψ1 + tΨ2 towards a second rest shape.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interpolate: Option<InterpolateSpec>,
    /// Surface parameterisation (a 2D energy on a disk-topology surface).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parameterize: Option<ParameterizeSpec>,
}

/// Time integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// Implicit (backward) Euler: first order, dissipative.
    Euler,
    /// Second-order backward differentiation (first step by implicit Euler).
    #[default]
    Bdf2,
}

/// Mass matrix kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    /// Diagonal: each element gives ρ|q|/(d+1) to each of its vertices.
    #[default]
    Lumped,
    /// Consistent linear-element mass: ρ|q|(1 + δ_ab)/((d+1)(d+2)).
    Consistent,
}

/// Dynamics.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InertiaSpec {
    /// Time step h (> 0).
    pub dt: f64,
    /// Time steps per output frame (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps_per_frame: Option<usize>,
    /// `euler` or `bdf2` (default).
    #[serde(default)]
    pub integrator: Integrator,
    /// `lumped` (default) or `consistent`.
    #[serde(default)]
    pub mass: MassKind,
    /// Initial velocity of every vertex (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vec<f64>>,
}

/// Rayleigh damping C = α M + β K, K the projected elastic Hessian at the
/// start of each time step.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSpec {
    /// Mass-proportional coefficient α ≥ 0 (1/s).
    #[serde(default)]
    pub alpha: f64,
    /// Stiffness-proportional coefficient β ≥ 0 (s).
    #[serde(default)]
    pub beta: f64,
}

/// How the ground pushes back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GroundKind {
    /// Smooth log-barrier (IPC): infinite at contact, nothing passes through.
    #[default]
    Barrier,
    /// Quadratic penalty on penetration depth (penetration ~ load/stiffness).
    Penalty,
}

/// The half-space {x : n·x ≥ height}.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundSpec {
    /// Offset along the normal (default 0).
    #[serde(default)]
    pub height: f64,
    /// Unit-length-normalised upward normal (default +y).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<Vec<f64>>,
    /// `barrier` (default) or `penalty`.
    #[serde(default)]
    pub kind: GroundKind,
    /// Barrier activation distance d̂ (default 1e-3 × bounding-box diagonal).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dhat: Option<f64>,
    /// Stiffness κ (default: from the body's weight, see the ground term).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
}

/// A set of vertices, pinned or driven by keyframed rigid transforms.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandleSpec {
    /// A label for reports.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Explicit vertex ids (0-based).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ids: Option<Vec<usize>>,
    /// Vertices inside an axis-aligned box.
    #[serde(default, rename = "box", skip_serializing_if = "Option::is_none")]
    pub bbox: Option<BoxSelect>,
    /// Vertices on the positive side of a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plane: Option<PlaneSelect>,
    /// Rotation centre (default: the handle's rest centroid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center: Option<Vec<f64>>,
    /// Key frames; none means pinned at rest.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keys: Vec<KeySpec>,
}

/// `min ≤ x ≤ max` componentwise.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSelect {
    /// Lower corner.
    pub min: Vec<f64>,
    /// Upper corner.
    pub max: Vec<f64>,
}

/// `(x − point)·normal ≥ 0`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSelect {
    /// A point on the plane.
    pub point: Vec<f64>,
    /// Normal towards the selected side.
    pub normal: Vec<f64>,
}

/// A rigid transform at a frame: rotate about the centre, then translate.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeySpec {
    /// Frame number (≥ 0; frame 0 is the rest pose unless keyed).
    pub frame: f64,
    /// Translation (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<Vec<f64>>,
    /// Rotation in degrees: a rotation vector (axis × angle) in 3D, `[angle]` in 2D.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<Vec<f64>>,
}

/// The second rest shape: a mesh file with the same connectivity, or a
/// deformation of the first (twist and/or bend along an axis).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolateSpec {
    /// A mesh file with the same vertices and elements (relative to the scene file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<String>,
    /// Twist about the axis, degrees from one end to the other.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub twist: Option<f64>,
    /// Bend into a circular arc, total angle in degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bend: Option<f64>,
    /// Axis of the twist / bend: `x` (default), `y` or `z`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<String>,
    /// Number of t values after t = 0 (t_k = k / steps); default 10.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
}

/// Tutte start weights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TutteKind {
    /// Uniform (barycentric) weights.
    #[default]
    Uniform,
    /// Floater's mean-value weights.
    MeanValue,
}

/// Parameterisation options.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterizeSpec {
    /// Weights of the Tutte start.
    #[serde(default)]
    pub tutte: TutteKind,
}

/// Eigenvalue filter choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterKind {
    /// Clamp negative eigenvalues to 0 (the paper's choice).
    #[default]
    Clamp,
    /// Replace eigenvalues by their absolute value.
    Abs,
    /// Per iteration, by the trust-region ratio (Chen et al. 2024).
    Adaptive,
}

/// Per-iteration filter policy (`ecc_fem::FilterPolicy`), `[solver] filter_policy`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FilterPolicyKind {
    /// Always `filter` (the deformation scenes' default).
    Fixed,
    /// Chen et al. 2024: clamp when the model is trusted, abs otherwise
    /// (what `filter = "adaptive"` selects).
    TrustRegion,
    /// `filter` while the model is not trusted, the raw Hessian once it is
    /// (the parameterisation default; docs/benchmarks/projection.md).
    TrustRegionNewton,
}

/// Linear solver choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LinearKind {
    /// Cholesky when the factor fits in memory, else PCG.
    #[default]
    Auto,
    /// Sparse Cholesky (faer).
    Cholesky,
    /// Jacobi-preconditioned conjugate gradients.
    Pcg,
}

/// How element Hessians are made positive semi-definite (`ecc_fem::elastic::Projection`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProjectionKind {
    /// Filter the analytic F-space eigenvalues (no eigensolve).
    FSpace,
    /// The exact projection of each element Hessian (a 4×4 / 9×9
    /// eigensolve on indefinite elements only).
    Element,
    /// `element` on elements far from isotropic, `f-space` elsewhere.
    Hybrid,
    /// `element` for triangles, `f-space` for tetrahedra (the default, see
    /// `docs/benchmarks/projection.md`).
    #[default]
    Auto,
}

/// Newton options.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Stop when ‖∇E‖∞ ≤ tol (the objective is divided by the total rest
    /// measure, so this is a per-unit-area/volume gradient); default 1e-4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tol: Option<f64>,
    /// Also stop when ‖∇E‖∞ ≤ tol_rel·‖∇E₀‖∞ (default 0: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tol_rel: Option<f64>,
    /// Newton iteration cap per solve (default 500: see
    /// `sim::build::DEFAULT_MAX_ITERS`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_iters: Option<usize>,
    /// `clamp` (default), `abs` or `adaptive`.
    #[serde(default)]
    pub filter: FilterKind,
    /// How the filter is chosen per iteration: `fixed`, `trust-region` or
    /// `trust-region-newton` (with `filter` = clamp/abs as the untrusted
    /// filter). Default: `trust-region-newton` for `[effects.parameterize]`,
    /// `fixed` otherwise; `trust-region` when `filter = "adaptive"` (which
    /// conflicts with any other value).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub filter_policy: Option<FilterPolicyKind>,
    /// `auto` (default), `cholesky` or `pcg`.
    #[serde(default)]
    pub linear: LinearKind,
    /// Reuse of a Cholesky factor as the preconditioner of CG on later
    /// Newton steps of a solve. Unset: the default policy
    /// (`ecc_fem::linear::FactorReuse::ONE_STEP`: one stale step per
    /// factor, at most 3 CG iterations, only where a factorisation is
    /// dear); `true`: the older `FactorReuse::STALE_CG` (no age limit,
    /// residual ≤ 1e-2); `false`: a factorisation every step
    /// (docs/benchmarks/reuse.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factor_reuse: Option<bool>,
    /// After a full Newton step with no inversion-free bound, try once the
    /// longer step that minimises the parabola through E(0), ∇Eᵀd and E(1)
    /// (`ecc_fem::NewtonParams::extrapolate`). Default: true for
    /// `[effects.parameterize]`, false otherwise (docs/benchmarks/projection.md:
    /// fewer iterations on the parameterisations, more on the 3D hand).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extrapolate: Option<bool>,
    /// `auto` (default: `element` for triangles, `f-space` for tets),
    /// `f-space`, `element` or `hybrid`.
    #[serde(default)]
    pub projection: ProjectionKind,
    /// Thread policy of the Cholesky factorisation: `split` (default: two
    /// halves of a separator on two threads when the symbolic analysis
    /// estimates it pays), `sequential`, `parallel` or `auto`
    /// (`ecc_fem::linear::cholesky::ThreadPolicy`; docs/benchmarks/threads.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub threads: Option<ecc_fem::linear::cholesky::ThreadPolicy>,
    /// Precision of a split Cholesky factor: `auto` (default: mixed for
    /// large factors, double below), `mixed` (its halves in single
    /// precision, solves refined by CG in double) or `double`
    /// (`ecc_fem::linear::cholesky::FactorPrecision`;
    /// docs/benchmarks/million.md, "Mixed precision").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<ecc_fem::linear::cholesky::FactorPrecision>,
    /// Fill-reducing ordering of the Cholesky factor: `auto` (default:
    /// `metis` for 2D systems of at least 500k unknowns, or there
    /// `geometric` on flat meshes; for 2D systems of 10k–50k unknowns
    /// `metis` where its factor costs at most 0.6× block AMD's; `block-amd`
    /// otherwise), `block-amd`,
    /// `amd`, `metis` or `geometric` (nested dissection from the rest
    /// positions: cheap to compute, good on flat meshes only); the run summary reports the one used
    /// (`ecc_fem::linear::ordering::FillOrdering`; docs/benchmarks/ordering.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ordering: Option<ecc_fem::linear::ordering::FillOrdering>,
    /// Quasi-static handle moves are split into this many solves per frame
    /// (default 1; halved further automatically while a move would invert
    /// an element of a barrier energy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substeps: Option<usize>,
}

/// Per-frame mesh formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrameFormat {
    /// Wavefront OBJ (the boundary surface of tet meshes; uvs for parameterisations).
    Obj,
    /// Legacy VTK unstructured grid (all elements, with point data).
    Vtk,
}

/// Outputs.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output folder, relative to the scene file (default `ecc-out/<name>`
    /// in the current directory; `ecc sim --out` overrides it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir: Option<String>,
    /// Per-frame files (default `["obj", "vtk"]`; `[]` for none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub formats: Option<Vec<FrameFormat>>,
    /// Write every k-th frame (the last frame is always written); default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub every: Option<usize>,
    /// Write `result.png` and `convergence.png` (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pictures: Option<bool>,
    /// Picture size `[width, height]` in pixels, 64–2048 (default `[960, 720]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image_size: Option<Vec<usize>>,
    /// Camera azimuth and elevation in degrees (default `[35, 25]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<Vec<f64>>,
    /// Draw the `[fibers]` directions in `result.png` (default true; only
    /// with a `[fibers]` table).
    #[serde(
        default,
        alias = "draw_fibres",
        skip_serializing_if = "Option::is_none"
    )]
    pub draw_fibers: Option<bool>,
}
