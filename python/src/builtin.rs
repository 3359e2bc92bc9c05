//! The standard library of `.psi` energies (energies/psi/), embedded so that
//! `Energy.builtin("snh")` evaluates exactly the text `ecc eval
//! energies/psi/snh.psi` reads.
//!
//! Names resolve like scene files' `energy = "…"` ([`ecc_energies::entry`],
//! aliases accepted); in dimension D the file `{name}{D}.psi` is preferred
//! over `{name}.psi` (sd → sd2/sd3, ogden → ogden2 in 2D), the same choice as
//! the generated registry (`ecc_energies::by_name::<D>`).

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use ecc_dsl::{LoadError, Source};

/// (file stem, text) of every standard energy.
const FILES: &[(&str, &str)] = &[
    ("arap", include_str!("../../energies/psi/arap.psi")),
    (
        "corotational",
        include_str!("../../energies/psi/corotational.psi"),
    ),
    ("hencky", include_str!("../../energies/psi/hencky.psi")),
    ("hencky2", include_str!("../../energies/psi/hencky2.psi")),
    ("mips2", include_str!("../../energies/psi/mips2.psi")),
    (
        "neohookean",
        include_str!("../../energies/psi/neohookean.psi"),
    ),
    ("ogden", include_str!("../../energies/psi/ogden.psi")),
    ("ogden2", include_str!("../../energies/psi/ogden2.psi")),
    ("poly", include_str!("../../energies/psi/poly.psi")),
    ("poly2", include_str!("../../energies/psi/poly2.psi")),
    ("polyneg", include_str!("../../energies/psi/polyneg.psi")),
    ("polyneg2", include_str!("../../energies/psi/polyneg2.psi")),
    ("sarap2", include_str!("../../energies/psi/sarap2.psi")),
    ("sarap3", include_str!("../../energies/psi/sarap3.psi")),
    ("sd2", include_str!("../../energies/psi/sd2.psi")),
    ("sd3", include_str!("../../energies/psi/sd3.psi")),
    ("snh", include_str!("../../energies/psi/snh.psi")),
    ("stvk", include_str!("../../energies/psi/stvk.psi")),
];

/// The text of the standard file `stem.psi`.
pub fn file(stem: &str) -> Option<&'static str> {
    FILES.iter().find(|(s, _)| *s == stem).map(|(_, t)| *t)
}

/// The compiled standard file `stem.psi`, named `energies/psi/{stem}.psi`
/// in diagnostics. Compiled once per process (a batch worker parameterising
/// many meshes with `"sd"` pays the CAS once, not per job).
pub fn compiled(stem: &str) -> Option<Result<Source, LoadError>> {
    static CACHE: OnceLock<Mutex<HashMap<String, Source>>> = OnceLock::new();
    let text = file(stem)?;
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(s) = cache.lock().ok().and_then(|c| c.get(stem).cloned()) {
        return Some(Ok(s));
    }
    let src = ecc_dsl::load_text(text, &format!("energies/psi/{stem}.psi"));
    if let (Ok(s), Ok(mut c)) = (&src, cache.lock()) {
        c.insert(stem.to_string(), s.clone());
    }
    Some(src)
}

/// Canonical name of a built-in energy (aliases accepted), or `None`.
pub fn canonical(name: &str) -> Option<&'static str> {
    ecc_energies::entry(name).map(|e| e.name)
}

/// The candidate file stems for `name` in dimension `dim`, preferred first.
pub fn stems(name: &str, dim: usize) -> [String; 2] {
    [format!("{name}{dim}"), name.to_string()]
}

/// Every built-in energy name.
pub fn names() -> Vec<&'static str> {
    ecc_energies::names()
}
