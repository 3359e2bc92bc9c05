//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

/// The public test meshes: `$ECC_DATA_DIR`, default `/work/shared/data`.
pub fn data(name: &str) -> PathBuf {
    let dir = std::env::var_os("ECC_DATA_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/work/shared/data"));
    let path = dir.join(name);
    assert!(
        path.exists(),
        "test mesh {} is missing (set ECC_DATA_DIR to the folder with SOURCES.md)",
        path.display()
    );
    path
}
