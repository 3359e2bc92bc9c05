//! Snapshot tests of the generated code for the standard library (inputs:
//! `energies/psi/*.psi`; outputs: `tests/snapshots/*.snap`, reviewed and
//! checked in), plus structural checks of what each energy is specialised to.

use ecc_codegen::{GenOptions, generate_pretty, report_markdown, type_name_from_stem};

fn library(stem: &str) -> (ecc_dsl::Module, String) {
    let path = format!(
        "{}/../../energies/psi/{stem}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    let source = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let module =
        ecc_dsl::compile(&source, stem).unwrap_or_else(|d| panic!("{}", d.render(&path, &source)));
    (module, source)
}

fn code(stem: &str) -> String {
    let (module, _) = library(stem);
    generate_pretty(&module, &GenOptions::named(type_name_from_stem(stem)))
        .unwrap_or_else(|e| panic!("{stem}: {e}"))
}

/// The body of `fn spectral` for dimension `dim`.
fn spectral_body(text: &str, dim: u8) -> String {
    let marker = format!("Energy<{dim}> for");
    let start = text
        .find(&marker)
        .unwrap_or_else(|| panic!("no Energy<{dim}> impl"));
    let rest = &text[start..];
    let s = rest
        .find("fn spectral")
        .unwrap_or_else(|| panic!("no spectral"));
    let e = rest.find("fn info").unwrap_or_else(|| panic!("no info"));
    rest[s..e].to_string()
}

/// Every energy of the standard library, found by globbing
/// `energies/psi/*.psi`, so a new `.psi` file cannot be left without a
/// snapshot: its generated code (`snapshots__code@<stem>.psi.snap`) and its
/// analysis report (`snapshots__report@<stem>.psi.snap`).
#[test]
fn library_code_and_reports() {
    insta::glob!("../../../energies/psi", "*.psi", |path| {
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_else(|| panic!("{}: not a UTF-8 file name", path.display()));
        insta::assert_snapshot!("code", code(stem));
        let (module, _) = library(stem);
        insta::assert_snapshot!("report", report_markdown(&module, stem));
    });
}

/// The glob above really covers the library (guards against a glob that
/// silently matches nothing after the folders move).
#[test]
fn glob_sees_every_library_energy() {
    let dir = format!("{}/../../energies/psi", env!("CARGO_MANIFEST_DIR"));
    let count = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "psi"))
        .count();
    assert!(count >= 18, "only {count} energies in {dir}");
}

#[test]
fn arap_needs_no_scaling_block_work() {
    let text = code("arap");
    for dim in [2, 3] {
        let body = spectral_body(&text, dim);
        let twos = vec!["2.0"; dim as usize].join(", ");
        assert!(
            body.contains(&format!("ScaleBlock::Diagonal([{twos}])")),
            "{body}"
        );
        assert!(
            !body.contains("LIMIT_TOL"),
            "ARAP has no removable singularity"
        );
        assert!(!body.contains("i3"), "ARAP never needs I3:\n{body}");
    }
}

#[test]
fn decoupled_energies_are_diagonal_and_coupled_ones_full() {
    for (stem, dim, diagonal) in [
        ("sd2", 2, true),
        ("sd3", 3, true),
        ("arap", 3, true),
        ("mips2", 2, false),
        ("snh", 3, false),
        ("ogden", 3, false),
    ] {
        let body = spectral_body(&code(stem), dim);
        assert_eq!(
            body.contains("ScaleBlock::Diagonal"),
            diagonal,
            "{stem} {dim}D"
        );
        assert_eq!(
            body.contains("ScaleBlock::Full"),
            !diagonal,
            "{stem} {dim}D"
        );
    }
}

#[test]
fn removable_singularities_are_guarded_only_where_needed() {
    // Ogden (non-integer power): flips guarded with the runtime's threshold.
    let ogden = spectral_body(&code("ogden"), 3);
    assert_eq!(ogden.matches("LIMIT_TOL").count(), 3, "{ogden}");
    // Rational energies have exact divided differences: nothing to guard.
    for stem in ["sd3", "snh", "stvk", "neohookean", "arap", "mips2"] {
        assert!(!code(stem).contains("LIMIT_TOL"), "{stem}");
    }
}

#[test]
fn integer_powers_are_products_and_sqrt_is_sqrt() {
    for stem in [
        "arap",
        "corotational",
        "sd2",
        "sd3",
        "sarap3",
        "mips2",
        "stvk",
        "neohookean",
        "snh",
        "ogden",
        "hencky",
    ] {
        let text = code(stem);
        assert!(!text.contains(".powi("), "{stem} uses powi");
        assert!(!text.contains(".powf("), "{stem} uses powf");
    }
    assert!(code("ogden").contains(".sqrt()"));
}

#[test]
fn invariants_are_computed_only_when_used() {
    let snh = code("snh");
    assert!(!snh.contains("let i1"), "SNH does not use I1");
    let hencky = code("hencky");
    assert!(!hencky.contains("let i2"), "Hencky does not use I2");
}

#[test]
fn svd_free_energies_get_psi_i2_i3() {
    assert!(code("snh").contains("fn psi_i2_i3"));
    assert!(code("sd2").contains("fn psi_i2_i3"));
    assert!(!code("sd3").contains("fn psi_i2_i3"));
    assert!(!code("arap").contains("fn psi_i2_i3"));
}

#[test]
fn header_names_the_source_and_specialisations() {
    let text = code("snh");
    assert!(text.starts_with("// @generated by ecc-codegen from `snh`"));
    assert!(text.contains("//     psi = mu/2*(IC - d)"));
    assert!(text.contains("// Parameters: mu = 1, lambda = 10."));
    assert!(text.contains("scaling block coupled"));
}
