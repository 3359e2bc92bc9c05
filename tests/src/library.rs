//! The standard library's generated types, with their sources and what the
//! compiler proved about them.

use ecc_energies::*;
use ecc_runtime::Energy;

/// A generated energy with its name and source.
pub struct Lib<const D: usize> {
    /// The registry name.
    pub name: &'static str,
    /// The energy.
    pub energy: Box<dyn Energy<D>>,
    /// Its `.psi` source (the generated `SOURCE` constant).
    pub source: &'static str,
}

impl<const D: usize> Lib<D> {
    /// Whether the CAS proved Ψ unchanged by (σi, σj) → (−σj, −σi) in this
    /// dimension (recompiled from the source; false if that fails).
    pub fn sign_symmetric(&self) -> bool {
        ecc_dsl::compile(self.source, self.name)
            .ok()
            .and_then(|m| m.dim(D as u8).map(|d| d.sign_symmetric))
            .unwrap_or(false)
    }
}

macro_rules! lib {
    ($name:literal, $ty:ident) => {
        Lib {
            name: $name,
            energy: Box::new($ty::new()),
            source: $ty::SOURCE,
        }
    };
}

/// Every generated 3D energy of the library.
pub fn library3() -> Vec<Lib<3>> {
    vec![
        lib!("arap", Arap),
        lib!("corotational", CoRotational),
        lib!("sd", SymmetricDirichlet3),
        lib!("sarap", Sarap3),
        lib!("stvk", Stvk),
        lib!("neohookean", NeoHookean),
        lib!("snh", StableNeoHookean),
        lib!("ogden", Ogden),
        lib!("hencky", Hencky),
        lib!("poly", Poly),
        lib!("polyneg", PolyNeg),
    ]
}

/// Every generated 2D energy of the library.
pub fn library2() -> Vec<Lib<2>> {
    vec![
        lib!("arap", Arap),
        lib!("corotational", CoRotational),
        lib!("sd", SymmetricDirichlet2),
        lib!("sarap", Sarap2),
        lib!("mips", Mips2),
        lib!("stvk", Stvk),
        lib!("neohookean", NeoHookean),
        lib!("snh", StableNeoHookean),
        lib!("ogden", Ogden2),
        lib!("hencky", Hencky2),
        lib!("poly", Poly2),
        lib!("polyneg", PolyNeg2),
    ]
}
