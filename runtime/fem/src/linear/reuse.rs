//! Reusing a numeric Cholesky factor across Newton steps.
//!
//! A numeric factorisation L Lᵀ = H_j + δI of the Hessian of step j is the
//! most expensive part of a Newton step on large 2D meshes (issue #11:
//! 64–81 % of the Newton time). At a later step k the Hessian H_k differs
//! from H_j by the change of the iterate, so the stale factor is an
//! excellent preconditioner: CG on (H_k + δI) d = −g with
//!
//!   M⁻¹ = (L Lᵀ)⁻¹ = (H_j + δI)⁻¹                                       (1)
//!
//! converges in a number of iterations governed by the spread of the
//! eigenvalues of M⁻¹(H_k + δI) around 1, which is small while the
//! iterate moves little (the final, linearly or quadratically converging
//! phase of Newton), and large after big steps (the early phase).
//!
//! **Policy.** After a successful factorisation the next steps first try
//! CG preconditioned by (1), from d = 0, with at most
//! [`FactorReuse::max_cg_iters`] iterations and the relative residual
//!
//!   ‖(H_k + δI) d + g‖ ≤ η_k ‖g‖,  η_k = min(η_forcing,k, `rel_tol`)     (2)
//!
//! where η_forcing,k = clamp(√(‖g_k‖∞/‖g₀‖∞), …) is the inexact-Newton
//! forcing term of the PCG path. Every CG iterate from d = 0 with an SPD
//! preconditioner is a descent direction, so an accepted direction is a
//! valid inexact Newton step. The step refactors (and solves directly) when
//!
//! * CG does not reach (2) within the budget, or meets non-positive
//!   curvature (H_k is not positive definite with the old shift);
//! * the direction is not a descent direction (rounding);
//! * the line search along the reused direction fails (the step is
//!   retried once with a fresh factor from the same iterate);
//! * the Hessian is unfiltered (the raw-Hessian steps of
//!   `FilterPolicy::TrustRegionNewton` need the growing shift search that
//!   only a factorisation performs);
//! * the factor has already served [`FactorReuse::max_age`] stale solves
//!   (without an attempt).
//!
//! **Budget by cost.** One CG iteration with (1) costs two triangular
//! solves with L and one product with H, memory-bound:
//!
//!   W_it = 4·nnz(L) + 4·nnz − 2n + 8n  matvec flops,                     (3)
//!
//! and a factorisation W_f = F/κ of the same units (F = Σ_j c_j², κ the
//! dense-kernel speed-up of [`super::AutoLimits::factor_speedup`]). A
//! reused step must cost less than the factorisation it saves, so the
//! budget is
//!
//!   b = min(`max_cg_iters`, ⌊`max_work_fraction`·W_f / W_it⌋),          (4)
//!
//! and no attempt at all when b < [`MIN_BUDGET`] (a stale-factor solve
//! needed at least 3 iterations in every measured step, so a smaller
//! budget only wastes work).
//!
//! **Default: one stale step per factor, where a factor is dear**
//! ([`FactorReuse::ONE_STEP`], docs/benchmarks/reuse.md, "One stale step
//! per factor"). On this machine a stale-factor CG iteration costs 1/5–1/8
//! of a factorisation, and on the 1M-triangle SD parameterisation a reused
//! step needed 2–3 iterations to reach the forcing term (≤ 0.1) when the
//! factor was one step old, and failed (3 iterations wasted) every time it
//! was two steps old: the projected Hessian moves too much per step. So
//! the default tries the stale factor for at most one step after the step
//! that made it (`max_age` = 1), with at most 3 iterations, and only where
//! one factorisation is worth ≥ 5 CG iterations by the work estimate (4)
//! (θ = 0.6). Measured end to end against a factorisation every step
//! (`ecc sim`, scene defaults, paired rounds, Newton time): the
//! 1M-triangle disk 8 iterations with 5 factorisations instead of 8,
//! 0.84–0.95×; the 135k-triangle disk 7 with 4, 0.96–1.03×; the 8-frame
//! hand.mesh scenes ARAP 17 of 29, 0.75–0.88×, SNH 34 of 56 (57 steps),
//! 0.96–1.21×. camelhead, armadillo_cut_low and hand_1_i_f5000 (a
//! factorisation worth 3.1, 1.5 and 0.9 CG iterations) stay below the
//! threshold: tried there, reuse made them 1.2–1.5× slower.
//! [`FactorReuse::OFF`] factorises every step; [`FactorReuse::STALE_CG`]
//! (no age limit, residual ≤ 1e-2) is the older opt-in policy that paid on
//! 3D handle solves.

use serde::{Deserialize, Serialize};

/// When the Cholesky path may reuse a stale numeric factor as the
/// preconditioner of CG instead of refactorising (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FactorReuse {
    /// CG iterations preconditioned by the stale factor allowed per Newton
    /// step before it refactorises; 0 disables reuse (a factorisation
    /// every step, the behaviour before reuse existed).
    pub max_cg_iters: usize,
    /// Upper bound on the relative residual (2) of a reused step; the
    /// inexact-Newton forcing term applies when it is tighter.
    pub rel_tol: f64,
    /// θ of eq. (4): the CG work a reused step may spend, as a fraction of
    /// one factorisation's estimated work (∞: only `max_cg_iters` limits).
    pub max_work_fraction: f64,
    /// Newton steps one numeric factor may serve after the step that made
    /// it before the next step refactorises without trying it
    /// (`usize::MAX`: no limit, only the residual test decides).
    #[serde(default = "unlimited_age")]
    pub max_age: usize,
}

fn unlimited_age() -> usize {
    usize::MAX
}

/// Smallest useful budget (see the module docs).
pub const MIN_BUDGET: usize = 3;

impl FactorReuse {
    /// The opt-in policy measured in docs/benchmarks/reuse.md: at most 10
    /// iterations, residual ≤ 1e-2 (or the forcing term), θ = 0.75.
    pub const STALE_CG: FactorReuse = FactorReuse {
        max_cg_iters: 10,
        rel_tol: 1e-2,
        max_work_fraction: 0.75,
        max_age: usize::MAX,
    };

    /// The default (module docs): the factor of one step serves at most
    /// the next step, with at most 3 CG iterations, where one factorisation
    /// is worth ≥ 5 of them (θ·W_f/W_it ≥ `MIN_BUDGET`).
    pub const ONE_STEP: FactorReuse = FactorReuse {
        max_cg_iters: 3,
        rel_tol: 0.1,
        max_work_fraction: 0.6,
        max_age: 1,
    };

    /// Never reuse: factorise at every Newton step.
    pub const OFF: FactorReuse = FactorReuse {
        max_cg_iters: 0,
        rel_tol: 0.0,
        max_work_fraction: 0.0,
        max_age: 0,
    };

    /// Whether reuse is enabled.
    pub fn enabled(&self) -> bool {
        self.max_cg_iters > 0 && self.rel_tol > 0.0
    }

    /// The residual target (2) for forcing term `eta`.
    pub fn target(&self, eta: f64) -> f64 {
        eta.min(self.rel_tol)
    }

    /// The budget b of eq. (4) for a factorisation of `factor_work` and a
    /// CG iteration of `iteration_work` (both in matvec flops).
    pub fn budget(&self, factor_work: f64, iteration_work: f64) -> usize {
        if !self.enabled() {
            return 0;
        }
        let by_cost = self.max_work_fraction * factor_work / iteration_work.max(1.0);
        if by_cost.is_nan() || by_cost < MIN_BUDGET as f64 {
            return 0;
        }
        let b = self
            .max_cg_iters
            .min(by_cost.min(usize::MAX as f64) as usize);
        if b < MIN_BUDGET { 0 } else { b }
    }
}

impl Default for FactorReuse {
    /// [`FactorReuse::ONE_STEP`] (module docs: measured).
    fn default() -> Self {
        FactorReuse::ONE_STEP
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_follows_the_cost_bound() {
        let p = FactorReuse::STALE_CG;
        // a factorisation worth 8 CG iterations: θ·8 = 6
        assert_eq!(p.budget(8.0, 1.0), 6);
        // worth 100: capped by max_cg_iters
        assert_eq!(p.budget(100.0, 1.0), 10);
        // worth 3: θ·3 < MIN_BUDGET, no attempt
        assert_eq!(p.budget(3.0, 1.0), 0);
        assert_eq!(FactorReuse::OFF.budget(100.0, 1.0), 0);
        assert_eq!(FactorReuse::default(), FactorReuse::ONE_STEP);
        assert_eq!(p.target(0.5), 1e-2);
        assert_eq!(p.target(1e-4), 1e-4);
    }

    /// The default attempts 3 iterations exactly where a factorisation is
    /// worth ≥ 5 of them: the 135k/1M disks and hand.mesh (6.3, 11.5, 6.0
    /// by eq. (4)), not camelhead, armadillo_cut_low, hand_1_i_f5000 (3.1,
    /// 1.5, 0.9).
    #[test]
    fn the_default_reuses_only_dear_factors_for_one_step() {
        let p = FactorReuse::default();
        for w in [0.9, 1.5, 3.1, 4.9] {
            assert_eq!(p.budget(w, 1.0), 0, "{w}");
        }
        for w in [5.0, 6.0, 6.3, 11.5, 1e6] {
            assert_eq!(p.budget(w, 1.0), 3, "{w}");
        }
        assert_eq!(p.max_age, 1);
        assert_eq!(FactorReuse::STALE_CG.max_age, usize::MAX);
        assert_eq!(FactorReuse::OFF.max_age, 0);
    }
}
