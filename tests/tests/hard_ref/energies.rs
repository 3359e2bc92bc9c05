//! Every energy ecc ships, grouped by formula: each formula's `.psi`
//! source gives the double-double reference ([`PsiGraph`]) and every
//! implementation of it is checked against that one reference —
//!
//! * the generated type in `ecc-energies` (the standard library),
//! * the interpreted energy from the same source (`ecc-interp`, what
//!   `ecc eval`, `ecc check` and `.psi` scenes use),
//! * the hand-written runtime energy where there is one (ARAP, symmetric
//!   Dirichlet, Stable Neo-Hookean),
//! * `energy!` macro energies: the README's `I2 - 2*I1 + d` and two
//!   example energies written with the macro (a Stable Neo-Hookean item and
//!   a stretch energy with a non-integer power).

use ecc_dsl::DimIr;
use ecc_runtime::Energy;
use ecc_tests::library::{library2, library3};

use super::graph::PsiGraph;

ecc_macros::energy! {
    /// Stable Neo-Hookean through the macro's item form, custom moduli.
    pub struct MacroSnh;
    param mu = 1.3;
    param lambda = 4.1;
    let alpha = 1 + mu/lambda - mu/((d + 1)*lambda);
    psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1);
}

/// The same text as [`MacroSnh`], for the reference.
const MACRO_SNH: &str = "param mu = 1.3\nparam lambda = 4.1\n\
    let alpha = 1 + mu/lambda - mu/((d + 1)*lambda)\n\
    psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1)";

ecc_macros::energy! {
    /// A 3D stretch energy with a non-integer power (guarded flips).
    pub struct MacroPow;
    param k = 0.7;
    psi = k*(s1^2.5 + s2^2.5 + s3^2.5) - log(s1*s2*s3);
}

const MACRO_POW: &str = "param k = 0.7\npsi = k*(s1^2.5 + s2^2.5 + s3^2.5) - log(s1*s2*s3)";

/// One implementation of a formula.
pub struct Impl<const D: usize> {
    /// "generated", "interpreted", "hand-written", "macro".
    pub kind: &'static str,
    /// The energy.
    pub energy: Box<dyn Energy<D>>,
}

/// A formula with its reference and its implementations.
pub struct Formula<const D: usize> {
    /// A short name ("snh", "macro pow", …).
    pub name: String,
    /// The reference Ψ.
    pub graph: PsiGraph,
    /// The implementations.
    pub impls: Vec<Impl<D>>,
}

impl<const D: usize> Formula<D> {
    /// The compiled IR (sign symmetry, barrier).
    pub fn ir(&self) -> &DimIr {
        self.graph.ir()
    }
}

fn formula<const D: usize>(name: &str, source: &str, impls: Vec<Impl<D>>) -> Formula<D> {
    let graph = PsiGraph::new(source, D as u8, &[])
        .unwrap_or_else(|| panic!("{name} does not compile for {D}D"));
    Formula {
        name: name.to_string(),
        graph,
        impls,
    }
}

fn interpreted<const D: usize>(name: &str, source: &str) -> Impl<D> {
    let e = ecc_interp::load_source::<D>(source, &format!("{name}.psi"), &[])
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    Impl {
        kind: "interpreted",
        energy: Box::new(e),
    }
}

fn hand_written<const D: usize>(name: &str) -> Option<Impl<D>>
where
    ecc_runtime::energies::Arap: Energy<D>,
    ecc_runtime::energies::SymmetricDirichlet: Energy<D>,
    ecc_runtime::energies::StableNeoHookean: Energy<D>,
{
    use ecc_runtime::energies::*;
    let energy: Box<dyn Energy<D>> = match name {
        "arap" => Box::new(Arap),
        "sd" => Box::new(SymmetricDirichlet),
        // the library's snh.psi defaults
        "snh" => Box::new(StableNeoHookean::new(1.0, 10.0)),
        _ => return None,
    };
    Some(Impl {
        kind: "hand-written",
        energy,
    })
}

/// Every 3D formula with all its implementations.
pub fn formulas3() -> Vec<Formula<3>> {
    let mut out: Vec<Formula<3>> = library3()
        .into_iter()
        .map(|lib| {
            let mut impls = vec![
                Impl {
                    kind: "generated",
                    energy: lib.energy,
                },
                interpreted::<3>(lib.name, lib.source),
            ];
            impls.extend(hand_written::<3>(lib.name));
            formula(lib.name, lib.source, impls)
        })
        .collect();
    out.push(formula(
        "macro arap",
        "psi = I2 - 2*I1 + d",
        vec![Impl {
            kind: "macro",
            energy: Box::new(ecc_macros::energy!(I2 - 2 * I1 + d)),
        }],
    ));
    out.push(formula(
        "macro snh",
        MACRO_SNH,
        vec![Impl {
            kind: "macro",
            energy: Box::new(MacroSnh::new()),
        }],
    ));
    out.push(formula(
        "macro pow",
        MACRO_POW,
        vec![Impl {
            kind: "macro",
            energy: Box::new(MacroPow::new()),
        }],
    ));
    out
}

/// Every 2D formula with all its implementations.
pub fn formulas2() -> Vec<Formula<2>> {
    let mut out: Vec<Formula<2>> = library2()
        .into_iter()
        .map(|lib| {
            let mut impls = vec![
                Impl {
                    kind: "generated",
                    energy: lib.energy,
                },
                interpreted::<2>(lib.name, lib.source),
            ];
            impls.extend(hand_written::<2>(lib.name));
            formula(lib.name, lib.source, impls)
        })
        .collect();
    out.push(formula(
        "macro arap",
        "psi = I2 - 2*I1 + d",
        vec![Impl {
            kind: "macro",
            energy: Box::new(ecc_macros::energy!(I2 - 2 * I1 + d)),
        }],
    ));
    out.push(formula(
        "macro snh",
        MACRO_SNH,
        vec![Impl {
            kind: "macro",
            energy: Box::new(MacroSnh::new()),
        }],
    ));
    out.push(formula(
        "macro mips",
        "dim 2\npsi = I2/I3",
        vec![Impl {
            kind: "macro",
            energy: Box::new(ecc_macros::energy!(dim 2; psi = I2/I3)),
        }],
    ));
    out
}
