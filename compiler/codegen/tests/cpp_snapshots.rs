//! Snapshot tests of the emitted C++ for every standard-library energy
//! (`energies/psi/*.psi`, runtime referenced by `#include` so the snapshots
//! show the generated part only), plus structural checks of what the C++
//! printer shares with the Rust one.

use ecc_codegen::{CppOptions, CppRuntime, cpp::CPP_RUNTIME, generate_cpp, type_name_from_stem};

fn header(stem: &str, runtime: CppRuntime) -> String {
    header_or_error(stem, runtime).unwrap_or_else(|e| panic!("{stem}: {e}"))
}

fn header_or_error(stem: &str, runtime: CppRuntime) -> Result<String, ecc_codegen::CodegenError> {
    let path = format!(
        "{}/../../energies/psi/{stem}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    let source = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let module =
        ecc_dsl::compile(&source, stem).unwrap_or_else(|d| panic!("{}", d.render(&path, &source)));
    let opts = CppOptions {
        type_name: type_name_from_stem(stem),
        energy_name: None,
        runtime,
    };
    generate_cpp(&module, &opts)
}

#[test]
fn generated_headers() {
    insta::glob!("../../../energies/psi", "*.psi", |path| {
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("a file stem");
        // Fibre energies (`fibre_*.psi`) are a clear error, not a header.
        let text = if stem.starts_with("fibre_") {
            match header_or_error(stem, CppRuntime::Include("ecc_runtime.hpp".into())) {
                Err(e) => format!("error: {e}"),
                Ok(_) => panic!("{stem}: a fibre energy must be refused by --emit cpp"),
            }
        } else {
            header(stem, CppRuntime::Include("ecc_runtime.hpp".into()))
        };
        insta::assert_snapshot!("cpp", text);
    });
}

#[test]
fn the_default_header_is_self_contained() {
    let text = header("snh", CppRuntime::Inline);
    assert!(text.contains(CPP_RUNTIME), "runtime inlined");
    assert!(!text.contains("#include \"ecc_runtime.hpp\""));
    // Only standard headers are included.
    for line in text.lines().filter(|l| l.starts_with("#include")) {
        assert!(line.contains('<'), "non-standard include: {line}");
    }
}

#[test]
fn arap_has_no_scaling_block_work_and_a_pole_at_antipodal_stretches() {
    let text = header("arap", CppRuntime::Include("ecc_runtime.hpp".into()));
    assert!(text.contains("out.diagonal = true;"));
    assert!(
        !text.contains("LIMIT_TOL"),
        "ARAP has no removable singularity"
    );
    assert!(
        text.contains("(s2 + s3 == 0.0) ? ::ecc::infinity()"),
        "the twist pole is +∞ on its plane:\n{text}"
    );
}

#[test]
fn guarded_pairs_use_the_runtime_threshold_lazily() {
    let text = header("ogden", CppRuntime::Include("ecc_runtime.hpp".into()));
    assert!(text.contains("<= ::ecc::LIMIT_TOL * std::fmax(std::fabs(s"));
    assert!(text.contains("double flip_23;"));
}

#[test]
fn bad_type_names_are_refused() {
    let src = "psi = I2 - 2*I1 + d\n";
    let m = ecc_dsl::compile(src, "x").expect("compiles");
    for bad in ["int", "1abc", "a-b", "", "_X", "std"] {
        assert!(
            generate_cpp(&m, &CppOptions::named(bad)).is_err(),
            "{bad:?}"
        );
    }
    assert!(generate_cpp(&m, &CppOptions::named("MyArap")).is_ok());
}
