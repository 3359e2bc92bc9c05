//! Turning a scene into an [`Engine`]: exactly the named terms, nothing more.
//!
//! | scene | term | stencils |
//! |---|---|---|
//! | always | `elastic` Σ|q|Ψ (or `interpolation` (1−t)E₁ + tE₂) | elements |
//! | `gravity` | `gravity` −Σ m_v g·x_v | vertices |
//! | `inertia` | `inertia` ½w‖x − x̃‖²_M (builds the mass matrix) | vertices / elements |
//! | `damping.alpha` | `damping_mass` ½αa‖x − y‖²_M | as inertia |
//! | `damping.beta` | `damping_stiffness` ½βa (x − y)ᵀK(x − y) | elements |
//! | `ground` | `ground` barrier or penalty | boundary vertices |
//! | `handles` | Dirichlet (fixed vertices), no term | — |
//!
//! The solver minimises the objective divided by the total rest measure
//! Σ|q| (a per-unit-area/volume objective), so `solver.tol` means the same
//! on small and large meshes.
//!
//! Ground defaults: normal +y, d̂ = 10⁻³ × bounding-box diagonal, and
//! κ = 10 W/(n_b d̂) with W the body's weight (Σ m_v |g|, or Σ|q| without
//! gravity) and n_b the number of boundary vertices: the barrier force at
//! d = d̂/2 is 1.19 κ d̂, so about a tenth of the boundary vertices hold the
//! body's weight there.

use std::sync::Arc;

use ecc_fem::elastic::Projection;
use ecc_fem::param::ParamOptions;
use ecc_fem::{DofMap, Filter, FilterPolicy, LinearSolver, NewtonParams, NewtonSolver, Term};
use ecc_runtime::FibreEnergy;

use super::engine::{Engine, Slots};
use crate::body::Body;
use crate::counters::{Counter, Counters};
use crate::dynamics::Dynamics;
use crate::error::SceneError;
use crate::handles::{Handle, build_handle, vector};
use crate::spec::{
    FilterKind, FilterPolicyKind, GroundKind, LinearKind, ProjectionKind, SceneFile, SolverSpec,
};
use crate::terms::{
    Blend, Gravity, Ground, MassMatrix, MassQuadratic, StiffnessDamping, vertex_masses,
};

/// `[solver] max_iters` when absent: the Newton library's default. The
/// slowest solve of the benchmark report's meshes to the scenes' default
/// tolerance 1e-4 is hand_1_i_f5000's parameterisation with symmetric
/// Dirichlet and the clamp filter, 228 iterations (camelhead: 32–55,
/// armadillo_cut_low: 71–144, hand ARAP/SNH: 4–20; 207 for camelhead with
/// `abs` to 1e-8); 500 leaves twice that, and a run that still does not
/// converge exits non-zero (`ecc sim`).
pub const DEFAULT_MAX_ITERS: usize = 500;

/// Newton parameters of a parameterisation (`[effects.parameterize]`):
/// [`newton_params`] with the filter policy and the line-search
/// extrapolation defaulting to the library's parameterisation defaults,
/// `ParamOptions::default()`'s ([`FilterPolicy::TrustRegionNewton`] and
/// `extrapolate = true`: fewer iterations on the measured
/// parameterisations, docs/benchmarks/projection.md).
pub fn param_newton_params(s: &SolverSpec, scale: f64) -> NewtonParams {
    let library = ParamOptions::default().newton;
    NewtonParams {
        filter_policy: filter_policy(s, library.filter_policy),
        extrapolate: s.extrapolate.unwrap_or(library.extrapolate),
        ..newton_params(s, scale)
    }
}

/// The filter policy of `[solver]`: `filter_policy` when given, else
/// trust-region for `filter = "adaptive"`, else `default`.
pub fn filter_policy(s: &SolverSpec, default: FilterPolicy) -> FilterPolicy {
    match (s.filter_policy, s.filter) {
        (Some(FilterPolicyKind::Fixed), _) => FilterPolicy::Fixed,
        (Some(FilterPolicyKind::TrustRegion), _) => FilterPolicy::TrustRegion,
        (Some(FilterPolicyKind::TrustRegionNewton), _) => FilterPolicy::TrustRegionNewton,
        (None, FilterKind::Adaptive) => FilterPolicy::TrustRegion,
        (None, _) => default,
    }
}

/// Newton parameters from `[solver]` with the objective scaled by `scale`
/// (deformation scenes: the filter policy defaults to the fixed filter).
pub fn newton_params(s: &SolverSpec, scale: f64) -> NewtonParams {
    NewtonParams {
        tol_abs: s.tol.unwrap_or(1e-4),
        tol_rel: s.tol_rel.unwrap_or(0.0),
        max_iters: s.max_iters.unwrap_or(DEFAULT_MAX_ITERS),
        filter: match s.filter {
            FilterKind::Abs => Filter::Abs,
            _ => Filter::Clamp,
        },
        filter_policy: filter_policy(s, FilterPolicy::Fixed),
        linear_solver: match s.linear {
            LinearKind::Auto => LinearSolver::Auto,
            LinearKind::Cholesky => LinearSolver::Cholesky,
            LinearKind::Pcg => LinearSolver::Pcg,
        },
        factor_reuse: match s.factor_reuse {
            None => ecc_fem::linear::FactorReuse::default(),
            Some(true) => ecc_fem::linear::FactorReuse::STALE_CG,
            Some(false) => ecc_fem::linear::FactorReuse::OFF,
        },
        extrapolate: s.extrapolate.unwrap_or(false),
        energy_scale: scale,
        cholesky: ecc_fem::linear::cholesky::CholeskyParams {
            ordering: s.ordering.unwrap_or_default(),
            threads: s.threads.unwrap_or_default(),
            precision: s.precision.unwrap_or_default(),
        },
        ..NewtonParams::default()
    }
}

/// The element projection of a `D`-dimensional deformation scene: `[solver]
/// projection` with `auto` resolved for the scene's filter policy
/// ([`Projection::resolve_for`]; parameterisations resolve it in
/// `ecc_fem::param::prepare` for theirs).
pub fn deformation_projection(s: &SolverSpec, d: usize) -> Projection {
    projection(s).resolve_for(d, filter_policy(s, FilterPolicy::Fixed))
}

/// The element projection of `[solver] projection`.
pub fn projection(s: &SolverSpec) -> Projection {
    match s.projection {
        ProjectionKind::FSpace => Projection::FSpace,
        ProjectionKind::Element => Projection::Element,
        ProjectionKind::Hybrid => Projection::hybrid(),
        ProjectionKind::Auto => Projection::Auto,
    }
}

/// What [`build_engine`] needs besides the scene.
pub struct EngineInput<'a, const D: usize> {
    /// The scene.
    pub file: &'a SceneFile,
    /// The body.
    pub body: Body<D>,
    /// File vertex id → body vertex id.
    pub vertex_map: &'a [Option<usize>],
    /// Boundary vertices (ground contact candidates).
    pub boundary: Vec<usize>,
    /// Second rest shape (interpolation).
    pub rest2: Option<Vec<[f64; D]>>,
    /// Run counters.
    pub counters: Arc<Counters>,
    /// The fibre energy on the `[fibers]` directions, if any
    /// ([`crate::terms::fibre::fibre_energy`]).
    pub fibre: Option<Arc<dyn FibreEnergy<D>>>,
}

/// The up direction +y in D dimensions.
fn up<const D: usize>() -> [f64; D] {
    std::array::from_fn(|c| if c == 1 { 1.0 } else { 0.0 })
}

fn bbox_diagonal<const D: usize>(x: &[[f64; D]]) -> f64 {
    (0..D)
        .map(|c| {
            let (lo, hi) = x
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    (l.min(p[c]), h.max(p[c]))
                });
            (hi - lo) * (hi - lo)
        })
        .sum::<f64>()
        .sqrt()
}

fn setup_err(e: ecc_fem::FemError) -> SceneError {
    SceneError::setup("the solver", e)
}

/// Number of frames: `frames`, else the interpolation steps, else the last
/// handle key (rounded up), else 50 for dynamics and 1 otherwise.
pub fn frame_count<const D: usize>(file: &SceneFile, handles: &[Handle<D>]) -> usize {
    let s = &file.scene;
    if let Some(n) = s.frames {
        return n;
    }
    if let Some(i) = &s.effects.interpolate {
        return i.steps.unwrap_or(10);
    }
    let last = handles.iter().map(|h| h.last_frame()).fold(0.0, f64::max);
    if last > 0.0 {
        return last.ceil() as usize;
    }
    if s.effects.inertia.is_some() { 50 } else { 1 }
}

/// The solver's terms as they are added, and where each effect sits.
struct TermList<const D: usize> {
    terms: Vec<Box<dyn Term<D>>>,
    slots: Slots,
}

impl<const D: usize> TermList<D> {
    /// Append a term and return its slot.
    fn push(&mut self, term: Box<dyn Term<D>>) -> usize {
        self.terms.push(term);
        self.terms.len() - 1
    }
}

/// What the inertia effect adds besides its terms.
struct Inertia<const D: usize> {
    mass: Arc<MassMatrix<D>>,
    dynamics: Dynamics<D>,
    steps_per_frame: usize,
}

/// The handles of the scene and the vertices they fix (handles must not overlap).
fn scene_handles<const D: usize>(
    file: &SceneFile,
    body: &Body<D>,
    vertex_map: &[Option<usize>],
) -> Result<(Vec<Handle<D>>, Vec<usize>), SceneError> {
    let specs = &file.scene.effects.handles;
    let mut taken = vec![None; body.n_vertices()];
    let mut handles = Vec::with_capacity(specs.len());
    for (i, h) in specs.iter().enumerate() {
        handles.push(build_handle::<D>(i, h, &body.rest, vertex_map, &mut taken)?);
    }
    let fixed = handles
        .iter()
        .flat_map(|h| h.vertices.iter().copied())
        .collect();
    Ok((handles, fixed))
}

/// The elastic term, or the interpolation blend between the rest shape and
/// `rest2` (slot 0).
fn elastic_term<const D: usize>(
    list: &mut TermList<D>,
    body: &Body<D>,
    rest2: Option<&[[f64; D]]>,
    counters: &Arc<Counters>,
) -> Result<(), SceneError> {
    let elastic = body.elastic().map_err(setup_err)?;
    let slot = match rest2 {
        Some(r2) => {
            let second = body.elastic_at(r2).map_err(|e| {
                SceneError::invalid(
                    "effects.interpolate",
                    format!("the second rest shape is not usable: {e}"),
                )
            })?;
            let blend = Blend::new(elastic, second, counters.clone())
                .map_err(|m| SceneError::invalid("effects.interpolate", m))?;
            list.slots.blend = true;
            list.push(Box::new(blend))
        }
        None => list.push(elastic),
    };
    list.slots.elastic = slot;
    Ok(())
}

/// The gravity term, if the scene has gravity; returns the body's weight
/// Σ m_v |g|.
fn gravity_term<const D: usize>(
    list: &mut TermList<D>,
    file: &SceneFile,
    body: &Body<D>,
    counters: &Arc<Counters>,
) -> Result<Option<f64>, SceneError> {
    let fx = &file.scene.effects;
    let Some(g) = fx.gravity.as_ref() else {
        return Ok(None);
    };
    let g = vector::<D>("effects.gravity", g)?;
    let masses = vertex_masses(body, fx.density.unwrap_or(1.0));
    let gnorm = g.iter().map(|c| c * c).sum::<f64>().sqrt();
    let weight = masses.iter().sum::<f64>() * gnorm;
    list.slots.gravity = Some(list.push(Box::new(Gravity::new(&masses, g, counters.clone()))));
    Ok(Some(weight))
}

/// Inertia and its damping terms, if the scene has inertia.
fn inertia_terms<const D: usize>(
    list: &mut TermList<D>,
    file: &SceneFile,
    body: &Body<D>,
    counters: &Arc<Counters>,
) -> Result<Option<Inertia<D>>, SceneError> {
    let fx = &file.scene.effects;
    let Some(spec) = &fx.inertia else {
        return Ok(None);
    };
    let n = body.n_vertices();
    let density = fx.density.unwrap_or(1.0);
    let m = Arc::new(MassMatrix::build(body, density, spec.mass, counters));
    let inertia = MassQuadratic::new(
        "inertia",
        Counter::InertiaPass,
        m.clone(),
        n,
        counters.clone(),
    );
    list.slots.inertia = Some(list.push(Box::new(inertia)));
    if let Some(d) = &fx.damping {
        if d.alpha > 0.0 {
            let mut q = MassQuadratic::new(
                "damping_mass",
                Counter::DampingPass,
                m.clone(),
                n,
                counters.clone(),
            );
            q.coefficient = d.alpha;
            list.slots.damping_mass = Some(list.push(Box::new(q)));
        }
        if d.beta > 0.0 {
            let mut k =
                StiffnessDamping::new(body.elastic().map_err(setup_err)?, n, counters.clone());
            k.coefficient = d.beta;
            list.slots.damping_stiffness = Some(list.push(Box::new(k)));
        }
    }
    let v0 = spec
        .velocity
        .as_ref()
        .map(|v| vector::<D>("effects.inertia.velocity", v))
        .transpose()?
        .unwrap_or([0.0; D]);
    Ok(Some(Inertia {
        mass: m,
        dynamics: Dynamics::new(spec.integrator, spec.dt, body.rest.clone(), v0),
        steps_per_frame: spec.steps_per_frame.unwrap_or(1),
    }))
}

/// The ground term, if the scene has a ground (defaults in the module docs;
/// `weight` is the body's weight under gravity).
fn ground_term<const D: usize>(
    list: &mut TermList<D>,
    file: &SceneFile,
    body: &Body<D>,
    boundary: Vec<usize>,
    weight: Option<f64>,
    counters: &Arc<Counters>,
) -> Result<(), SceneError> {
    let Some(gs) = &file.scene.effects.ground else {
        return Ok(());
    };
    let normal = match &gs.normal {
        Some(nv) => vector::<D>("effects.ground.normal", nv)?,
        None => up::<D>(),
    };
    let dhat = gs.dhat.unwrap_or(1e-3 * bbox_diagonal(&body.rest));
    let nb = boundary.len().max(1) as f64;
    let w = weight.unwrap_or_else(|| body.total_rest_measure());
    let kappa = gs.stiffness.unwrap_or(10.0 * w / (nb * dhat));
    let ground = Ground::new(
        boundary,
        normal,
        gs.height,
        gs.kind,
        dhat,
        kappa,
        counters.clone(),
    );
    if gs.kind == GroundKind::Barrier {
        let d = ground.min_distance(&body.rest);
        if !(d > 0.0) {
            return Err(SceneError::invalid(
                "effects.ground.height",
                format!(
                    "the body starts at distance {d:.4} from the ground; a barrier needs \
                     every vertex strictly above it (lower the ground or move the mesh)"
                ),
            ));
        }
    }
    list.slots.ground = Some(list.push(Box::new(ground)));
    Ok(())
}

/// Build the engine (see the module docs).
pub fn build_engine<const D: usize>(input: EngineInput<'_, D>) -> Result<Engine<D>, SceneError> {
    let EngineInput {
        file,
        body,
        vertex_map,
        boundary,
        rest2,
        counters,
        fibre,
    } = input;
    let (handles, fixed) = scene_handles(file, &body, vertex_map)?;
    let mut list = TermList {
        terms: Vec::new(),
        slots: Slots::default(),
    };
    elastic_term(&mut list, &body, rest2.as_deref(), &counters)?;
    if let Some(t) = crate::terms::fibre::fibre_term(file, &body, fibre)? {
        list.push(t);
    }
    let weight = gravity_term(&mut list, file, &body, &counters)?;
    let inertia = inertia_terms(&mut list, file, &body, &counters)?;
    ground_term(&mut list, file, &body, boundary, weight, &counters)?;
    let scale = 1.0 / body.total_rest_measure();
    let params = newton_params(&file.scene.solver, scale);
    let n = body.n_vertices();
    // rest positions for the `geometric` ordering (2D: z = 0)
    let at: Vec<[f64; 3]> = body
        .rest
        .iter()
        .map(|p| std::array::from_fn(|k| p.get(k).copied().unwrap_or(0.0)))
        .collect();
    let solver = DofMap::from_fixed_vertices(n, D, &fixed)
        .and_then(|dofs| NewtonSolver::with_geometry(list.terms, dofs, params, &at))
        .map_err(setup_err)?;
    let interp_steps = file
        .scene
        .effects
        .interpolate
        .as_ref()
        .map(|i| i.steps.unwrap_or(10));
    let (mass, dynamics, steps_per_frame) = match inertia {
        Some(i) => (Some(i.mass), Some(i.dynamics), i.steps_per_frame),
        None => (None, None, 1),
    };
    Ok(Engine::new(
        body,
        solver,
        list.slots,
        handles,
        mass,
        dynamics,
        steps_per_frame,
        interp_steps,
        file.scene.solver.substeps.unwrap_or(1),
        counters,
    ))
}
