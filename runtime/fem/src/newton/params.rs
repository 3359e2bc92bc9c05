//! Solver parameters.

use ecc_runtime::filter::Filter;

use serde::{Deserialize, Serialize};

use crate::linear::cholesky::CholeskyParams;
use crate::linear::{AutoLimits, FactorReuse, LinearSolver};

/// Per-iteration choice of the eigenvalue filter.
///
/// The adaptive policies compute, after every accepted step αd, the
/// trust-region ratio ρ = actual / predicted decrease with the *unfiltered*
/// quadratic model (see [`crate::newton`]), and call the model *trusted*
/// when |ρ − 1| < `adaptive_threshold`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum FilterPolicy {
    /// Always `NewtonParams::filter` (Smith et al. 2019; default Clamp).
    #[default]
    Fixed,
    /// Chen, Liu, Jacobson, Levin & Zheng 2024: `Clamp` when trusted, `Abs`
    /// otherwise; the first iteration uses `Abs`.
    TrustRegion,
    /// An extension in the same spirit (not from the paper): `filter` when
    /// not trusted, the **raw** Hessian (`Filter::None`) when trusted. An
    /// indefinite raw Hessian is made positive definite by the linear
    /// solver's growing diagonal shift (modified Newton, Nocedal & Wright
    /// §3.4), so near a minimiser the iteration becomes Newton's method and
    /// converges quadratically instead of linearly. A raw Hessian with a
    /// non-finite entry falls back to `filter` for that iteration.
    TrustRegionNewton,
}

impl FilterPolicy {
    /// The filter of the first iteration.
    pub fn first(self, filter: Filter) -> Filter {
        match self {
            FilterPolicy::TrustRegion => Filter::Abs,
            _ => filter,
        }
    }

    /// The filter after a step with trust-region ratio `rho`.
    pub fn next(self, filter: Filter, rho: f64, threshold: f64) -> Filter {
        let trusted = (rho - 1.0).abs() < threshold;
        match self {
            FilterPolicy::Fixed => filter,
            FilterPolicy::TrustRegion if trusted => Filter::Clamp,
            FilterPolicy::TrustRegion => Filter::Abs,
            FilterPolicy::TrustRegionNewton if trusted => Filter::None,
            FilterPolicy::TrustRegionNewton => filter,
        }
    }
}

/// Parameters of the projected Newton solver. `Default` gives the paper's
/// setting: stop on ‖∇E‖∞ ≤ 1e-4, clamp filter, Cholesky when it fits.
#[derive(Clone, Debug)]
pub struct NewtonParams {
    /// Stop when ‖∇E‖∞ over the free DOFs is ≤ this (in units of the scaled
    /// objective, see `energy_scale`). Smith et al. 2019 use 1e-4.
    pub tol_abs: f64,
    /// Also stop when ‖∇E‖∞ ≤ `tol_rel`·‖∇E(x₀)‖∞ (0 disables).
    pub tol_rel: f64,
    /// Maximum number of Newton steps.
    pub max_iters: usize,
    /// Eigenvalue filter for the element Hessians (clamp by default).
    pub filter: Filter,
    /// How the filter is chosen per iteration (fixed `filter`, or adaptively
    /// from the trust-region ratio ρ of the previous step; see [`FilterPolicy`]).
    pub filter_policy: FilterPolicy,
    /// The adaptive policies' "model is trusted" test: |ρ − 1| < this
    /// (Chen et al. 2024 use 0.01).
    pub adaptive_threshold: f64,
    /// Linear solver; `Auto` chooses from the symbolic factor size.
    pub linear_solver: LinearSolver,
    /// When `Auto` switches to PCG.
    pub auto_limits: AutoLimits,
    /// Fill-reducing ordering and thread policy of the Cholesky factor
    /// (`linear::cholesky::ThreadPolicy`; default: block AMD, sequential).
    pub cholesky: CholeskyParams,
    /// With Cholesky: when a later step solves by CG preconditioned by the
    /// last (stale) factor instead of factorising again (default
    /// [`FactorReuse::ONE_STEP`]: the step after a factorisation, with at
    /// most 3 CG iterations, where a factorisation is worth ≥ 5 of them;
    /// [`FactorReuse::OFF`] factorises every step; see
    /// [`crate::linear::reuse`]).
    pub factor_reuse: FactorReuse,
    /// The solver minimises `energy_scale`·E; energies and gradients reported
    /// and tested are scaled too (1/Σ|q| gives the area-weighted mean).
    pub energy_scale: f64,
    /// Armijo sufficient-decrease constant c₁.
    pub armijo_c1: f64,
    /// Backtracking factor (0 < β < 1).
    pub backtrack: f64,
    /// Give up the line search below this step length.
    pub min_step: f64,
    /// Start barrier line searches at min(1, `barrier_safety`·α_max)
    /// (α_max: the inversion-free bound). `f64::INFINITY` starts every search
    /// at 1 and lets the barrier's +∞ reject steps past α_max (TinyAD's
    /// `line_search`; see `docs/benchmarks/projection.md` for the comparison).
    pub barrier_safety: f64,
    /// After an accepted full step with no inversion-free bound, try once
    /// the minimiser α* ∈ [1.1, 2] of the parabola through E(0), ∇Eᵀd and
    /// E(1), keeping it if it lowers E (`line_search` module docs).
    /// Default false; the parameterisations turn it on
    /// (`ParamOptions::default`, docs/benchmarks/projection.md).
    pub extrapolate: bool,
    /// Relative diagonal shift used when nothing is fixed (null space), see
    /// [`crate::linear`]. Systems with fixed DOFs start unshifted.
    pub null_space_shift: f64,
    /// Maximum factorisation attempts with growing shift.
    pub shift_attempts: usize,
    /// PCG iteration cap per Newton step.
    pub pcg_max_iters: usize,
    /// PCG forcing term η_k = clamp(√(‖∇E_k‖∞/‖∇E₀‖∞), `pcg_rel_min`, `pcg_rel_max`):
    /// loose far from the solution, tight near it (inexact Newton).
    pub pcg_rel_max: f64,
    /// Lower bound of the PCG forcing term.
    pub pcg_rel_min: f64,
}

impl Default for NewtonParams {
    fn default() -> Self {
        NewtonParams {
            tol_abs: 1e-4,
            tol_rel: 0.0,
            max_iters: 500,
            filter: Filter::default(),
            filter_policy: FilterPolicy::Fixed,
            adaptive_threshold: 0.01,
            linear_solver: LinearSolver::Auto,
            auto_limits: AutoLimits::default(),
            cholesky: CholeskyParams::default(),
            factor_reuse: FactorReuse::default(),
            energy_scale: 1.0,
            armijo_c1: 1e-4,
            backtrack: 0.5,
            min_step: 1e-12,
            barrier_safety: 0.9,
            extrapolate: false,
            null_space_shift: 1e-10,
            shift_attempts: 12,
            pcg_max_iters: 20_000,
            pcg_rel_max: 0.1,
            pcg_rel_min: 1e-8,
        }
    }
}
