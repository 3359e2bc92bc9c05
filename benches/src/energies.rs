//! The energies the report measures, each in its three forms: generated
//! (ecc-energies, compiled Rust), interpreted (ecc-interp: the `ecc eval`
//! path, the same `.psi` text compiled at run time), and the CAS graph (for
//! the generic f32/f64 kernel and the high-precision reference).
//!
//! 2D: ARAP, symmetric Dirichlet, stable Neo-Hookean, StVK, MIPS, Ogden.
//! 3D: the same without MIPS (the standard library's MIPS is 2D only:
//! ‖F‖²/det F is not the 3D MIPS energy, which has a different exponent).
//! Parameters are the `.psi` defaults (SNH μ = 1, λ = 10; StVK and Ogden μ = λ = 1).

use std::sync::Arc;

use ecc_dsl::Module;
use ecc_runtime::Energy;

use crate::generic_kernel::GenericEnergy;

/// One energy in dimension `D`.
pub struct BenchEnergy<const D: usize> {
    /// Short name used in tables.
    pub name: &'static str,
    /// `.psi` file name (in `energies/psi/`).
    pub file: &'static str,
    /// Generated code (ecc-energies).
    pub generated: Arc<dyn Energy<D>>,
    /// Interpreted at run time (ecc-interp).
    pub interp: Arc<dyn Energy<D>>,
    /// The compiled module (CAS graph).
    pub module: Module,
    /// The CAS graph in any precision.
    pub generic: GenericEnergy,
    /// Ψ is +∞ for det F ≤ 0.
    pub barrier: bool,
}

/// What can go wrong building the energy set (a broken `.psi` file).
#[derive(Debug)]
pub struct EnergySetError(pub String);

impl std::fmt::Display for EnergySetError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "energy set: {}", self.0)
    }
}

impl std::error::Error for EnergySetError {}

const ARAP: &str = include_str!("../../energies/psi/arap.psi");
const SD2: &str = include_str!("../../energies/psi/sd2.psi");
const SD3: &str = include_str!("../../energies/psi/sd3.psi");
const SNH: &str = include_str!("../../energies/psi/snh.psi");
const STVK: &str = include_str!("../../energies/psi/stvk.psi");
const MIPS2: &str = include_str!("../../energies/psi/mips2.psi");
const OGDEN: &str = include_str!("../../energies/psi/ogden.psi");
const OGDEN2: &str = include_str!("../../energies/psi/ogden2.psi");

fn build<const D: usize>(
    name: &'static str,
    file: &'static str,
    source: &str,
    generated: Arc<dyn Energy<D>>,
) -> Result<BenchEnergy<D>, EnergySetError> {
    let err = |m: String| EnergySetError(format!("{file}: {m}"));
    let stem = ecc_interp::energy_name(file);
    let module = ecc_interp::compile_module(source, file, &stem).map_err(|e| err(e.to_string()))?;
    let interp =
        ecc_interp::energy_from_module::<D>(&module, file, &[]).map_err(|e| err(e.to_string()))?;
    let ir = module
        .dim(D as u8)
        .ok_or_else(|| err(format!("no {D}D form")))?;
    let generic = GenericEnergy::new(ir, &module.param_defaults());
    Ok(BenchEnergy {
        name,
        file,
        barrier: ir.barrier,
        generated,
        interp: Arc::new(interp),
        generic,
        module,
    })
}

/// The 2D set.
pub fn energies2() -> Result<Vec<BenchEnergy<2>>, EnergySetError> {
    use ecc_energies as g;
    Ok(vec![
        build("ARAP", "arap.psi", ARAP, Arc::new(g::Arap::new()))?,
        build(
            "SD",
            "sd2.psi",
            SD2,
            Arc::new(g::SymmetricDirichlet2::new()),
        )?,
        build("SNH", "snh.psi", SNH, Arc::new(g::StableNeoHookean::new()))?,
        build("StVK", "stvk.psi", STVK, Arc::new(g::Stvk::new()))?,
        build("MIPS", "mips2.psi", MIPS2, Arc::new(g::Mips2::new()))?,
        build("Ogden", "ogden2.psi", OGDEN2, Arc::new(g::Ogden2::new()))?,
    ])
}

/// The 3D set.
pub fn energies3() -> Result<Vec<BenchEnergy<3>>, EnergySetError> {
    use ecc_energies as g;
    Ok(vec![
        build("ARAP", "arap.psi", ARAP, Arc::new(g::Arap::new()))?,
        build(
            "SD",
            "sd3.psi",
            SD3,
            Arc::new(g::SymmetricDirichlet3::new()),
        )?,
        build("SNH", "snh.psi", SNH, Arc::new(g::StableNeoHookean::new()))?,
        build("StVK", "stvk.psi", STVK, Arc::new(g::Stvk::new()))?,
        build("Ogden", "ogden.psi", OGDEN, Arc::new(g::Ogden::new()))?,
    ])
}
