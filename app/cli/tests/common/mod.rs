//! Helpers shared by the binary-level tests: run the built `ecc`, find the library.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The `.psi` standard library.
pub fn library_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi"))
}

/// Path of a library energy by stem.
pub fn lib(name: &str) -> String {
    library_dir()
        .join(format!("{name}.psi"))
        .display()
        .to_string()
}

/// Every library energy as (stem, path), sorted.
pub fn library() -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(library_dir())
        .expect("library directory")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "psi"))
        .map(|p| {
            (
                p.file_stem().unwrap().to_string_lossy().into_owned(),
                p.display().to_string(),
            )
        })
        .collect();
    out.sort();
    assert!(
        out.len() >= 12,
        "expected the whole library, found {}",
        out.len()
    );
    out
}

/// Run `ecc` with `args`.
pub fn ecc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(args)
        .output()
        .expect("the ecc binary runs")
}

/// Standard output as text, asserting success.
pub fn ok(args: &[&str]) -> String {
    let out = ecc(args);
    assert!(
        out.status.success(),
        "ecc {args:?} failed ({:?}):\n{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Standard error as text, asserting a non-zero exit, no output on stdout
/// and no panic.
pub fn fails(args: &[&str]) -> String {
    let out = ecc(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "ecc {args:?} should fail");
    assert_ne!(
        out.status.code(),
        Some(101),
        "ecc {args:?} panicked:\n{stderr}"
    );
    assert!(
        !stderr.contains("panicked"),
        "ecc {args:?} panicked:\n{stderr}"
    );
    assert!(!stderr.trim().is_empty(), "ecc {args:?}: empty stderr");
    stderr
}
