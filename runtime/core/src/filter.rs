//! Eigenvalue filters: how an indefinite Hessian is made positive semi-definite.
//!
//! A filter acts on each analytic eigenvalue λ of the F-space Hessian; the
//! filtered Hessian is Σ filter(λ) e eᵀ over the orthonormal eigenbasis, so it
//! is PSD whenever every filtered value is ≥ 0, and it equals the raw Hessian
//! wherever the raw one is already PSD (for `Clamp`, `Abs`).
//!
//! | filter | filtered value | reference |
//! |---|---|---|
//! | `None` | λ (raw Hessian, may be indefinite) | — |
//! | `Clamp` (default) | max(λ, 0) | Smith et al. 2019, Teran et al. 2005 |
//! | `ClampEps(ε)` | max(λ, ε) (strictly positive definite) | — |
//! | `Abs` | \|λ\| | Chen et al. 2024 |
//!
//! **Non-finite eigenvalues.** λ = ±∞ or NaN means the energy is genuinely
//! singular in that mode at this point (e.g. ARAP's twist 2 − 4/(σ_i+σ_j) at
//! σ_i + σ_j = 0). Every filter except `None` maps a non-finite λ to its floor
//! (0 for `Clamp`/`Abs`, ε for `ClampEps`), i.e. the mode is dropped (or made
//! ε-stiff) and no NaN/∞ ever reaches a filtered Hessian. `None` passes it
//! through unchanged: the raw Hessian is genuinely non-finite there.
//!
//! `ClampEps(ε)` with a negative or non-finite ε behaves as `Clamp` (floor 0).

/// How eigenvalues are filtered (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Filter {
    /// No filtering: the raw (possibly indefinite) Hessian.
    None,
    /// λ ↦ max(λ, 0) (the paper's projection).
    #[default]
    Clamp,
    /// λ ↦ max(λ, ε) for a small ε ≥ 0 (positive definite).
    ClampEps(f64),
    /// λ ↦ |λ| (absolute-value projection, Chen et al. 2024).
    Abs,
}

impl Filter {
    /// The smallest value this filter can output (0 for `None`, which has none).
    #[inline]
    pub fn floor(self) -> f64 {
        match self {
            Filter::ClampEps(eps) if eps.is_finite() && eps > 0.0 => eps,
            _ => 0.0,
        }
    }

    /// True for [`Filter::None`] (the raw Hessian is requested).
    #[inline]
    pub fn is_raw(self) -> bool {
        matches!(self, Filter::None)
    }

    /// The filtered eigenvalue (see the module docs for non-finite input).
    #[inline]
    pub fn apply(self, lambda: f64) -> f64 {
        match self {
            Filter::None => lambda,
            _ if !lambda.is_finite() => self.floor(),
            Filter::Clamp => lambda.max(0.0),
            Filter::ClampEps(_) => lambda.max(self.floor()),
            Filter::Abs => lambda.abs(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Filter;

    #[test]
    fn values_and_non_finite_handling() {
        assert_eq!(Filter::default(), Filter::Clamp);
        assert_eq!(Filter::None.apply(-2.0), -2.0);
        assert!(Filter::None.apply(f64::NAN).is_nan());
        assert_eq!(Filter::None.apply(f64::NEG_INFINITY), f64::NEG_INFINITY);
        assert_eq!(Filter::Clamp.apply(-2.0), 0.0);
        assert_eq!(Filter::Clamp.apply(3.0), 3.0);
        assert_eq!(Filter::ClampEps(0.5).apply(0.1), 0.5);
        assert_eq!(Filter::ClampEps(0.5).apply(3.0), 3.0);
        assert_eq!(Filter::Abs.apply(-2.0), 2.0);
        for f in [Filter::Clamp, Filter::ClampEps(1e-3), Filter::Abs] {
            for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                assert_eq!(f.apply(x), f.floor(), "{f:?} on {x}");
            }
        }
        assert_eq!(Filter::ClampEps(1e-3).floor(), 1e-3);
        // A meaningless ε falls back to the plain clamp.
        assert_eq!(Filter::ClampEps(-1.0).apply(-5.0), 0.0);
        assert_eq!(Filter::ClampEps(f64::NAN).apply(-5.0), 0.0);
        assert_eq!(Filter::ClampEps(f64::INFINITY).apply(-5.0), 0.0);
    }
}
