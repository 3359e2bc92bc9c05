//! Hand-written fibre energies ψ(I4, I5) (see [`crate::fibre`]).
//!
//! | energy | ψ | eigenvalues (eqs. P3–P4 of `fibre::point`) |
//! |---|---|---|
//! | [`FibreArap`] | μ/2 (√I5 − S(I4))², S = sign | along μ, across μ(1 − S/√I5) |
//! | [`FibreStvk`] | μ/2 (I5 − 1)² | along 2μ(I5 − 1) + 4μ I5, across 2μ(I5 − 1) |
//! | [`FibreFung`] | k1/(2k2) (exp(k2 (I5 − 1)²) − 1) | along 2e k1 (I5 − 1) + 4 e k1 (1 + 2k2 (I5 − 1)²) I5, across 2 e k1 (I5 − 1), e = exp(k2 (I5 − 1)²) |
//!
//! The first two are Kim, de Goes & Iben 2019's anisotropic ARAP and the
//! StVK fibre term of *Dynamic Deformables*, as implemented in HOBAK
//! (`ANISOTROPIC_ARAP.cpp`: ψ = ½μ(√I5 − S)², S = +1 if I4 > 0 else −1;
//! `ANISOTROPIC_STVK.cpp`: ψ = ½μ(I5 − 1)²; both checked in the source,
//! their `hessian`/`clampedHessian`s use these two eigenvalues; the
//! papers' equation numbers could not be checked here, see
//! [`crate::fibre`]); the third is the Holzapfel–Gasser–Ogden fibre term
//! (HOBAK's `ANISOTROPIC_FUNG` is the different μ(exp(I5 − 1) − I5),
//! tested as `HobakFung` in runtime/core/tests/fibre.rs).
//! ARAP's S(I4) = +1 for I4 > 0 and −1 otherwise (HOBAK's convention, which
//! also decides I4 = 0); S is piecewise constant, so ψ4 = ψ44 = ψ45 = 0 and
//! its Hessian takes the closed form although it reads I4. ψ jumps where I4
//! changes sign with F a ≠ 0 (the published energy does; the solver's line
//! search sees the jump like any other energy increase).

use super::param_error;
use crate::energy::ParamError;
use crate::fibre::{FibreDerivs, FibreEnergy, FibreUse};

/// Anisotropic ARAP: ψ = μ/2 (√I5 − S(I4))² (Kim, de Goes & Iben 2019;
/// HOBAK's `ANISOTROPIC_ARAP::psi`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreArap {
    /// Stiffness μ.
    pub mu: f64,
}

/// Anisotropic StVK fibre term: ψ = μ/2 (I5 − 1)² (HOBAK's
/// `ANISOTROPIC_STVK::psi`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreStvk {
    /// Stiffness μ.
    pub mu: f64,
}

/// Fung-type exponential fibre term: ψ = k1/(2 k2) (exp(k2 (I5 − 1)²) − 1)
/// (Holzapfel, Gasser, Ogden 2000); k2 → 0 tends to StVK with μ = k1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreFung {
    /// Stiffness k1.
    pub k1: f64,
    /// Exponential stiffening k2 (> 0).
    pub k2: f64,
}

impl Default for FibreArap {
    fn default() -> Self {
        FibreArap { mu: 1.0 }
    }
}
impl Default for FibreStvk {
    fn default() -> Self {
        FibreStvk { mu: 1.0 }
    }
}
impl Default for FibreFung {
    fn default() -> Self {
        FibreFung { k1: 1.0, k2: 1.0 }
    }
}

fn arap(mu: f64, i4: f64, i5: f64) -> FibreDerivs {
    let s = if i4 > 0.0 { 1.0 } else { -1.0 };
    let r = i5.sqrt();
    FibreDerivs {
        psi: 0.5 * mu * (r - s) * (r - s),
        d4: 0.0,
        d5: 0.5 * mu * (1.0 - s / r),
        d44: 0.0,
        d45: 0.0,
        d55: 0.25 * mu * s / (r * i5),
    }
}

fn stvk(mu: f64, i5: f64) -> FibreDerivs {
    FibreDerivs {
        psi: 0.5 * mu * (i5 - 1.0) * (i5 - 1.0),
        d5: mu * (i5 - 1.0),
        d55: mu,
        ..FibreDerivs::default()
    }
}

fn fung(k1: f64, k2: f64, i5: f64) -> FibreDerivs {
    let t = i5 - 1.0;
    let e = (k2 * t * t).exp();
    if !e.is_finite() {
        // exp overflowed: ψ = +∞ (a huge stretch), no derivatives
        return FibreDerivs {
            psi: f64::INFINITY,
            ..FibreDerivs::default()
        };
    }
    FibreDerivs {
        psi: k1 / (2.0 * k2) * (e - 1.0),
        d5: k1 * t * e,
        d55: k1 * e * (1.0 + 2.0 * k2 * t * t),
        ..FibreDerivs::default()
    }
}

/// Set the one parameter named `name` among `fields`.
fn set(fields: &mut [(&str, &mut f64)], name: &str, value: f64) -> Result<(), ParamError> {
    let known: Vec<&str> = fields.iter().map(|(n, _)| *n).collect();
    match fields.iter_mut().find(|(n, _)| *n == name) {
        Some((_, v)) if value.is_finite() => {
            **v = value;
            Ok(())
        }
        _ => Err(param_error(name, value, &known)),
    }
}

macro_rules! fibre_impl {
    ($t:ty, $name:literal, $uses:expr, |$s:ident, $i4:ident, $i5:ident| $body:expr,
     [$($p:ident),*]) => {
        impl<const D: usize> FibreEnergy<D> for $t {
            fn name(&self) -> &str {
                $name
            }
            fn fibre(&self, $i4: f64, $i5: f64) -> FibreDerivs {
                let $s = self;
                $body
            }
            fn uses(&self) -> FibreUse {
                $uses
            }
            fn fibre_params(&self) -> Vec<(String, f64)> {
                vec![$((stringify!($p).to_string(), self.$p)),*]
            }
            fn set_fibre_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
                set(&mut [$((stringify!($p), &mut self.$p)),*], name, value)
            }
        }
    };
}

fibre_impl!(
    FibreArap,
    "fibre-arap",
    FibreUse::Both,
    |s, i4, i5| arap(s.mu, i4, i5),
    [mu]
);
fibre_impl!(
    FibreStvk,
    "fibre-stvk",
    FibreUse::I5,
    |s, _i4, i5| stvk(s.mu, i5),
    [mu]
);
fibre_impl!(
    FibreFung,
    "fibre-fung",
    FibreUse::I5,
    |s, _i4, i5| fung(s.k1, s.k2, i5),
    [k1, k2]
);

/// The hand-written fibre energies by name (`fibre-arap`, `fibre-stvk`,
/// `fibre-fung`), default parameters; `None` for an unknown name.
pub fn fibre_by_name<const D: usize>(name: &str) -> Option<Box<dyn FibreEnergy<D>>> {
    Some(match name {
        "fibre-arap" | "fiber-arap" => Box::new(FibreArap::default()),
        "fibre-stvk" | "fiber-stvk" => Box::new(FibreStvk::default()),
        "fibre-fung" | "fiber-fung" => Box::new(FibreFung::default()),
        _ => return None,
    })
}

/// The names [`fibre_by_name`] knows.
pub const FIBRE_NAMES: &[&str] = &["fibre-arap", "fibre-stvk", "fibre-fung"];
