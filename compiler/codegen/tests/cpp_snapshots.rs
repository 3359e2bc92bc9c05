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
        let text = header(stem, CppRuntime::Include("ecc_runtime.hpp".into()));
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

#[test]
fn fibre_energies_get_the_fibre_members_and_isotropic_ones_do_not() {
    let inc = || CppRuntime::Include("ecc_runtime.hpp".into());
    for stem in ["fibre_arap", "fibre_stvk", "fibre_fung"] {
        let text = header(stem, inc());
        for member in [
            "static constexpr bool has_fibre(int d)",
            "fibre_uses(int d)",
            "::ecc::FibreDerivs fibre(double i4, double i5) const",
            "::ecc::FibreEval<3> fibre_eval(",
            "::ecc::FibreEval<2> fibre_eval(",
            "fibre_eval_tet(",
            "fibre_eval_tri(",
            "fibre_psi_f(",
            "closed-form eigensystem",
        ] {
            assert!(text.contains(member), "{stem}: no `{member}`:\n{text}");
        }
    }
    // ARAP reads sign(I4) (so I4 is computed: FibreUse::Both) but has no I4
    // derivative: the closed form still applies.
    let arap = header("fibre_arap", inc());
    assert!(arap.contains("const double sign_i4 = i4 > 0.0 ? 1.0"));
    assert!(arap.contains("d == 3 ? ::ecc::FibreUse::Both"), "{arap}");
    let stvk = header("fibre_stvk", inc());
    assert!(
        stvk.contains("(void)i4;"),
        "ψ(I5) does not read I4:\n{stvk}"
    );
    assert!(stvk.contains("d == 3 ? ::ecc::FibreUse::I5"), "{stvk}");
    let snh = header("snh", inc());
    assert!(!snh.contains("fibre"), "no fibre members without `fiber`");
}

#[test]
fn a_fibre_energy_with_i4_terms_is_emitted_with_the_numeric_block() {
    let src = "fiber a\nparam k = 1.5\npsi = k*(I4 - 1)^2 + (I5 - 1)^2\n";
    let m = ecc_dsl::compile(src, "x").expect("compiles");
    let text = generate_cpp(&m, &CppOptions::named("Mixed")).expect("emitted");
    assert!(text.contains("::ecc::FibreUse::Both"));
    assert!(text.contains("fibre_eval filters the Hessian by a d²×d² eigensolve"));
    assert!(text.contains(CPP_RUNTIME), "runtime inlined");
}
