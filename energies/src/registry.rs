//! Look energies up by name (scene files say `energy = "snh"`).

use ecc_runtime::Energy;

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
}

/// Every built-in energy, in a stable order.
pub const ENTRIES: &[Entry] = &[
    Entry {
        name: "arap",
        aliases: &["as_rigid_as_possible"],
        d2: true,
        d3: true,
        summary: "as-rigid-as-possible, ‖F − R‖²",
    },
    Entry {
        name: "corotational",
        aliases: &["corot", "co_rotational"],
        d2: true,
        d3: true,
        summary: "co-rotational, μ‖F − R‖² + κ/2 tr²(S − I)",
    },
    Entry {
        name: "sd",
        aliases: &["symmetric_dirichlet", "sd2", "sd3"],
        d2: true,
        d3: true,
        summary: "symmetric Dirichlet, (‖F‖² + ‖F⁻¹‖²)/2 (barrier)",
    },
    Entry {
        name: "sarap",
        aliases: &["symmetric_arap", "sarap2", "sarap3"],
        d2: true,
        d3: true,
        summary: "symmetric ARAP (barrier)",
    },
    Entry {
        name: "mips",
        aliases: &["mips2"],
        d2: true,
        d3: false,
        summary: "MIPS, ‖F‖²/det F (2D, barrier)",
    },
    Entry {
        name: "stvk",
        aliases: &["st_venant_kirchhoff"],
        d2: true,
        d3: true,
        summary: "St. Venant–Kirchhoff",
    },
    Entry {
        name: "neohookean",
        aliases: &["nh", "neo_hookean"],
        d2: true,
        d3: true,
        summary: "compressible Neo-Hookean with log J (barrier)",
    },
    Entry {
        name: "snh",
        aliases: &["stable_neohookean", "stable_neo_hookean"],
        d2: true,
        d3: true,
        summary: "stable Neo-Hookean (Smith et al. 2018)",
    },
    Entry {
        name: "ogden",
        aliases: &["ogden2"],
        d2: true,
        d3: true,
        summary: "one-term compressible Ogden, α = 1.5 (barrier)",
    },
    Entry {
        name: "hencky",
        aliases: &["hencky2"],
        d2: true,
        d3: true,
        summary: "Hencky (logarithmic strain, barrier)",
    },
    Entry {
        name: "poly",
        aliases: &["poly2"],
        d2: true,
        d3: true,
        summary: "Σ(σi² − 1)²",
    },
    Entry {
        name: "polyneg",
        aliases: &["polyneg2"],
        d2: true,
        d3: true,
        summary: "Σ(σi − 1/σi)² (barrier)",
    },
];

/// The registry names, in a stable order.
pub fn names() -> Vec<&'static str> {
    ENTRIES.iter().map(|e| e.name).collect()
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

/// A fresh 2D energy by registry name, with its default parameters.
pub fn by_name2(name: &str) -> Option<Box<dyn Energy<2>>> {
    Some(match entry(name)?.name {
        "arap" => Box::new(Arap::new()),
        "corotational" => Box::new(CoRotational::new()),
        "sd" => Box::new(SymmetricDirichlet2::new()),
        "sarap" => Box::new(Sarap2::new()),
        "mips" => Box::new(Mips2::new()),
        "stvk" => Box::new(Stvk::new()),
        "neohookean" => Box::new(NeoHookean::new()),
        "snh" => Box::new(StableNeoHookean::new()),
        "ogden" => Box::new(Ogden2::new()),
        "hencky" => Box::new(Hencky2::new()),
        "poly" => Box::new(Poly2::new()),
        "polyneg" => Box::new(PolyNeg2::new()),
        _ => return None,
    })
}

/// A fresh 3D energy by registry name, with its default parameters.
pub fn by_name3(name: &str) -> Option<Box<dyn Energy<3>>> {
    Some(match entry(name)?.name {
        "arap" => Box::new(Arap::new()),
        "corotational" => Box::new(CoRotational::new()),
        "sd" => Box::new(SymmetricDirichlet3::new()),
        "sarap" => Box::new(Sarap3::new()),
        "stvk" => Box::new(Stvk::new()),
        "neohookean" => Box::new(NeoHookean::new()),
        "snh" => Box::new(StableNeoHookean::new()),
        "ogden" => Box::new(Ogden::new()),
        "hencky" => Box::new(Hencky::new()),
        "poly" => Box::new(Poly::new()),
        "polyneg" => Box::new(PolyNeg::new()),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_resolves_in_its_dimensions() {
        for e in ENTRIES {
            assert_eq!(by_name2(e.name).is_some(), e.d2, "{} in 2D", e.name);
            assert_eq!(by_name3(e.name).is_some(), e.d3, "{} in 3D", e.name);
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
        assert!(by_name3("mips").is_none());
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
