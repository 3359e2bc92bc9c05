//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

/// The public test meshes: `$ECC_DATA_DIR`, default the repository's `data/`.
pub fn data(name: &str) -> PathBuf {
    let path = ecc_mesh::data_file(name);
    assert!(
        path.exists(),
        "test mesh {} is missing (set ECC_DATA_DIR to the folder with SOURCES.md)",
        path.display()
    );
    path
}
