//! The Newton linear system H d = −g: direct (faer sparse Cholesky) or
//! iterative (Jacobi PCG), with a diagonal shift for singular Hessians.
//!
//! **Null space.** With no fixed DOFs (parameterisation) the Hessian of any
//! translation-invariant objective is singular: H·(1,…,1 per coordinate) = 0,
//! and after PSD filtering the projected Hessian may have further zero
//! eigenvalues. We factor H + δI instead. δ starts at `base_shift` (relative
//! to the mean diagonal, so it is unit-free; the solver uses a tiny value such
//! as 1e-10 when nothing is fixed and 0 otherwise) and, whenever the
//! numeric factorisation meets a non-positive pivot, is raised to
//! max(100·δ, 1e-10·mean diag) and the factorisation retried (at most
//! `max_attempts` times). Because g is orthogonal to the translation modes
//! (up to rounding), the shift changes the step only by O(δ/λ_min) in the
//! remaining directions and never creates a large null-space component.
//! The same shifted values feed PCG.
//!
//! **Stale factors.** With Cholesky, a later Newton step may solve with CG
//! preconditioned by the last numeric factor instead of factorising again
//! ([`LinearSystem::solve_stale`], policy in [`reuse`]).
//!
//! **Mixed precision.** A large (split) Cholesky factor is by default kept
//! in single precision from [`cholesky::MIXED_MIN_FLOPS`] on and its solves
//! refined by CG in double ([`mixed`], [`cholesky::FactorPrecision`]).

pub mod adaptive;
pub mod auto;
pub mod cholesky;
pub mod mixed;
pub mod ordering;
pub mod pcg;
pub mod precond;
pub mod reuse;

use serde::{Deserialize, Serialize};

use crate::error::FemError;
use crate::pattern::Pattern;
use adaptive::{Adaptive, factorize_shifted};
pub use auto::{AutoLimits, SystemSize};
use cholesky::{CholeskyFactor, CholeskyParams};
use ordering::Coordinates;
use pcg::{Pcg, PcgInfo};
pub use precond::Preconditioner;
pub use reuse::FactorReuse;

/// Which linear solver the Newton iteration uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum LinearSolver {
    /// From the symbolic analysis (once per pattern, model in [`auto`]):
    /// PCG when the Cholesky factor does not fit, Cholesky when the model
    /// is sure it is cheaper, otherwise PCG tried at every step under a
    /// counted work budget with Cholesky as the fallback ([`adaptive`]).
    #[default]
    Auto,
    /// Sparse Cholesky (faer), symbolic once, numeric every step.
    Cholesky,
    /// Preconditioned conjugate gradients (inexact Newton), preconditioner
    /// [`AutoLimits::preconditioner`] (default IC(0)).
    Pcg,
}

/// How a linear system was prepared for this Newton step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PrepareInfo {
    /// Absolute diagonal shift δ actually used.
    pub shift: f64,
    /// δ relative to the mean diagonal.
    pub relative_shift: f64,
    /// Numeric factorisations attempted (0 for PCG).
    pub factorizations: usize,
}

/// The factorisation failed even with the largest shift.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FactorizationFailed {
    /// The last shift tried.
    pub shift: f64,
}

/// Outcome of one solve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveInfo {
    /// CG iterations (0 for a direct Cholesky solve; the refinement's with
    /// a mixed-precision factor).
    pub iterations: usize,
    /// ‖H d + g‖ / ‖g‖ as reported by CG (0 for a direct Cholesky solve).
    pub relative_residual: f64,
    /// CG stopped on non-positive curvature (PCG only).
    pub negative_curvature: bool,
    /// Numeric factorisations made by the solve itself (`Auto` after a
    /// failed PCG attempt, a mixed-precision factor turned double; the
    /// others factorise in `prepare`).
    pub factorizations: usize,
}

impl SolveInfo {
    fn from_pcg(info: PcgInfo) -> Self {
        SolveInfo {
            iterations: info.iterations,
            relative_residual: info.relative_residual,
            negative_curvature: info.negative_curvature,
            factorizations: 0,
        }
    }
}

enum Backend {
    Cholesky(Box<CholeskyFactor>),
    Pcg(Box<Pcg>),
    Adaptive(Box<Adaptive>),
}

/// The Newton system for one pattern: backend state reused across iterations.
pub struct LinearSystem {
    backend: Backend,
    /// (bytes, flops) of the Cholesky factor, if a symbolic analysis was done.
    analysis: Option<(usize, f64)>,
    /// Symbolic analyses whose factor was not kept (`Auto` chose PCG).
    discarded_analyses: usize,
    /// The Cholesky factor holds a successful numeric factorisation.
    factored: bool,
    /// [`LinearSystem::solve_stale`] calls since that factorisation (the
    /// factor's age, limited by [`FactorReuse::max_age`]).
    stale_solves: usize,
    /// CG state for solves preconditioned by a factor, stale or mixed
    /// (allocated on first use).
    cg: Option<Box<Pcg>>,
}

impl LinearSystem {
    /// [`LinearSystem::for_dimension`] for 2D vertices (the dimension
    /// only enters `Auto`'s estimate of PCG iterations).
    pub fn new(
        pattern: &Pattern,
        choice: LinearSolver,
        limits: AutoLimits,
    ) -> Result<Self, FemError> {
        Self::for_dimension(pattern, choice, limits, 2)
    }

    /// Choose and set up the backend for unknowns of `dim`-dimensional
    /// vertices. `Auto` runs the symbolic analysis and keeps Cholesky if
    /// [`AutoLimits::prefers_cholesky`].
    pub fn for_dimension(
        pattern: &Pattern,
        choice: LinearSolver,
        limits: AutoLimits,
        dim: usize,
    ) -> Result<Self, FemError> {
        Self::with_cholesky_params(pattern, choice, limits, dim, CholeskyParams::default())
    }

    /// [`LinearSystem::for_dimension`] with the fill-reducing ordering and
    /// thread policy of the Cholesky factor chosen by `cholesky`.
    pub fn with_cholesky_params(
        pattern: &Pattern,
        choice: LinearSolver,
        limits: AutoLimits,
        dim: usize,
        cholesky: CholeskyParams,
    ) -> Result<Self, FemError> {
        Self::with_geometry(pattern, choice, limits, dim, cholesky, None)
    }

    /// [`LinearSystem::with_cholesky_params`] with the position of every
    /// unknown, for the `geometric` ordering ([`CholeskyFactor::analyze_at`]).
    pub fn with_geometry(
        pattern: &Pattern,
        choice: LinearSolver,
        limits: AutoLimits,
        dim: usize,
        cholesky: CholeskyParams,
        coords: Option<Coordinates>,
    ) -> Result<Self, FemError> {
        if choice != LinearSolver::Pcg {
            // an error here, not `Auto` quietly falling back to PCG below
            let positioned = coords.as_ref().is_some_and(|c| c.at.len() == pattern.n());
            cholesky.ordering.check_usable(positioned)?;
        }
        let pcg = || {
            Backend::Pcg(Box::new(Pcg::with_preconditioner(
                pattern,
                limits.preconditioner,
            )))
        };
        let mut discarded_analyses = 0;
        let (backend, analysis) = match choice {
            LinearSolver::Pcg => (pcg(), None),
            LinearSolver::Cholesky => {
                let f = CholeskyFactor::analyze_at(pattern, cholesky, coords)?;
                let a = (f.factor_bytes(), f.factor_flops());
                (Backend::Cholesky(Box::new(f)), Some(a))
            }
            LinearSolver::Auto => match CholeskyFactor::analyze_at(pattern, cholesky, coords) {
                Ok(f) => {
                    let a = (f.factor_bytes(), f.factor_flops());
                    let size = SystemSize {
                        unknowns: pattern.n(),
                        nnz: pattern.nnz(),
                        dim,
                        factor_bytes: a.0,
                        factor_flops: a.1,
                    };
                    if limits.tries_pcg(&size) {
                        let setup = limits.preconditioner.setup_work(pattern);
                        let budget = limits.pcg_budget(&size, setup);
                        let p = limits.preconditioner;
                        let cap = limits.pcg_rel_tol;
                        let ad = Adaptive::new(pattern, Box::new(f), p, budget, cap);
                        (Backend::Adaptive(Box::new(ad)), Some(a))
                    } else if limits.factor_fits(&size) {
                        (Backend::Cholesky(Box::new(f)), Some(a))
                    } else {
                        drop(f);
                        discarded_analyses = 1;
                        (pcg(), Some(a))
                    }
                }
                // out of memory or index overflow in the analysis: the factor would not fit either
                Err(_) => (pcg(), None),
            },
        };
        Ok(LinearSystem {
            backend,
            analysis,
            discarded_analyses,
            factored: false,
            stale_solves: 0,
            cg: None,
        })
    }

    /// The backend in use (`Cholesky` or `Pcg`, never `Auto`); for the
    /// adaptive backend of `Auto`, the one that solved the last step
    /// (`Cholesky` before the first).
    pub fn kind(&self) -> LinearSolver {
        match &self.backend {
            Backend::Cholesky(_) => LinearSolver::Cholesky,
            Backend::Pcg(_) => LinearSolver::Pcg,
            Backend::Adaptive(a) => a.last_kind(),
        }
    }

    /// `Auto`'s adaptive backend, if that is the backend (budget, attempts).
    pub fn adaptive(&self) -> Option<&Adaptive> {
        match &self.backend {
            Backend::Adaptive(a) => Some(a),
            _ => None,
        }
    }

    /// Bytes of the Cholesky factor, if a symbolic analysis was done.
    pub fn factor_bytes(&self) -> Option<usize> {
        self.analysis.map(|a| a.0)
    }

    /// Estimated flops of one Cholesky factorisation, if a symbolic analysis was done.
    pub fn factor_flops(&self) -> Option<f64> {
        self.analysis.map(|a| a.1)
    }

    /// Symbolic analyses run by this system: the kept factor's (1, plus one
    /// per pattern change) and one `Auto` may have discarded for PCG.
    pub fn symbolic_analyses(&self) -> usize {
        self.discarded_analyses + self.cholesky().map_or(0, CholeskyFactor::symbolic_analyses)
    }

    /// The Cholesky factor (for its counters), if the backend has one.
    pub fn cholesky(&self) -> Option<&CholeskyFactor> {
        match &self.backend {
            Backend::Cholesky(f) => Some(f),
            Backend::Adaptive(a) => Some(a.factor()),
            Backend::Pcg(_) => None,
        }
    }

    /// Shift the diagonal of `values` (H → H + δI) and, for Cholesky, factor,
    /// raising δ on failure (see the module docs). On return `values` holds
    /// the matrix that was factored / will be used by PCG.
    pub fn prepare(
        &mut self,
        pattern: &Pattern,
        values: &mut [f64],
        base_shift: f64,
        max_attempts: usize,
    ) -> Result<PrepareInfo, FactorizationFailed> {
        let n = pattern.n();
        if n == 0 {
            return Ok(PrepareInfo::default());
        }
        let mean_diag = mean_diagonal(pattern, values);
        let shift = base_shift.max(0.0) * mean_diag;
        shift_diagonal(pattern, values, shift);
        let info = |(shift, factorizations): (f64, usize)| PrepareInfo {
            shift,
            relative_shift: shift / mean_diag,
            factorizations,
        };
        match &mut self.backend {
            Backend::Pcg(_) => Ok(info((shift, 0))),
            Backend::Cholesky(f) => {
                self.factored = false;
                let done = factorize_shifted(f, pattern, values, shift, mean_diag, max_attempts)?;
                self.factored = true;
                self.stale_solves = 0;
                Ok(info(done))
            }
            Backend::Adaptive(a) => a
                .prepare(pattern, values, shift, mean_diag, max_attempts)
                .map(info),
        }
    }

    /// Solve (H + δI) d = rhs into `out`. `rel_tol`/`max_iters` matter for
    /// PCG; `rel_tol` also for a mixed-precision factor ([`mixed`]).
    pub fn solve(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        rhs: &[f64],
        out: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
    ) -> SolveInfo {
        match &mut self.backend {
            Backend::Cholesky(f) => {
                let cg = self.cg.get_or_insert_with(|| Box::new(Pcg::new(pattern)));
                mixed::solve_with_factor(f, cg, pattern, values, rhs, out, rel_tol)
            }
            Backend::Pcg(p) => {
                SolveInfo::from_pcg(p.solve(pattern, values, rhs, out, rel_tol, max_iters))
            }
            Backend::Adaptive(a) => a.solve(pattern, values, rhs, out, rel_tol, max_iters),
        }
    }

    /// Whether a numeric factor from an earlier [`LinearSystem::prepare`]
    /// is available to precondition [`LinearSystem::solve_stale`].
    pub fn has_factor(&self) -> bool {
        self.factored && matches!(self.backend, Backend::Cholesky(_))
    }

    /// CG iterations a step may spend with the stale factor, eq. (4) of
    /// [`reuse`], with the factorisation's work from `limits`' κ (0 when
    /// there is no factor, it has served `reuse.max_age` stale solves
    /// already, or reuse does not pay).
    pub fn stale_budget(
        &self,
        pattern: &Pattern,
        reuse: &FactorReuse,
        limits: &AutoLimits,
    ) -> usize {
        let (Some(f), true) = (self.cholesky(), self.has_factor()) else {
            return 0;
        };
        if self.stale_solves >= reuse.max_age {
            return 0;
        }
        let flops = f.factor_flops();
        let (n, nnz) = (pattern.n() as f64, pattern.nnz() as f64);
        let nnz_l = f.factor_nnz() as f64;
        let iteration = 4.0 * nnz_l + 4.0 * nnz - 2.0 * n + 8.0 * n;
        reuse.budget(flops / limits.factor_speedup, iteration)
    }

    /// Forget the numeric factor for [`LinearSystem::solve_stale`] (the next
    /// [`LinearSystem::prepare`] factorises again). Newton calls this at the
    /// start of every solve: term data and handles may change between
    /// solves, so a factor is only reused within the solve that made it.
    pub fn forget_factor(&mut self) {
        self.factored = false;
    }

    /// Shift the diagonal of `values` by `base_shift`·mean|diag| without
    /// factorising (the step that [`LinearSystem::solve_stale`] solves).
    pub fn shift_only(
        &self,
        pattern: &Pattern,
        values: &mut [f64],
        base_shift: f64,
    ) -> PrepareInfo {
        if pattern.n() == 0 {
            return PrepareInfo::default();
        }
        let mean_diag = mean_diagonal(pattern, values);
        let shift = base_shift.max(0.0) * mean_diag;
        shift_diagonal(pattern, values, shift);
        PrepareInfo {
            shift,
            relative_shift: shift / mean_diag,
            factorizations: 0,
        }
    }

    /// Undo a shift applied by [`LinearSystem::prepare`] or
    /// [`LinearSystem::shift_only`] (before preparing the same step again).
    pub fn unshift(&self, pattern: &Pattern, values: &mut [f64], shift: f64) {
        shift_diagonal(pattern, values, -shift);
    }

    /// Solve (H + δI) d = rhs by CG preconditioned by the last numeric
    /// factor, which may be of an earlier H (eq. (1) of [`reuse`]), to
    /// relative residual `rel_tol` in at most `max_iters` iterations.
    /// `None` when there is no factor (PCG backend or no factorisation yet).
    pub fn solve_stale(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        rhs: &[f64],
        out: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
    ) -> Option<SolveInfo> {
        let Backend::Cholesky(f) = &mut self.backend else {
            return None;
        };
        if !self.factored {
            return None;
        }
        self.stale_solves += 1;
        let cg = self.cg.get_or_insert_with(|| Box::new(Pcg::new(pattern)));
        let info = cg.solve_preconditioned(values, rhs, out, rel_tol, max_iters, |r, z| {
            z.copy_from_slice(r);
            if !f.solve_in_place(z) {
                z.fill(f64::NAN);
            }
        });
        Some(SolveInfo::from_pcg(info))
    }
}

/// Mean |diagonal| of `values` (1 when it is 0 or not finite): the unit of
/// the relative shift.
fn mean_diagonal(pattern: &Pattern, values: &[f64]) -> f64 {
    let n = pattern.n();
    let s: f64 = (0..n)
        .map(|j| values[pattern.diag_slot(j)].abs())
        .sum::<f64>()
        / n.max(1) as f64;
    if s > 0.0 && s.is_finite() { s } else { 1.0 }
}

/// values += delta·I on the diagonal.
fn shift_diagonal(pattern: &Pattern, values: &mut [f64], delta: f64) {
    if delta != 0.0 {
        for j in 0..pattern.n() {
            values[pattern.diag_slot(j)] += delta;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::pattern::{StencilSet, build};

    /// Pure graph Laplacian of a path: singular (constant null vector).
    fn laplacian(n: usize) -> (Pattern, Vec<f64>) {
        let edges: Vec<usize> = (0..n - 1).flat_map(|i| [i, i + 1]).collect();
        let dofs = DofMap::all_free(n, 1).unwrap();
        let (p, _) = build(
            &[StencilSet {
                name: "e",
                arity: 2,
                stencils: &edges,
            }],
            &dofs,
        )
        .unwrap();
        let mut v = vec![0.0; p.nnz()];
        for e in edges.chunks(2) {
            v[p.diag_slot(e[0])] += 1.0;
            v[p.diag_slot(e[1])] += 1.0;
            v[p.slot(e[0], e[1]).unwrap()] -= 1.0;
        }
        (p, v)
    }

    /// `geometric` without a position per unknown is an error for every
    /// solver that may factorise (never `Auto` quietly switching to PCG);
    /// with them, the factor uses it.
    #[test]
    fn geometric_needs_positions_and_uses_them() {
        let p = ordering::tests::grid(6, 5, 2);
        let params = CholeskyParams {
            ordering: ordering::FillOrdering::Geometric,
            ..Default::default()
        };
        let limits = AutoLimits::default();
        for choice in [LinearSolver::Cholesky, LinearSolver::Auto] {
            let Err(e) = LinearSystem::with_cholesky_params(&p, choice, limits, 2, params) else {
                panic!("{choice:?} without positions");
            };
            assert!(format!("{e}").contains("vertex positions"), "{e}");
        }
        assert!(
            LinearSystem::with_cholesky_params(&p, LinearSolver::Pcg, limits, 2, params).is_ok()
        );
        let coords: Coordinates = ordering::tests::grid_coords(6, 5, 2).into();
        let s = LinearSystem::with_geometry(
            &p,
            LinearSolver::Cholesky,
            limits,
            2,
            params,
            Some(coords),
        )
        .unwrap();
        let used = s.cholesky().unwrap().params().ordering;
        assert_eq!(used, ordering::FillOrdering::Geometric);
    }

    #[test]
    fn singular_laplacian_is_solved_with_a_shift() {
        let n = 40;
        let (p, v) = laplacian(n);
        // right-hand side orthogonal to the constant null vector
        let b: Vec<f64> = (0..n)
            .map(|i| (i as f64 - (n as f64 - 1.0) / 2.0) / n as f64)
            .collect();
        for kind in [
            LinearSolver::Cholesky,
            LinearSolver::Pcg,
            LinearSolver::Auto,
        ] {
            let mut sys = LinearSystem::new(&p, kind, AutoLimits::default()).unwrap();
            let mut vals = v.clone();
            let info = sys.prepare(&p, &mut vals, 0.0, 12).unwrap();
            let mut x = vec![0.0; n];
            let solved = sys.solve(&p, &vals, &b, &mut x, 1e-12, 10 * n);
            let mut hx = vec![0.0; n];
            p.sym_matvec(&v, &x, &mut hx);
            let err = hx
                .iter()
                .zip(&b)
                .map(|(a, c)| (a - c).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-6, "{kind:?}: residual {err}, shift {}", info.shift);
            if sys.kind() == LinearSolver::Cholesky {
                // `Auto`'s adaptive backend factorises in `solve` after a
                // failed PCG attempt: count both
                assert!(info.factorizations + solved.factorizations >= 1);
            }
        }
    }

    #[test]
    fn auto_falls_back_to_pcg_when_the_factor_is_too_big() {
        let (p, _) = laplacian(20);
        let tiny = AutoLimits {
            max_factor_bytes: 8,
            ..AutoLimits::default()
        };
        let sys = LinearSystem::new(&p, LinearSolver::Auto, tiny).unwrap();
        assert_eq!(sys.kind(), LinearSolver::Pcg);
        assert!(sys.factor_bytes().unwrap() > 8);
        let few = AutoLimits {
            max_factor_flops: 1.0,
            ..AutoLimits::default()
        };
        assert_eq!(
            LinearSystem::new(&p, LinearSolver::Auto, few)
                .unwrap()
                .kind(),
            LinearSolver::Pcg
        );
        let sys = LinearSystem::new(&p, LinearSolver::Auto, AutoLimits::default()).unwrap();
        assert_eq!(sys.kind(), LinearSolver::Cholesky);
    }
}
