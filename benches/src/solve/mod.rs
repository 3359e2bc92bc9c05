//! Part 2 of the report: convergence of whole solves, ‖∇E‖∞ against
//! iteration and wall time, for each way of building the Newton system.
//!
//! Problems (all with the generated energies and faer Cholesky):
//! * **parameterisation** (SD, `camelhead.off`, `armadillo_cut_low.obj`): as
//!   `ecc_fem::param` — isometric rest frames, unit total area, mean energy
//!   (energy_scale = 1/Σ|q|), uniform Tutte start scaled to the rest area, no
//!   fixed vertex (the translation null space is handled by the solver's shift);
//! * **deformation** (ARAP and stable Neo-Hookean μ = 1, λ = 10, `hand.mesh`):
//!   along the longest bounding-box axis the lowest 8 % of vertices are fixed
//!   and the highest 8 % are moved in one go, twisted 60° about that axis and
//!   pulled out by 10 % of the length; start = rest positions with the handles
//!   at their targets; energy_scale = 1/total volume.
//!
//! Methods ([`SolveMethod`]): the library's defaults (as `ecc sim` runs them)
//! on two threads and in a one-thread pool; projected Newton with the analytic clamp,
//! with |λ| (Chen et al. 2024's "abs"), with the adaptive trust-region
//! filter (`FilterPolicy::TrustRegion`: clamp when the previous step's
//! ρ = actual/predicted decrease is within 1 % of 1, abs otherwise), with
//! numeric per-element projection ([`terms::NumericProjection`]), the
//! first-order Laplacian proxy ([`terms::LaplacianProxy`]), and the autodiff
//! baseline ([`crate::autodiff::term::AutodiffTerm`]: forward-mode dual
//! numbers + numeric element projection, what TinyAD does; SD and SNH only,
//! other energies have no SVD-free form there and are skipped with a note). Every run stops at
//! ‖∇E‖∞ ≤ 10⁻⁸, at its iteration cap or at its wall-time limit.
//!
//! Times come from the solver's own per-iteration records (assembly +
//! factorisation + solve + line search), so the callback costs nothing. The
//! proxy's Hessian is constant, but `NewtonSolver` refactorises it every
//! step; its curve therefore counts the factorisation only once (the first
//! step), as a prefactored solver would — the measured time without that
//! correction is kept in the JSON (`seconds_measured`).

pub mod terms;

use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::Instant;

use ecc_fem::elastic::Projection;
use ecc_fem::linear::FactorReuse;
use ecc_fem::param::ParamOptions;
use ecc_fem::{
    Elastic, Filter, FilterPolicy, LinearSolver, NewtonParams, NewtonSolver, Term, Tet, Tri,
};
use ecc_mesh::{TetMesh, TriMesh, TutteWeights, tutte_embedding};
use ecc_runtime::Energy;
use serde::Serialize;

use crate::autodiff::AdEnergy;
use crate::autodiff::term::AutodiffTerm;
use terms::{LaplacianProxy, NumericProjection};

/// The gradient thresholds the report tabulates.
pub const THRESHOLDS: [f64; 4] = [1e-2, 1e-4, 1e-6, 1e-8];

/// How the Newton system is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SolveMethod {
    /// The library's defaults (what `ecc sim` and `ecc_fem::param` run):
    /// `Projection::default()`, `LinearSolver::Auto`, the split thread
    /// policy, and on parameterisations the trust-region Newton policy and
    /// the line-search extrapolation of `ParamOptions::default()`.
    Defaults,
    /// [`SolveMethod::Defaults`] in a one-thread rayon pool (symbolic
    /// analysis included), for the 1-vs-2-threads comparison.
    DefaultsOneThread,
    Clamp,
    Abs,
    Adaptive,
    NumericProjection,
    LaplacianProxy,
    Autodiff,
}

impl SolveMethod {
    pub const ALL: [SolveMethod; 8] = [
        SolveMethod::Defaults,
        SolveMethod::DefaultsOneThread,
        SolveMethod::Clamp,
        SolveMethod::Abs,
        SolveMethod::Adaptive,
        SolveMethod::NumericProjection,
        SolveMethod::LaplacianProxy,
        SolveMethod::Autodiff,
    ];

    /// Label for tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            SolveMethod::Defaults => "ecc defaults",
            SolveMethod::DefaultsOneThread => "ecc defaults, 1 thread",
            SolveMethod::Clamp => "analytic clamp",
            SolveMethod::Abs => "analytic abs",
            SolveMethod::Adaptive => "adaptive (clamp/abs by ρ)",
            SolveMethod::NumericProjection => "numeric elem. projection",
            SolveMethod::LaplacianProxy => "Laplacian proxy",
            SolveMethod::Autodiff => "autodiff + numeric elem. proj.",
        }
    }

    /// [`SolveMethod::Defaults`] on any number of threads.
    pub fn is_defaults(self) -> bool {
        matches!(self, SolveMethod::Defaults | SolveMethod::DefaultsOneThread)
    }

    /// The element projection this method solves with: the library default
    /// for [`SolveMethod::is_defaults`], the variant's otherwise.
    fn projection(self, variant: &Variant) -> Projection {
        if self.is_defaults() {
            Projection::default()
        } else {
            variant.projection
        }
    }

    /// Run `f` on the threads this method asks for: a one-thread pool for
    /// [`SolveMethod::DefaultsOneThread`], the caller's pool otherwise.
    fn on_its_threads<R: Send>(
        self,
        f: impl FnOnce() -> Result<R, SolveError> + Send,
    ) -> Result<R, SolveError> {
        if self != SolveMethod::DefaultsOneThread {
            return f();
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(err)?
            .install(f)
    }
}

/// One point of a convergence curve.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Point {
    pub iter: usize,
    /// Seconds since the start of the solve when this gradient was known.
    pub seconds: f64,
    pub grad_inf: f64,
    pub energy: f64,
}

/// One solve.
#[derive(Clone, Debug, Serialize)]
pub struct Trace {
    pub problem: String,
    pub method: SolveMethod,
    pub elements: usize,
    pub unknowns: usize,
    pub points: Vec<Point>,
    pub status: String,
    /// Wall time of the solve as measured (proxy: including every refactorisation).
    pub seconds_measured: f64,
}

impl Trace {
    /// Seconds until ‖∇E‖∞ ≤ `tol` first held (None: never).
    pub fn time_to(&self, tol: f64) -> Option<f64> {
        self.points
            .iter()
            .find(|p| p.grad_inf <= tol)
            .map(|p| p.seconds)
    }

    /// Iterations until ‖∇E‖∞ ≤ `tol` first held.
    pub fn iters_to(&self, tol: f64) -> Option<usize> {
        self.points
            .iter()
            .find(|p| p.grad_inf <= tol)
            .map(|p| p.iter)
    }
}

/// Limits of one solve.
#[derive(Clone, Copy, Debug)]
pub struct SolveLimits {
    /// Wall-time limit per solve (seconds).
    pub seconds: f64,
    /// Iteration cap for the Newton variants.
    pub newton_iters: usize,
    /// Iteration cap for the proxy.
    pub proxy_iters: usize,
}

/// Errors setting up a problem (unreadable mesh, degenerate rest element, …).
#[derive(Debug)]
pub struct SolveError(pub String);

impl std::fmt::Display for SolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "solve setup: {}", self.0)
    }
}

impl std::error::Error for SolveError {}

fn err(e: impl std::fmt::Display) -> SolveError {
    SolveError(e.to_string())
}

/// Departures from the solver's defaults for the iteration study of issue
/// #11 (`examples/iterations.rs`): the analytic projection and the
/// line-search rule. `Variant::default()` is what the report runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variant {
    /// Projection of the analytic element term (the report's methods use a
    /// bare `Elastic`, i.e. `FSpace`; the library default is `Auto`).
    pub projection: Projection,
    /// Eigenvalue filter instead of the method's (e.g. TinyAD's
    /// `ClampEps(1e-9)` on the numeric 6×6 projection).
    pub filter: Option<Filter>,
    /// `NewtonParams::barrier_safety` (∞: every search starts at α = 1).
    pub barrier_safety: f64,
    /// `NewtonParams::backtrack` (β).
    pub backtrack: f64,
    /// `NewtonParams::armijo_c1`.
    pub armijo_c1: f64,
    /// Filter policy instead of the method's (e.g. `TrustRegionNewton`).
    pub filter_policy: Option<FilterPolicy>,
    /// Stopping tolerance on ‖∇E‖∞ (the report runs to 1e-8).
    pub tol_abs: f64,
    /// Keep the Tutte start on the unit circle instead of scaling it to the
    /// rest area (TinyAD-Examples' `parametrization_*.cc`).
    pub unit_disk_start: bool,
    /// TinyAD-Examples' units: the mesh at its own scale (no unit-area
    /// normalisation) and the summed objective Σ A (‖J‖² + ‖J⁻¹‖²) = 2 Σ |q| ψ
    /// (energy_scale 2) instead of the area-weighted mean.
    pub raw_units: bool,
    /// Fill-reducing ordering of the Cholesky factor instead of the
    /// default `auto`.
    pub ordering: Option<ecc_fem::linear::ordering::FillOrdering>,
}

impl Default for Variant {
    fn default() -> Self {
        let p = NewtonParams::default();
        Variant {
            projection: Projection::FSpace,
            filter: None,
            barrier_safety: p.barrier_safety,
            backtrack: p.backtrack,
            armijo_c1: p.armijo_c1,
            filter_policy: None,
            tol_abs: THRESHOLDS[3],
            unit_disk_start: false,
            raw_units: false,
            ordering: None,
        }
    }
}

impl Variant {
    /// TinyAD's `line_search` defaults (`include/TinyAD/Utils/LineSearch.hh`):
    /// s_max = 1, shrink 0.8, Armijo 1e-4, no injectivity bound (the barrier's
    /// +∞ rejects steps past it), and its `project_positive_definite` clamp
    /// to ε = 1e-9 (`default_hessian_projection_eps`).
    pub fn tinyad() -> Self {
        Variant {
            filter: Some(Filter::ClampEps(1e-9)),
            barrier_safety: f64::INFINITY,
            backtrack: 0.8,
            armijo_c1: 1e-4,
            ..Default::default()
        }
    }

    fn apply(&self, p: &mut NewtonParams) {
        if let Some(f) = self.filter {
            p.filter = f;
        }
        if let Some(policy) = self.filter_policy {
            p.filter_policy = policy;
        }
        p.barrier_safety = self.barrier_safety;
        p.backtrack = self.backtrack;
        p.armijo_c1 = self.armijo_c1;
        p.tol_abs = self.tol_abs;
        if let Some(o) = self.ordering {
            p.cholesky.ordering = o;
        }
    }
}

fn params(method: SolveMethod, limits: &SolveLimits, scale: f64) -> NewtonParams {
    let mut p = NewtonParams {
        tol_abs: THRESHOLDS[3],
        linear_solver: LinearSolver::Cholesky,
        energy_scale: scale,
        ..Default::default()
    };
    p.max_iters = if method == SolveMethod::LaplacianProxy {
        limits.proxy_iters
    } else {
        limits.newton_iters
    };
    match method {
        SolveMethod::Defaults | SolveMethod::DefaultsOneThread => {
            p.linear_solver = NewtonParams::default().linear_solver;
            return p;
        }
        SolveMethod::Abs => p.filter = Filter::Abs,
        SolveMethod::Adaptive => p.filter_policy = FilterPolicy::TrustRegion,
        _ => {}
    }
    // the alternatives factorise at every Newton step, as TinyAD does (and
    // as ecc did before `FactorReuse::ONE_STEP`), so their iteration counts
    // are not lengthened by inexact stale-factor steps
    p.factor_reuse = FactorReuse::OFF;
    p
}

/// The term `method` solves with, around the analytic element term `inner`
/// of `energy` (rest data `rest`).
fn wrap<const D: usize>(
    method: SolveMethod,
    inner: Box<dyn Term<D>>,
    energy: &str,
    rest: Vec<ecc_runtime::Rest<D>>,
) -> Result<Box<dyn Term<D>>, SolveError> {
    Ok(match method {
        SolveMethod::NumericProjection => Box::new(NumericProjection::new(inner)),
        SolveMethod::LaplacianProxy => Box::new(LaplacianProxy::new(inner, &rest)),
        SolveMethod::Autodiff => {
            let ad = AdEnergy::for_energy(energy, D).ok_or_else(|| {
                SolveError(format!(
                    "no autodiff baseline for {energy} in {D}D (no SVD-free form)"
                ))
            })?;
            Box::new(AutodiffTerm::new(inner, ad, rest))
        }
        _ => inner,
    })
}

/// Run a solver from `x`, recording the curve.
fn record<const D: usize>(
    mut solver: NewtonSolver<D>,
    x: &mut [[f64; D]],
    problem: &str,
    method: SolveMethod,
    elements: usize,
    limits: &SolveLimits,
) -> Result<Trace, SolveError> {
    let start = Instant::now();
    let limit = limits.seconds;
    let result = solver
        .solve_with(x, |_, _| {
            if start.elapsed().as_secs_f64() > limit {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .map_err(err)?;
    let proxy = method == SolveMethod::LaplacianProxy;
    let mut points = Vec::with_capacity(result.records.len() + 1);
    let mut t = 0.0;
    for (k, r) in result.records.iter().enumerate() {
        points.push(Point {
            iter: r.iter,
            seconds: t + r.t_assembly,
            grad_inf: r.grad_inf,
            energy: r.energy,
        });
        let factor = if proxy && k > 0 { 0.0 } else { r.t_factor };
        t += r.t_assembly + factor + r.t_solve + r.t_line_search;
    }
    // the final gradient: one more assembly after the last step (≈ one record's assembly)
    let last_asm = result.records.last().map_or(0.0, |r| r.t_assembly);
    points.push(Point {
        iter: result.iterations,
        seconds: t + last_asm,
        grad_inf: result.grad_inf,
        energy: result.energy,
    });
    Ok(Trace {
        problem: problem.to_string(),
        method,
        elements,
        unknowns: result.unknowns,
        points,
        status: format!("{:?}", result.status)
            .split(['(', ' ', '{'])
            .next()
            .unwrap_or("")
            .to_string(),
        seconds_measured: result.times.total,
    })
}

/// SD-style surface parameterisation of `mesh` with `energy` by `method`.
pub fn parameterization(
    problem: &str,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
    method: SolveMethod,
    limits: &SolveLimits,
) -> Result<Trace, SolveError> {
    parameterization_with(problem, mesh, energy, method, limits, &Variant::default())
}

/// [`parameterization`] with the solver's defaults changed by `variant`.
pub fn parameterization_with(
    problem: &str,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
    method: SolveMethod,
    limits: &SolveLimits,
    variant: &Variant,
) -> Result<Trace, SolveError> {
    method.on_its_threads(|| param_run(problem, mesh, energy, method, limits, variant))
}

fn param_run(
    problem: &str,
    mesh: &TriMesh,
    energy: Arc<dyn Energy<2>>,
    method: SolveMethod,
    limits: &SolveLimits,
    variant: &Variant,
) -> Result<Trace, SolveError> {
    let defaults = ParamOptions::default();
    // the defaults' `Auto` resolves for the parameterisation's policy, as
    // `ecc_fem::param::prepare` does
    let projection = method
        .projection(variant)
        .resolve_for(2, defaults.newton.filter_policy);
    let e0 =
        Elastic::<dyn Energy<2>, Tri>::surface(energy.clone(), &mesh.positions, &mesh.triangles)
            .map_err(err)?;
    let s = if variant.raw_units {
        1.0
    } else {
        1.0 / e0.total_measure().sqrt()
    };
    let scaled: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.map(|c| c * s)).collect();
    let elastic = Elastic::<dyn Energy<2>, Tri>::surface(energy, &scaled, &mesh.triangles)
        .map_err(err)?
        .with_projection(projection);
    let area = elastic.total_measure();
    let rest = elastic.rest().to_vec();
    let name = elastic.energy().name().to_string();
    let term = wrap(method, Box::new(elastic), &name, rest)?;
    let scale = if variant.raw_units { 2.0 } else { 1.0 / area };
    let mut p = params(method, limits, scale);
    variant.apply(&mut p);
    if method.is_defaults() {
        p.filter_policy = defaults.newton.filter_policy;
        p.extrapolate = defaults.newton.extrapolate;
    }
    let solver = NewtonSolver::new(mesh.positions.len(), vec![term], &[], p).map_err(err)?;
    let mut uv = tutte_embedding(mesh, TutteWeights::Uniform).map_err(err)?;
    let uv_area: f64 = mesh
        .triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (uv[t[0]], uv[t[1]], uv[t[2]]);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        })
        .sum();
    if !(uv_area.is_finite() && uv_area > 0.0) {
        return Err(SolveError(format!(
            "{problem}: Tutte start has area {uv_area}"
        )));
    }
    let k = if variant.unit_disk_start {
        1.0
    } else {
        (area / uv_area).sqrt()
    };
    uv.iter_mut().for_each(|p| *p = [p[0] * k, p[1] * k]);
    record(
        solver,
        &mut uv,
        problem,
        method,
        mesh.triangles.len(),
        limits,
    )
}

/// Handles of the deformation problem: (fixed + moved vertex ids, start positions).
pub fn handle_setup(mesh: &TetMesh) -> (Vec<usize>, Vec<[f64; 3]>) {
    let p = &mesh.positions;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for q in p {
        for c in 0..3 {
            lo[c] = lo[c].min(q[c]);
            hi[c] = hi[c].max(q[c]);
        }
    }
    let axis = (0..3)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let len = hi[axis] - lo[axis];
    let low: Vec<usize> = (0..p.len())
        .filter(|&v| p[v][axis] <= lo[axis] + 0.08 * len)
        .collect();
    let high: Vec<usize> = (0..p.len())
        .filter(|&v| p[v][axis] >= hi[axis] - 0.08 * len)
        .collect();
    let mut centre = [0.0; 3];
    for &v in &high {
        for c in 0..3 {
            centre[c] += p[v][c] / high.len().max(1) as f64;
        }
    }
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let th = 60f64.to_radians();
    let mut x = p.clone();
    for &v in &high {
        let (da, db) = (p[v][a] - centre[a], p[v][b] - centre[b]);
        x[v][a] = centre[a] + th.cos() * da - th.sin() * db;
        x[v][b] = centre[b] + th.sin() * da + th.cos() * db;
        x[v][axis] = p[v][axis] + 0.1 * len;
    }
    let mut handles = low;
    handles.extend(high);
    (handles, x)
}

/// The hand deformation with `energy` by `method`.
pub fn deformation(
    problem: &str,
    mesh: &TetMesh,
    energy: Arc<dyn Energy<3>>,
    method: SolveMethod,
    limits: &SolveLimits,
) -> Result<Trace, SolveError> {
    deformation_with(problem, mesh, energy, method, limits, &Variant::default())
}

/// [`deformation`] with the solver's defaults changed by `variant` (its
/// start and unit fields do not apply: the start is [`handle_setup`]'s).
pub fn deformation_with(
    problem: &str,
    mesh: &TetMesh,
    energy: Arc<dyn Energy<3>>,
    method: SolveMethod,
    limits: &SolveLimits,
    variant: &Variant,
) -> Result<Trace, SolveError> {
    method.on_its_threads(|| deform_run(problem, mesh, energy, method, limits, variant))
}

fn deform_run(
    problem: &str,
    mesh: &TetMesh,
    energy: Arc<dyn Energy<3>>,
    method: SolveMethod,
    limits: &SolveLimits,
    variant: &Variant,
) -> Result<Trace, SolveError> {
    let projection = method.projection(variant);
    let elastic = Elastic::<dyn Energy<3>, Tet>::new(energy, &mesh.positions, &mesh.tets)
        .map_err(err)?
        .with_projection(projection);
    let volume = elastic.total_measure();
    let rest = elastic.rest().to_vec();
    let name = elastic.energy().name().to_string();
    let term = wrap(method, Box::new(elastic), &name, rest)?;
    let (handles, mut x) = handle_setup(mesh);
    let mut p = params(method, limits, 1.0 / volume);
    variant.apply(&mut p);
    let solver = NewtonSolver::new(mesh.positions.len(), vec![term], &handles, p).map_err(err)?;
    record(solver, &mut x, problem, method, mesh.tets.len(), limits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variants_change_only_their_fields() {
        let limits = SolveLimits {
            seconds: 1.0,
            newton_iters: 7,
            proxy_iters: 3,
        };
        let base = params(SolveMethod::NumericProjection, &limits, 0.5);
        let mut p = base.clone();
        Variant::default().apply(&mut p);
        assert_eq!(format!("{p:?}"), format!("{base:?}"));
        Variant::tinyad().apply(&mut p);
        assert_eq!(p.filter, Filter::ClampEps(1e-9));
        assert_eq!(p.barrier_safety, f64::INFINITY);
        assert_eq!((p.backtrack, p.armijo_c1), (0.8, 1e-4));
        assert_eq!((p.max_iters, p.energy_scale), (7, 0.5));
        assert_eq!(p.filter_policy, FilterPolicy::Fixed);
    }
}
