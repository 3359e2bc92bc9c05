//! Projected Newton (Smith, de Goes & Kim 2019, Algorithm 1).
//!
//! Each iteration k:
//!
//! 1. assemble E(x), g = ∇E(x) over the free DOFs and the projected Hessian
//!    H = Σ_e PSD(H_e) (per-element eigenvalue filter from the runtime);
//! 2. stop if ‖g‖∞ ≤ `tol_abs` or ‖g‖∞ ≤ `tol_rel`·‖g₀‖∞;
//! 3. solve (H + δI) d = −g (sparse Cholesky, or PCG to relative residual
//!    η_k = clamp(√(‖g_k‖∞/‖g₀‖∞), `pcg_rel_min`, `pcg_rel_max`));
//! 4. α_max = min over barrier elements of the first root of det F(x + αd)
//!    in (0, 2] (∞ if none), α₀ = min(1, `barrier_safety`·α_max);
//!    backtracking Armijo from α₀ (see [`line_search`]); x ← x + αd.
//!
//! **Adaptive filters** ([`params::FilterPolicy`]). After each accepted step
//! compute the trust-region ratio
//!
//!   ρ = (E(x) − E(x + αd)) / −(α gᵀd + ½ α² dᵀH₀d),
//!
//! where H₀ is the *unfiltered* Hessian at x (dᵀH₀d is summed per element
//! from raw element Hessians: one extra element pass, no assembly), and call
//! the quadratic model trusted when |ρ − 1| < `adaptive_threshold` (0.01).
//! `TrustRegion` is the rule of Chen, Liu, Jacobson, Levin & Zheng 2024,
//! "Trust-Region Eigenvalue Filtering for Projected Newton", as in the
//! authors' code: the next iteration uses `Clamp` when trusted and `Abs`
//! otherwise, and the first iteration uses `Abs` (their ρ₀ = 0).
//! `TrustRegionNewton` is our extension of the same test: the configured
//! filter when not trusted, the raw Hessian (made positive definite by the
//! diagonal shift, see [`crate::linear`]) when trusted, which restores
//! Newton's quadratic convergence in the final phase.

mod iteration;
pub mod line_search;
pub mod params;
pub mod record;
pub mod solver;
