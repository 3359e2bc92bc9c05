//! The build-script helper on real files.

use ecc_codegen::GenOptions;
use ecc_codegen::build::{BuildError, compile_file, compile_file_to};

#[test]
fn compiles_a_file_and_rewrites_only_on_change() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let src = dir.path().join("my_energy.psi");
    std::fs::write(&src, "param k = 2\npsi = k*(I2 - 2*I1 + d)\n")
        .unwrap_or_else(|e| panic!("{e}"));
    let opts = GenOptions::named("MyEnergy");
    let out = compile_file_to(&src, dir.path(), &opts).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out, dir.path().join("my_energy.rs"));
    let text = std::fs::read_to_string(&out).unwrap_or_else(|e| panic!("{e}"));
    assert!(text.contains("pub struct MyEnergy {"));
    assert!(text.contains("impl ::ecc_runtime::Energy<3> for MyEnergy"));
    let before = std::fs::metadata(&out).and_then(|m| m.modified()).ok();
    std::thread::sleep(std::time::Duration::from_millis(20));
    compile_file_to(&src, dir.path(), &opts).unwrap_or_else(|e| panic!("{e}"));
    let after = std::fs::metadata(&out).and_then(|m| m.modified()).ok();
    assert_eq!(before, after, "unchanged output must not be rewritten");
}

#[test]
fn errors_are_rendered_and_returned() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let src = dir.path().join("bad.psi");
    std::fs::write(&src, "psi = I2 - 2*I7\n").unwrap_or_else(|e| panic!("{e}"));
    match compile_file_to(&src, dir.path(), &GenOptions::named("Bad")) {
        Err(BuildError::Compile { rendered, .. }) => {
            assert!(rendered.contains("unknown identifier `I7`"), "{rendered}");
            assert!(rendered.contains("bad.psi:1:"), "{rendered}");
        }
        other => panic!("expected a compile error, got {other:?}"),
    }
    assert!(!dir.path().join("bad.rs").exists());
    let missing = dir.path().join("missing.psi");
    assert!(matches!(
        compile_file_to(&missing, dir.path(), &GenOptions::default()),
        Err(BuildError::Io { .. })
    ));
}

#[test]
fn outside_a_build_script_there_is_no_out_dir() {
    // Cargo sets OUT_DIR for build scripts, not for this test binary.
    if std::env::var_os("OUT_DIR").is_none() {
        assert!(matches!(
            compile_file("whatever.psi"),
            Err(BuildError::NoOutDir)
        ));
    }
}
