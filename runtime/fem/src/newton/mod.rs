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
//! **Adaptive filter** (`adaptive_filter = true`), after Chen, Liu, Jacobson,
//! Levin & Zheng 2024, "Trust-Region Eigenvalue Filtering for Projected
//! Newton": after each accepted step compute the trust-region ratio
//!
//!   ρ = (E(x) − E(x + αd)) / −(α gᵀd + ½ α² dᵀH₀d),
//!
//! where H₀ is the *unfiltered* Hessian at x (dᵀH₀d is summed per element
//! from raw element Hessians, one extra element pass, no assembly). The next
//! iteration uses `Clamp` if |ρ − 1| < `adaptive_threshold` (0.01, the
//! authors' default: the quadratic model is trustworthy, so take the
//! Newton-like clamped step) and `Abs` otherwise (|λ| filtering, more
//! conservative far from the solution). The first iteration uses `Abs`, as
//! in the authors' implementation (ρ₀ = 0).

pub mod line_search;
pub mod params;
pub mod record;
pub mod solver;
