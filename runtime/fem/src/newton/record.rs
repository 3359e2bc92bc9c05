//! What a solve reports: per-iteration records, status and totals
//! (serde-serialisable for JSON summaries).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::assembly::{NonFiniteStencil, TermTiming};
use crate::linear::LinearSolver;

/// JSON has no NaN/∞: such values are written as `null` and read back as NaN.
mod maybe_finite {
    use super::*;

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_finite() {
            s.serialize_some(v)
        } else {
            s.serialize_none()
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// Why the solver stopped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind")]
pub enum NewtonStatus {
    /// ‖∇E‖∞ reached `tol_abs` or `tol_rel`.
    Converged,
    /// `max_iters` steps taken.
    MaxIterations,
    /// No step length down to `min_step` gave sufficient decrease.
    LineSearchFailed {
        /// Smallest step tried.
        last_step: f64,
        /// The inversion-free bound (`None`: unbounded).
        max_step: Option<f64>,
    },
    /// A stencil gave a non-finite energy / gradient / Hessian at an iterate
    /// (e.g. an inverted element in the *initial* positions of a barrier energy).
    NonFinite(NonFiniteStencil),
    /// The linear solve produced a non-finite or non-descent direction.
    BadDirection {
        /// gᵀd (should be negative; `null` in JSON when not finite).
        #[serde(with = "maybe_finite")]
        slope: f64,
    },
    /// Cholesky failed even with the largest diagonal shift.
    FactorizationFailed {
        /// Last shift tried.
        shift: f64,
    },
    /// The per-iteration callback asked to stop.
    Interrupted,
}

/// One Newton step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct IterationRecord {
    /// Step index (0-based).
    pub iter: usize,
    /// Scaled energy at the start of the step.
    pub energy: f64,
    /// ‖∇E‖∞ (scaled, free DOFs) at the start of the step.
    pub grad_inf: f64,
    /// Accepted step length α.
    pub step: f64,
    /// Inversion-free bound on α (`None`: no barrier term or unbounded below 2).
    pub max_step: Option<f64>,
    /// Newton decrement λ² = −∇Eᵀd (≥ 0).
    pub decrement: f64,
    /// ‖α·d‖∞: the largest coordinate change.
    pub dx_inf: f64,
    /// Filter used for this step's Hessian.
    pub filter: String,
    /// Trust-region ratio ρ of this step (adaptive filter only; `null` if not finite).
    pub rho: Option<f64>,
    /// Absolute diagonal shift used in the linear system.
    pub shift: f64,
    /// Numeric factorisations this step needed (> 1: the shift was raised).
    pub factorizations: usize,
    /// CG iterations: PCG's, or those preconditioned by a stale Cholesky
    /// factor (including an attempt that fell back to factorising).
    pub cg_iterations: usize,
    /// The direction came from CG preconditioned by a stale factor (no
    /// factorisation this step; see `linear::reuse`).
    #[serde(default)]
    pub reused_factor: bool,
    /// Energy evaluations in the line search.
    pub line_search_evals: usize,
    /// Step accepted without Armijo decrease because the predicted decrease
    /// was below the energy's rounding level.
    pub noise_limited: bool,
    /// Seconds: gradient + Hessian assembly.
    pub t_assembly: f64,
    /// Seconds: diagonal shift + numeric factorisation.
    pub t_factor: f64,
    /// Seconds: triangular solves or PCG.
    pub t_solve: f64,
    /// Seconds: inversion-free bound + energy evaluations.
    pub t_line_search: f64,
}

/// Total seconds per phase over a solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TimeSplit {
    pub assembly: f64,
    pub factor: f64,
    pub solve: f64,
    pub line_search: f64,
    /// Wall time of the whole `solve` call.
    pub total: f64,
}

/// The outcome of a solve. The positions passed to `solve` hold the best
/// (lowest-energy) iterate: the line search only accepts steps that do not
/// increase the energy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NewtonResult {
    pub status: NewtonStatus,
    /// Newton steps taken.
    pub iterations: usize,
    /// Scaled energy at the start and at the returned positions; `+∞` (`null`
    /// in JSON) when a stencil is outside its domain there (e.g. a barrier
    /// energy started inverted) or returned NaN.
    #[serde(with = "maybe_finite")]
    pub initial_energy: f64,
    #[serde(with = "maybe_finite")]
    pub energy: f64,
    /// ‖∇E‖∞ at the start and at the returned positions (scaled, free DOFs);
    /// `+∞` (`null` in JSON) when the gradient could not be evaluated.
    #[serde(with = "maybe_finite")]
    pub initial_grad_inf: f64,
    #[serde(with = "maybe_finite")]
    pub grad_inf: f64,
    /// Unknowns of the reduced system.
    pub unknowns: usize,
    /// Linear solver actually used.
    pub linear_solver: LinearSolver,
    /// Symbolic analyses and numeric factorisations done by this solver object
    /// so far, over every linear backend it has had (symbolic stays 1 while
    /// the backend is kept: it is done once per pattern; `Auto` counts the
    /// analysis it runs to decide, even when it then chooses PCG).
    pub symbolic_analyses: usize,
    pub numeric_factorizations: usize,
    pub times: TimeSplit,
    /// Per-term evaluation cost during this solve.
    pub terms: Vec<TermTiming>,
    pub records: Vec<IterationRecord>,
}

impl NewtonResult {
    /// Whether the solve converged.
    pub fn converged(&self) -> bool {
        self.status == NewtonStatus::Converged
    }
}
