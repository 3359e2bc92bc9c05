//! Generates the built-in energies from the standard library of `.psi`
//! files (`energies/psi/`) with `ecc_codegen::build`, one Rust file per
//! energy in `$OUT_DIR`, which `src/generated.rs` `include!`s.

use std::path::Path;

use ecc_codegen::GenOptions;
use ecc_codegen::build::compile_file_with;

/// (file stem, Rust type name) of every built-in energy.
const ENERGIES: &[(&str, &str)] = &[
    ("arap", "Arap"),
    ("corotational", "CoRotational"),
    ("sd2", "SymmetricDirichlet2"),
    ("sd3", "SymmetricDirichlet3"),
    ("sarap2", "Sarap2"),
    ("sarap3", "Sarap3"),
    ("mips2", "Mips2"),
    ("stvk", "Stvk"),
    ("neohookean", "NeoHookean"),
    ("snh", "StableNeoHookean"),
    ("ogden", "Ogden"),
    ("ogden2", "Ogden2"),
    ("hencky", "Hencky"),
    ("hencky2", "Hencky2"),
    ("poly", "Poly"),
    ("poly2", "Poly2"),
    ("polyneg", "PolyNeg"),
    ("polyneg2", "PolyNeg2"),
    ("fibre_arap", "AnisotropicArap"),
    ("fibre_stvk", "AnisotropicStvk"),
    ("fibre_fung", "AnisotropicFung"),
];

fn main() {
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("psi");
    println!("cargo:rerun-if-changed={}", lib.display());
    for (stem, ty) in ENERGIES {
        let path = lib.join(format!("{stem}.psi"));
        let opts = GenOptions {
            energy_name: Some(stem.to_string()),
            ..GenOptions::named(*ty)
        };
        if let Err(e) = compile_file_with(&path, &opts) {
            // The diagnostics are on stderr; fail the build with the summary.
            panic!("{e}");
        }
    }
}
