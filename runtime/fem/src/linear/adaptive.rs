//! `Auto` that cannot be a trap: PCG tried under a counted work budget,
//! Cholesky as the fallback.
//!
//! The static model of [`super::auto`] cannot see how far the start is from
//! the solution (a 22k-triangle disk from its Tutte embedding: PCG 3.5×
//! faster than the Cholesky it picks). So where the model is undecided
//! (W_pcg ≤ ρ·W_chol, [`super::AutoLimits::pcg_trial_ratio`]) `Auto` runs
//! this backend, which holds both the analysed Cholesky factor and a PCG
//! state with the preconditioner of [`super::precond`].
//!
//! **Budget, in counted work** (matvec flops, no clocks: the same input
//! gives the same iterates). One Cholesky step costs
//! W_f = F/κ + 4·nnz(L) (eq. (1) of [`super::auto`]); one PCG iteration
//! W_it = 4·nnz + 8n + W_M (product, vector operations, preconditioner
//! application W_M) after a setup W_s of the preconditioner. A PCG step is
//! allowed
//!
//!   b = ⌊(W_f − W_s) / W_it⌋ iterations,                                (1)
//!
//! so an accepted PCG step never costs more than the Cholesky step it
//! replaces: W_s + b·W_it ≤ W_f.
//!
//! **Policy.** At a Newton step the backend tries PCG (from d = 0, at most
//! b iterations, relative residual ≤ min(η_k, `pcg_rel_tol`) with η_k the
//! forcing term of the PCG path) unless it is waiting after a failure; if
//! CG does not reach the tolerance within b iterations, meets non-positive
//! curvature, or gives up early because its residual, extrapolated, will
//! not reach the tolerance within b (`Pcg::solve_budgeted`), the step
//! factorises and solves directly. After the m-th failed attempt it waits
//! 2^m steps before trying again. The cap `pcg_rel_tol` defaults to 1e-2:
//! it keeps Cholesky's Newton count (camelhead 32 steps instead of 47 with
//! the F-space projection, 29 instead of 64 with the element projection),
//! at the price of more CG work on the 1M-triangle disk (825 CG iterations
//! instead of 502 with the forcing term's own cap 0.1).
//!
//! **Bound.** Let a run take N Newton steps. Steps are of three kinds:
//! accepted PCG (work ≤ W_f by (1)), Cholesky (W_f), failed attempt +
//! Cholesky (≤ 2·W_f). The m-th failure happens at a step k_m ≥ 2^m − 1
//! (the waits before it sum to 2 + 4 + … + 2^{m−1}), so there are at most
//! ⌊log₂(N + 1)⌋ failures and
//!
//!   W_auto ≤ N·W_f + ⌊log₂(N + 1)⌋·W_f.                                (2)
//!
//! Against Cholesky (N_chol steps of W_f): when the accepted PCG steps do
//! not lengthen the Newton run (N ≤ N_chol), W_auto ≤ (1 + log₂(N+1)/N)·
//! W_chol, i.e. at most ⌊log₂(N+1)⌋ wasted budgets (≤ 1.2× for N ≥ 30;
//! for shorter runs the loss is ≤ 3 factorisations up to N = 14; the
//! give-up rule usually stops a failing attempt after b/4 iterations).
//! Against PCG: when every PCG step needs ≤ b iterations, no attempt fails
//! and, with `pcg_rel_tol` ≥ the forcing term's cap, the iterates are
//! exactly those of `LinearSolver::Pcg` (same preconditioner, tolerance and
//! start), so W_auto = W_pcg; when some step needs more than b, that PCG
//! step costs more than W_f and Cholesky is the better solver for it. The
//! bound is in counted work: it holds in seconds as far as κ and eq. (3) of
//! [`super::auto`] price a factorisation and a CG iteration correctly
//! (measured in docs/benchmarks/reuse.md, with the table of runs).

use super::cholesky::{CholeskyFactor, FactorizeError};
use super::pcg::Pcg;
use super::precond::Preconditioner;
use super::{FactorizationFailed, LinearSolver, SolveInfo};
use crate::pattern::Pattern;

/// Longest wait after failures (2^MAX_BACKOFF steps).
const MAX_BACKOFF: u32 = 20;

/// What [`Adaptive::prepare`] set up for this step.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Step {
    /// Factorised: solve directly.
    Direct,
    /// Try PCG; on failure factorise (up to this many shift attempts).
    TryPcg { max_attempts: usize },
}

/// The adaptive backend (module docs).
pub struct Adaptive {
    factor: Box<CholeskyFactor>,
    pcg: Box<Pcg>,
    /// CG iterations allowed per PCG step, eq. (1).
    budget: usize,
    /// Cap on the relative residual of a PCG step.
    rel_cap: f64,
    /// Steps to wait before the next attempt.
    wait: usize,
    failures: u32,
    step: Step,
    /// The backend that solved the last step.
    last: LinearSolver,
    /// PCG steps accepted.
    accepted: usize,
    /// Shifted copy of H for a factorisation after a failed attempt.
    scratch: Vec<f64>,
}

impl Adaptive {
    /// Hold the analysed `factor` and a PCG state with `precond`; `budget`
    /// from eq. (1) ([`super::AutoLimits::pcg_budget`]).
    pub fn new(
        pattern: &Pattern,
        factor: Box<CholeskyFactor>,
        precond: Preconditioner,
        budget: usize,
        rel_cap: f64,
    ) -> Self {
        Adaptive {
            factor,
            pcg: Box::new(Pcg::with_preconditioner(pattern, precond)),
            budget,
            rel_cap,
            wait: 0,
            failures: 0,
            step: Step::Direct,
            last: LinearSolver::Cholesky,
            accepted: 0,
            scratch: Vec::new(),
        }
    }

    /// The Cholesky factor (analysis and counters).
    pub fn factor(&self) -> &CholeskyFactor {
        &self.factor
    }

    /// The CG budget b of eq. (1).
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// PCG attempts that failed (each followed by a factorisation).
    pub fn failed_attempts(&self) -> usize {
        self.failures as usize
    }

    /// PCG steps accepted.
    pub fn pcg_steps(&self) -> usize {
        self.accepted
    }

    /// `Pcg` if the last step was solved by PCG, else `Cholesky`.
    pub fn last_kind(&self) -> LinearSolver {
        self.last
    }

    /// Prepare this step for `values` already shifted by `shift` (of
    /// `mean_diag`): an attempt leaves them as they are, otherwise factorise
    /// (`factorize_shifted`). Returns (shift, factorisations).
    pub fn prepare(
        &mut self,
        pattern: &Pattern,
        values: &mut [f64],
        shift: f64,
        mean_diag: f64,
        max_attempts: usize,
    ) -> Result<(f64, usize), FactorizationFailed> {
        if self.wait == 0 && self.budget > 0 {
            self.step = Step::TryPcg { max_attempts };
            return Ok((shift, 0));
        }
        self.wait = self.wait.saturating_sub(1);
        self.step = Step::Direct;
        factorize_shifted(
            &mut self.factor,
            pattern,
            values,
            shift,
            mean_diag,
            max_attempts,
        )
    }

    /// Solve this step: directly, or by PCG within the budget with a
    /// factorisation after a failed attempt (module docs). A factorisation
    /// that fails with every shift leaves NaN in `out`.
    pub fn solve(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        rhs: &[f64],
        out: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
    ) -> SolveInfo {
        let mut info = SolveInfo::default();
        if let Step::TryPcg { max_attempts } = self.step {
            let rel_tol = rel_tol.min(self.rel_cap);
            let budget = self.budget.min(max_iters);
            let cg = (self.pcg).solve_budgeted(pattern, values, rhs, out, rel_tol, budget, true);
            info = SolveInfo::from_pcg(cg);
            if !cg.negative_curvature && cg.relative_residual <= rel_tol {
                self.last = LinearSolver::Pcg;
                self.accepted += 1;
                return info;
            }
            self.failures = (self.failures + 1).min(MAX_BACKOFF);
            self.wait = 1 << self.failures;
            self.scratch.clear();
            self.scratch.extend_from_slice(values);
            let mean_diag = super::mean_diagonal(pattern, values);
            let done = factorize_shifted(
                &mut self.factor,
                pattern,
                &mut self.scratch,
                0.0,
                mean_diag,
                max_attempts,
            );
            info.factorizations = done.map_or(max_attempts.max(1), |d| d.1);
            info.negative_curvature = false;
            info.relative_residual = 0.0;
        }
        self.last = LinearSolver::Cholesky;
        let direct = super::mixed::solve_with_factor(
            &mut self.factor,
            &mut self.pcg,
            pattern,
            values,
            rhs,
            out,
            rel_tol,
        );
        info.iterations += direct.iterations;
        info.relative_residual = direct.relative_residual;
        info.factorizations += direct.factorizations;
        info
    }
}

/// Factorise `values` + extra shifts: `values` already carry `shift`; on a
/// non-positive pivot the shift is raised to max(100·δ, 1e-10·mean diag)
/// and the factorisation retried, at most `max_attempts` times (see
/// [`super`]). Returns (shift in `values`, factorisations) or the last
/// shift tried; `values` hold the factored matrix on success.
pub(crate) fn factorize_shifted(
    f: &mut CholeskyFactor,
    pattern: &Pattern,
    values: &mut [f64],
    shift: f64,
    mean_diag: f64,
    max_attempts: usize,
) -> Result<(f64, usize), FactorizationFailed> {
    let (mut target, mut applied) = (shift, shift);
    for attempt in 1..=max_attempts.max(1) {
        super::shift_diagonal(pattern, values, target - applied);
        applied = target;
        match f.factorize(pattern, values) {
            Ok(()) => return Ok((applied, attempt)),
            // a new pattern that cannot be analysed: no shift helps
            Err(FactorizeError::Symbolic(_)) => break,
            Err(FactorizeError::NotPositiveDefinite(_)) => {}
        }
        target = (100.0 * target).max(1e-10 * mean_diag);
    }
    Err(FactorizationFailed { shift: applied })
}
