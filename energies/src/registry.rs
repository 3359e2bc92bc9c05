//! Look energies up by name (scene files say `energy = "snh"`).

use std::any::Any;

use ecc_runtime::{Energy, FibreEnergy};

use crate::generated::*;

/// A registry entry: a name and the dimensions it exists in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// The name scenes and the CLI use.
    pub name: &'static str,
    /// Other accepted spellings.
    pub aliases: &'static [&'static str],
    /// Has a 2D version.
    pub d2: bool,
    /// Has a 3D version.
    pub d3: bool,
    /// One line about the energy.
    pub summary: &'static str,
    /// A fibre energy ψ(I4, I5) (`fiber a` in its `.psi`): built by
    /// [`fibre_by_name`], not [`by_name`].
    pub fibre: bool,
}

/// Every built-in energy, in a stable order.
pub const ENTRIES: &[Entry] = &[
    Entry {
        name: "arap",
        aliases: &["as_rigid_as_possible"],
        d2: true,
        d3: true,
        summary: "as-rigid-as-possible, ‖F − R‖²",
        fibre: false,
    },
    Entry {
        name: "corotational",
        aliases: &["corot", "co_rotational"],
        d2: true,
        d3: true,
        summary: "co-rotational, μ‖F − R‖² + κ/2 tr²(S − I)",
        fibre: false,
    },
    Entry {
        name: "sd",
        aliases: &["symmetric_dirichlet", "sd2", "sd3"],
        d2: true,
        d3: true,
        summary: "symmetric Dirichlet, (‖F‖² + ‖F⁻¹‖²)/2 (barrier)",
        fibre: false,
    },
    Entry {
        name: "sarap",
        aliases: &["symmetric_arap", "sarap2", "sarap3"],
        d2: true,
        d3: true,
        summary: "symmetric ARAP (barrier)",
        fibre: false,
    },
    Entry {
        name: "mips",
        aliases: &["mips2"],
        d2: true,
        d3: false,
        summary: "MIPS, ‖F‖²/det F (2D, barrier)",
        fibre: false,
    },
    Entry {
        name: "stvk",
        aliases: &["st_venant_kirchhoff"],
        d2: true,
        d3: true,
        summary: "St. Venant–Kirchhoff",
        fibre: false,
    },
    Entry {
        name: "neohookean",
        aliases: &["nh", "neo_hookean"],
        d2: true,
        d3: true,
        summary: "compressible Neo-Hookean with log J (barrier)",
        fibre: false,
    },
    Entry {
        name: "snh",
        aliases: &["stable_neohookean", "stable_neo_hookean"],
        d2: true,
        d3: true,
        summary: "stable Neo-Hookean (Smith et al. 2018)",
        fibre: false,
    },
    Entry {
        name: "ogden",
        aliases: &["ogden2"],
        d2: true,
        d3: true,
        summary: "one-term compressible Ogden, α = 1.5 (barrier)",
        fibre: false,
    },
    Entry {
        name: "hencky",
        aliases: &["hencky2"],
        d2: true,
        d3: true,
        summary: "Hencky (logarithmic strain, barrier)",
        fibre: false,
    },
    Entry {
        name: "poly",
        aliases: &["poly2"],
        d2: true,
        d3: true,
        summary: "Σ(σi² − 1)²",
        fibre: false,
    },
    Entry {
        name: "polyneg",
        aliases: &["polyneg2"],
        d2: true,
        d3: true,
        summary: "Σ(σi − 1/σi)² (barrier)",
        fibre: false,
    },
    Entry {
        name: "fibre_arap",
        aliases: &["fiber_arap", "anisotropic_arap"],
        d2: true,
        d3: true,
        summary: "fibre: anisotropic ARAP, μ/2 (√I5 − sign(I4))² (Kim et al. 2019)",
        fibre: true,
    },
    Entry {
        name: "fibre_stvk",
        aliases: &["fiber_stvk", "anisotropic_stvk"],
        d2: true,
        d3: true,
        summary: "fibre: anisotropic StVK term, μ/2 (I5 − 1)²",
        fibre: true,
    },
    Entry {
        name: "fibre_fung",
        aliases: &["fiber_fung", "anisotropic_fung"],
        d2: true,
        d3: true,
        summary: "fibre: Fung-type exponential, k1/(2k2) (exp(k2 (I5 − 1)²) − 1)",
        fibre: true,
    },
];

/// The names of the isotropic energies ([`by_name`]), in a stable order.
pub fn names() -> Vec<&'static str> {
    ENTRIES
        .iter()
        .filter(|e| !e.fibre)
        .map(|e| e.name)
        .collect()
}

/// The names of the fibre energies ([`fibre_by_name`]), in a stable order.
pub fn fibre_names() -> Vec<&'static str> {
    ENTRIES.iter().filter(|e| e.fibre).map(|e| e.name).collect()
}

/// The entry called `name` (or one of its aliases; case-insensitive, `-`
/// and ` ` read as `_`).
pub fn entry(name: &str) -> Option<&'static Entry> {
    let key: String = name
        .trim()
        .chars()
        .map(|c| {
            if c == '-' || c == ' ' {
                '_'
            } else {
                c.to_ascii_lowercase()
            }
        })
        .collect();
    ENTRIES
        .iter()
        .find(|e| e.name == key || e.aliases.contains(&key.as_str()))
}

/// A constructor of a d-dimensional energy with its default parameters.
type New<const D: usize> = fn() -> Box<dyn Energy<D>>;

/// `Some(constructor)` of the generated type `$t` (coerced to `dyn Energy<D>`).
macro_rules! new {
    ($t:ident) => {
        Some(|| Box::new($t::new()))
    };
}

/// The constructors of the isotropic [`ENTRIES`], in the same order: (2D, 3D).
const NEW: [(Option<New<2>>, Option<New<3>>); 12] = [
    (new!(Arap), new!(Arap)),
    (new!(CoRotational), new!(CoRotational)),
    (new!(SymmetricDirichlet2), new!(SymmetricDirichlet3)),
    (new!(Sarap2), new!(Sarap3)),
    (new!(Mips2), None),
    (new!(Stvk), new!(Stvk)),
    (new!(NeoHookean), new!(NeoHookean)),
    (new!(StableNeoHookean), new!(StableNeoHookean)),
    (new!(Ogden2), new!(Ogden)),
    (new!(Hencky2), new!(Hencky)),
    (new!(Poly2), new!(Poly)),
    (new!(PolyNeg2), new!(PolyNeg)),
];

/// A fresh d-dimensional energy (d = `D`, 2 or 3) by registry name or
/// alias (see [`entry`]), with its default parameters; `None` for an
/// unknown name, a dimension the energy does not exist in, or another `D`.
pub fn by_name<const D: usize>(name: &str) -> Option<Box<dyn Energy<D>>> {
    let key = entry(name).filter(|e| !e.fibre)?.name;
    let (new2, new3) = NEW[ENTRIES
        .iter()
        .filter(|e| !e.fibre)
        .position(|e| e.name == key)?];
    // Box<dyn Energy<2>> *is* Box<dyn Energy<D>> when D = 2: the downcast
    // only names that identity for the generic signature.
    let made: Box<dyn Any> = match D {
        2 => Box::new(new2?()),
        3 => Box::new(new3?()),
        _ => return None,
    };
    made.downcast::<Box<dyn Energy<D>>>().ok().map(|b| *b)
}

/// A constructor of a d-dimensional fibre energy with its default parameters.
type NewFibre<const D: usize> = fn() -> Box<dyn FibreEnergy<D>>;

/// The constructors of the fibre [`ENTRIES`], in the same order: (2D, 3D).
const NEW_FIBRE: [(NewFibre<2>, NewFibre<3>); 3] = [
    (
        || Box::new(AnisotropicArap::new()),
        || Box::new(AnisotropicArap::new()),
    ),
    (
        || Box::new(AnisotropicStvk::new()),
        || Box::new(AnisotropicStvk::new()),
    ),
    (
        || Box::new(AnisotropicFung::new()),
        || Box::new(AnisotropicFung::new()),
    ),
];

/// A fresh d-dimensional fibre energy ψ(I4, I5) (generated from
/// `energies/psi/fibre_*.psi`) by registry name or alias, with its default
/// parameters; `None` for an unknown or isotropic name or another `D`.
pub fn fibre_by_name<const D: usize>(name: &str) -> Option<Box<dyn FibreEnergy<D>>> {
    let key = entry(name).filter(|e| e.fibre)?.name;
    let (new2, new3) = NEW_FIBRE[ENTRIES
        .iter()
        .filter(|e| e.fibre)
        .position(|e| e.name == key)?];
    let made: Box<dyn Any> = match D {
        2 => Box::new(new2()),
        3 => Box::new(new3()),
        _ => return None,
    };
    made.downcast::<Box<dyn FibreEnergy<D>>>().ok().map(|b| *b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_resolves_in_its_dimensions() {
        for e in ENTRIES {
            let (d2, d3) = if e.fibre {
                (
                    fibre_by_name::<2>(e.name).is_some(),
                    fibre_by_name::<3>(e.name).is_some(),
                )
            } else {
                (
                    by_name::<2>(e.name).is_some(),
                    by_name::<3>(e.name).is_some(),
                )
            };
            assert_eq!(d2, e.d2, "{} in 2D", e.name);
            assert_eq!(d3, e.d3, "{} in 3D", e.name);
            // One kind each: an isotropic name is no fibre energy and back.
            assert!(by_name::<3>(e.name).is_none() || fibre_by_name::<3>(e.name).is_none());
            for a in e.aliases {
                assert_eq!(entry(a).map(|x| x.name), Some(e.name));
            }
        }
    }

    #[test]
    fn lookup_is_forgiving_about_spelling_but_not_names() {
        assert_eq!(entry("Stable-Neo-Hookean").map(|e| e.name), Some("snh"));
        assert_eq!(entry(" SD ").map(|e| e.name), Some("sd"));
        assert!(entry("snhh").is_none());
        assert!(by_name::<3>("mips").is_none());
        assert!(by_name::<4>("snh").is_none());
    }

    #[test]
    fn every_constructor_builds_the_named_energy() {
        assert_eq!(NEW.len() + NEW_FIBRE.len(), ENTRIES.len());
        for e in ENTRIES.iter().filter(|e| e.fibre) {
            for a in std::iter::once(&e.name).chain(e.aliases) {
                let x = fibre_by_name::<3>(a).unwrap();
                assert_eq!(entry(x.name()).map(|y| y.name), Some(e.name), "{a}");
            }
        }
        for e in ENTRIES {
            for a in std::iter::once(&e.name).chain(e.aliases) {
                if let Some(x) = by_name::<2>(a) {
                    assert_eq!(entry(x.name()).map(|y| y.name), Some(e.name), "{a} in 2D");
                }
                if let Some(x) = by_name::<3>(a) {
                    assert_eq!(entry(x.name()).map(|y| y.name), Some(e.name), "{a} in 3D");
                }
            }
        }
    }

    #[test]
    fn names_are_unique() {
        let mut all: Vec<&str> = ENTRIES
            .iter()
            .flat_map(|e| std::iter::once(e.name).chain(e.aliases.iter().copied()))
            .collect();
        let n = all.len();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), n);
    }
}
