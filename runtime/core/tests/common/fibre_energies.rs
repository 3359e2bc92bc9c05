//! Test-only fibre energies ψ(I4, I5) with I4 terms, shared by the fibre
//! tests (the library's own fibre energies have none).

use ecc_runtime::fibre::{FibreDerivs, FibreEnergy, FibreUse};

/// A test-only ψ of I4 alone: (I4 − 1)² + 0.1 I4³.
pub struct I4Only;
impl<const D: usize> FibreEnergy<D> for I4Only {
    fn name(&self) -> &str {
        "i4-only"
    }
    fn fibre(&self, i4: f64, _i5: f64) -> FibreDerivs {
        FibreDerivs {
            psi: (i4 - 1.0).powi(2) + 0.1 * i4.powi(3),
            d4: 2.0 * (i4 - 1.0) + 0.3 * i4 * i4,
            d44: 2.0 + 0.6 * i4,
            ..FibreDerivs::default()
        }
    }
    fn uses(&self) -> FibreUse {
        FibreUse::I4
    }
}

/// A test-only ψ of both: (I4 − 1)² + 0.3 (I5 − 1)² − 0.2 I4 I5.
pub struct Mixed;
impl<const D: usize> FibreEnergy<D> for Mixed {
    fn name(&self) -> &str {
        "mixed"
    }
    fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs {
        FibreDerivs {
            psi: (i4 - 1.0).powi(2) + 0.3 * (i5 - 1.0).powi(2) - 0.2 * i4 * i5,
            d4: 2.0 * (i4 - 1.0) - 0.2 * i5,
            d5: 0.6 * (i5 - 1.0) - 0.2 * i4,
            d44: 2.0,
            d45: -0.2,
            d55: 0.6,
        }
    }
    fn uses(&self) -> FibreUse {
        FibreUse::Both
    }
}
