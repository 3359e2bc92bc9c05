//! Where the public test meshes live.
//!
//! The repository carries copies of the public meshes listed in
//! `data/SOURCES.md` (sources, licences, checks). [`data_dir`] finds them:
//! `$ECC_DATA_DIR` when set, otherwise the `data/` folder of this checkout.

use std::path::PathBuf;

/// The folder holding the public meshes: `$ECC_DATA_DIR`, else `<repo>/data`.
pub fn data_dir() -> PathBuf {
    std::env::var_os("ECC_DATA_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data")))
}

/// `data_dir().join(name)`.
pub fn data_file(name: &str) -> PathBuf {
    data_dir().join(name)
}
