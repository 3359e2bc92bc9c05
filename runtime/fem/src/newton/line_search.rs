//! Backtracking Armijo line search that tolerates `+∞`.
//!
//! From α₀ (1, or `barrier_safety`·α_max for barrier objectives) try
//! α₀, βα₀, β²α₀, … and accept the first α with
//!
//!   E(x + α d) ≤ E(x) + c₁ α ∇Eᵀd.
//!
//! `+∞` (an element left its domain) and NaN simply fail the test ("step too
//! long"). Near convergence the predicted decrease c₁α|∇Eᵀd| can fall below
//! the rounding level of E itself (≈ 1e3·ε·|E| for sums over many
//! elements); the test is then meaningless, so if even α₀·|∇Eᵀd| is below
//! that level and E(x + α₀d) is within it of E(x), the step α₀ is accepted
//! and flagged `noise_limited`: the gradient-norm test, not the energy,
//! decides convergence from there.
//!
//! **Extrapolation** (opt-in, `extrapolation`). When the full step α = 1
//! passed and nothing bounds the step, the minimiser of the parabola
//! through E(0), E'(0) = ∇Eᵀd and E(1) (Nocedal & Wright 2006, eq. 3.57),
//!
//!   φ(α) = E(0) + α ∇Eᵀd + c α²,  c = E(1) − E(0) − ∇Eᵀd,  α* = −∇Eᵀd / 2c,
//!
//! is tried once (at most `EXTRAPOLATION_CAP`) and kept if it lowers E
//! further. On the symmetric Dirichlet parameterisations the Newton step is
//! short: the energy along d keeps falling to α ≈ 1.25–1.5 at most
//! iterations, and the gradient falls by only ≈ 0.42 per step whatever the
//! Hessian modification (clamp, abs, exact element projection, shifted raw
//! Hessian): a compressed element's Newton step on σ⁻² grows σ by 4/3 and
//! ∇ ∝ σ⁻³, (3/4)³ = 0.42. Near a minimiser where the Newton model is
//! exact, α* → 1 and nothing is tried.

/// Largest extrapolated step: the range the inversion-free bound searches
/// (`STEP_SEARCH_MAX` of `crate::elastic`), so an unbounded α_max means no
/// element inverts up to it.
pub(crate) const EXTRAPOLATION_CAP: f64 = 2.0;

/// Smallest extrapolated step worth an energy evaluation.
pub(crate) const MIN_EXTRAPOLATION: f64 = 1.1;

/// The extrapolated step α* of the module docs after the full step passed
/// with E(1) = `e1` (`slope` = ∇Eᵀd < 0), or `None` when the
/// inversion-free bound `alpha_max` is finite (a barrier is near: the
/// longer step would move towards it) or α* < [`MIN_EXTRAPOLATION`]. A
/// parabola without a minimum (c ≤ 0) gives the cap.
pub(crate) fn extrapolation(e0: f64, slope: f64, e1: f64, alpha_max: f64) -> Option<f64> {
    if alpha_max.is_finite() || slope.is_nan() || slope >= 0.0 || !e1.is_finite() {
        return None;
    }
    let c = e1 - e0 - slope;
    let alpha = if c > 0.0 {
        (-slope / (2.0 * c)).min(EXTRAPOLATION_CAP)
    } else {
        EXTRAPOLATION_CAP
    };
    (alpha >= MIN_EXTRAPOLATION).then_some(alpha)
}

/// Accepted step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Accepted {
    pub alpha: f64,
    pub energy: f64,
    pub evals: usize,
    pub noise_limited: bool,
}

/// Line-search constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Armijo {
    pub c1: f64,
    pub beta: f64,
    pub min_step: f64,
}

/// The first trial step α₀ = min(1, `safety`·α_max) for the inversion-free
/// bound α_max (+∞ when nothing bounds the step); a non-finite `safety`
/// gives α₀ = 1 (TinyAD's `line_search`: the barrier's +∞ rejects the steps
/// past α_max during backtracking).
pub(crate) fn initial_step(alpha_max: f64, safety: f64) -> f64 {
    if alpha_max.is_finite() && safety.is_finite() {
        (safety * alpha_max).min(1.0)
    } else {
        1.0
    }
}

/// Run the search. `energy_at(α)` evaluates E(x + α d). `slope` = ∇Eᵀd < 0.
/// On failure returns the last α tried.
pub(crate) fn backtrack(
    e0: f64,
    slope: f64,
    alpha0: f64,
    c: Armijo,
    mut energy_at: impl FnMut(f64) -> f64,
) -> Result<Accepted, f64> {
    let noise = 1e3 * f64::EPSILON * e0.abs().max(f64::MIN_POSITIVE);
    let mut alpha = alpha0;
    let mut evals = 0;
    while alpha >= c.min_step {
        let e = energy_at(alpha);
        evals += 1;
        if e.is_finite() && e <= e0 + c.c1 * alpha * slope {
            return Ok(Accepted {
                alpha,
                energy: e,
                evals,
                noise_limited: false,
            });
        }
        if evals == 1 && e.is_finite() && (alpha * slope).abs() <= noise && (e - e0).abs() <= noise
        {
            return Ok(Accepted {
                alpha,
                energy: e,
                evals,
                noise_limited: true,
            });
        }
        alpha *= c.beta;
    }
    Err(alpha / c.beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: Armijo = Armijo {
        c1: 1e-4,
        beta: 0.5,
        min_step: 1e-12,
    };

    #[test]
    fn initial_step_is_the_safe_fraction_of_the_bound_or_one() {
        assert_eq!(initial_step(0.5, 0.9), 0.45);
        assert_eq!(initial_step(2.0, 0.9), 1.0);
        assert_eq!(initial_step(f64::INFINITY, 0.9), 1.0);
        // TinyAD's rule: always 1, even with a bound below 1 (or at 0)
        assert_eq!(initial_step(0.5, f64::INFINITY), 1.0);
        assert_eq!(initial_step(0.0, f64::INFINITY), 1.0);
        // with it, the backtracking lands below the barrier at 0.8^k
        let f = |a: f64| if a >= 0.5 { f64::INFINITY } else { 1.0 - a };
        let c = Armijo { beta: 0.8, ..C };
        let r = backtrack(1.0, -1.0, initial_step(0.5, f64::INFINITY), c, f).unwrap();
        assert_eq!(r.evals, 5);
        assert!((r.alpha - 0.8f64.powi(4)).abs() < 1e-15);
    }

    #[test]
    fn extrapolation_finds_the_minimum_of_a_parabola() {
        // E(α) = (1.5 − α)², E(0) = 2.25, slope −3, E(1) = 0.25: α* = 1.5
        let a = extrapolation(2.25, -3.0, 0.25, f64::INFINITY).unwrap();
        assert!((a - 1.5).abs() < 1e-15, "{a}");
        // the exact Newton step of a quadratic: α* = 1, nothing to try
        assert_eq!(extrapolation(1.0, -2.0, 0.0, f64::INFINITY), None);
        // beyond the cap
        assert_eq!(
            extrapolation(25.0, -10.0, 16.0, f64::INFINITY),
            Some(EXTRAPOLATION_CAP)
        );
        // concave along d: the cap
        assert_eq!(
            extrapolation(1.0, -1.0, -0.5, f64::INFINITY),
            Some(EXTRAPOLATION_CAP)
        );
        // a finite inversion-free bound, a bad slope or E(1): nothing
        assert_eq!(extrapolation(2.25, -3.0, 0.25, 3.0), None);
        assert_eq!(extrapolation(2.25, 0.0, 0.25, f64::INFINITY), None);
        assert_eq!(extrapolation(2.25, f64::NAN, 0.25, f64::INFINITY), None);
        assert_eq!(extrapolation(2.25, -3.0, f64::NAN, f64::INFINITY), None);
    }

    #[test]
    fn quadratic_takes_the_full_step() {
        // E(α) = (1 − α)², slope −2
        let r = backtrack(1.0, -2.0, 1.0, C, |a| (1.0 - a) * (1.0 - a)).unwrap();
        assert_eq!(r.alpha, 1.0);
        assert_eq!(r.evals, 1);
    }

    #[test]
    fn infinity_means_too_long() {
        // barrier at α = 0.3: E = −log(0.3 − α) shifted, +∞ beyond
        let f = |a: f64| if a >= 0.3 { f64::INFINITY } else { 1.0 - a };
        let r = backtrack(1.0, -1.0, 1.0, C, f).unwrap();
        assert_eq!(r.alpha, 0.25);
        assert_eq!(r.evals, 3);
    }

    #[test]
    fn failure_reports_the_last_step() {
        let r = backtrack(1.0, -1.0, 1.0, C, |_| 2.0);
        assert!(matches!(r, Err(a) if a < 1e-11));
    }

    #[test]
    fn rounding_level_steps_are_accepted_and_flagged() {
        let e0 = 2.0;
        let r = backtrack(e0, -1e-20, 1.0, C, |_| e0 + 1e-14).unwrap();
        assert!(r.noise_limited);
        // a real increase is not noise
        assert!(backtrack(e0, -1e-20, 1.0, C, |_| e0 + 1e-6).is_err());
    }
}
