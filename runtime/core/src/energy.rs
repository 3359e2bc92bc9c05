//! The trait every energy implements: hand-written, generated, or interpreted.

use crate::spectral::Spectral;

/// Static facts about an energy that solvers use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnergyInfo {
    /// Ψ is singular on det F = 0 (Ψ → +∞ as det F → 0⁺; SD, SARAP, MIPS,
    /// Neo-Hookean with log J, Ogden with fractional powers, …). Ψ is `+∞`
    /// on det F = 0 and wherever the formula is undefined (log J for J < 0);
    /// where the formula is defined for det F < 0 (SD) it keeps its value
    /// there, but that region is unreachable for a solver that starts
    /// uninverted: solvers must keep every element uninverted
    /// (inversion-free line search).
    pub barrier: bool,
    /// Ψ depends on F only through I2 = ‖F‖² and I3 = det F, so `psi_f` can
    /// skip the SVD (a line-search fast path).
    pub svd_free_psi: bool,
}

/// A parameter could not be set.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamError {
    /// The energy has no parameter of that name; `known` lists the ones it has.
    Unknown { name: String, known: Vec<String> },
    /// The value is NaN or infinite.
    NotFinite { name: String, value: f64 },
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ParamError::Unknown { name, known } => {
                write!(f, "unknown parameter `{name}`")?;
                if known.is_empty() {
                    write!(f, " (this energy has no parameters)")
                } else {
                    write!(f, " (known: {})", known.join(", "))
                }
            }
            ParamError::NotFinite { name, value } => {
                write!(f, "parameter `{name}` must be finite, got {value}")
            }
        }
    }
}

impl std::error::Error for ParamError {}

/// An isotropic energy density Ψ(F) in dimension `D` (2 or 3), described in
/// stretch space.
///
/// `sigma` is always the *signed* singular value vector of F, ordered as the
/// runtime's signed SVD returns it: |σ_0| ≥ |σ_1| ≥ |σ_2| and only the last
/// entry may be negative (det F < 0). Implementations must not assume more
/// than that (in particular σ may be repeated, zero, or negative in the last slot).
pub trait Energy<const D: usize>: Send + Sync {
    /// A short human-readable name (for reports and summaries).
    fn name(&self) -> &str;

    /// Ψ(σ): the energy density. `+∞` outside the energy's domain, never NaN.
    fn psi(&self, sigma: &[f64; D]) -> f64;

    /// Ψ, ∂Ψ/∂σ and the stretch-space Hessian eigen data at σ.
    fn spectral(&self, sigma: &[f64; D]) -> Spectral<D>;

    /// Static facts used by solvers.
    fn info(&self) -> EnergyInfo {
        EnergyInfo::default()
    }

    /// Ψ evaluated from the invariants I2 = ‖F‖² and I3 = det F alone, when
    /// `info().svd_free_psi` is true (line-search fast path). The default says
    /// "not available".
    fn psi_i2_i3(&self, _i2: f64, _i3: f64) -> Option<f64> {
        None
    }

    /// The energy's parameters and their current values.
    fn params(&self) -> Vec<(String, f64)> {
        Vec::new()
    }

    /// Override a parameter at run time.
    fn set_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        if !value.is_finite() {
            return Err(ParamError::NotFinite {
                name: name.to_string(),
                value,
            });
        }
        Err(ParamError::Unknown {
            name: name.to_string(),
            known: self.params().into_iter().map(|(n, _)| n).collect(),
        })
    }
}
