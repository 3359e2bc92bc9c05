//! `ecc FILE.psi --emit rs|report`: generated Rust parses (every library
//! energy) and compiles against ecc-runtime in a separate crate; `-o` writes
//! atomically; the report has derivatives, eigenvalues and singularities.

mod common;

use std::path::Path;
use std::process::Command;

use common::{lib, library, ok};

#[test]
fn generated_rust_parses_for_every_library_energy() {
    for (name, path) in library() {
        let code = ok(&[&path, "--emit", "rs"]);
        let file: syn::File =
            syn::parse_file(&code).unwrap_or_else(|e| panic!("{name}: {e}\n{code}"));
        let has_impl = |d: &str| {
            file.items.iter().any(|i| match i {
                syn::Item::Impl(imp) => imp
                    .trait_
                    .as_ref()
                    .is_some_and(|(_, p, _)| quote_path(p).ends_with(&format!("Energy<{d}>"))),
                _ => false,
            })
        };
        assert!(has_impl("2") || has_impl("3"), "{name}: no Energy impl");
    }
}

fn quote_path(p: &syn::Path) -> String {
    p.segments
        .iter()
        .map(|s| {
            let args = match &s.arguments {
                syn::PathArguments::AngleBracketed(a) => {
                    let inner: Vec<String> = a
                        .args
                        .iter()
                        .map(|g| match g {
                            syn::GenericArgument::Const(syn::Expr::Lit(l)) => match &l.lit {
                                syn::Lit::Int(i) => i.base10_digits().to_string(),
                                _ => "?".into(),
                            },
                            _ => "?".into(),
                        })
                        .collect();
                    format!("<{}>", inner.join(","))
                }
                _ => String::new(),
            };
            format!("{}{args}", s.ident)
        })
        .collect::<Vec<_>>()
        .join("::")
}

#[test]
fn output_files_are_written_atomically_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("snh.rs");
    let out_s = out.display().to_string();
    let stdout = ok(&[&lib("snh"), "--emit", "rs", "-o", &out_s, "--name", "MySnh"]);
    assert!(stdout.is_empty(), "nothing on stdout with -o");
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("pub struct MySnh"), "type named by --name");
    assert_eq!(
        text.trim_end(),
        ok(&[&lib("snh"), "--emit", "rs", "--name", "MySnh"]).trim_end()
    );
    // Overwrite in place; no temporary file is left behind.
    ok(&[&lib("arap"), "--emit", "rs", "-o", &out_s]);
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("pub struct Arap")
    );
    let report = dir.path().join("report.md");
    ok(&[
        &lib("sd3"),
        "--emit",
        "report",
        "-o",
        &report.display().to_string(),
    ]);
    let entries: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(entries.len(), 2, "{entries:?}");
}

#[test]
fn the_report_shows_derivatives_eigenvalues_and_singularities() {
    let sd3 = ok(&[&lib("sd3"), "--emit", "report"]);
    for part in ["∂Ψ/∂I1", "∂²Ψ/∂I1", "twist", "flip", "I3"] {
        assert!(sd3.contains(part), "sd3 report lacks `{part}`:\n{sd3}");
    }
    assert!(
        sd3.to_lowercase().contains("singular"),
        "sd3 report lists singularities:\n{sd3}"
    );
    let arap = ok(&[&lib("arap"), "--emit", "report"]);
    assert!(
        arap.contains("s1 + s2")
            || arap.contains("s1+s2")
            || arap.contains("σ1 + σ2")
            || arap.contains("I1"),
        "{arap}"
    );
    let ogden = ok(&[&lib("ogden"), "--emit", "report"]);
    assert!(
        ogden.contains("∂Ψ/∂s1"),
        "stretch derivatives in the report:\n{ogden}"
    );
    assert!(
        ogden.to_lowercase().contains("guarded") || ogden.to_lowercase().contains("limit"),
        "{ogden}"
    );
}

/// The workspace root (for the path dependency and the lock file).
fn workspace_root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Emit every library energy into one scratch crate that depends on
/// ecc-runtime by path, and `cargo check` it (offline, pinned to the
/// workspace's lock file, with its own persistent target dir so later runs
/// are incremental).
#[test]
fn generated_rust_compiles_in_a_crate_that_depends_on_the_runtime() {
    let dir = tempfile::tempdir().unwrap();
    let root = workspace_root().canonicalize().unwrap();
    let src = dir.path().join("src");
    std::fs::create_dir(&src).unwrap();
    let mut lib_rs =
        String::from("//! Scratch crate: every library energy emitted by `ecc --emit rs`.\n");
    let mut uses = String::new();
    for (name, path) in library() {
        let module = format!("e_{}", name.replace('-', "_"));
        let out = src.join(format!("{module}.rs"));
        ok(&[&path, "--emit", "rs", "-o", &out.display().to_string()]);
        lib_rs.push_str(&format!("pub mod {module};\n"));
        uses.push_str(&format!(
            "    let _ = {module}::{}::default();\n",
            ecc_codegen::type_name_from_stem(&name)
        ));
    }
    lib_rs.push_str(&format!(
        "\n/// Every type can be constructed.\npub fn all() {{\n{uses}}}\n"
    ));
    std::fs::write(src.join("lib.rs"), lib_rs).unwrap();
    let manifest = format!(
        "[package]\nname = \"ecc-emit-check\"\nversion = \"0.0.0\"\nedition = \"2024\"\npublish = false\n\n[dependencies]\necc-runtime = {{ path = {:?} }}\n\n[workspace]\n",
        root.join("runtime/core").display().to_string()
    );
    std::fs::write(dir.path().join("Cargo.toml"), manifest).unwrap();
    std::fs::copy(root.join("Cargo.lock"), dir.path().join("Cargo.lock")).unwrap();
    // Next to the binary under test: <target>/<profile>/ecc → <target>/emit-check.
    let exe = Path::new(env!("CARGO_BIN_EXE_ecc"));
    let target = exe
        .parent()
        .and_then(Path::parent)
        .map_or_else(|| dir.path().join("target"), |t| t.join("emit-check"));
    let out = Command::new(env!("CARGO"))
        .args(["check", "--offline", "--quiet", "--manifest-path"])
        .arg(dir.path().join("Cargo.toml"))
        .env("CARGO_TARGET_DIR", &target)
        .env_remove("RUSTFLAGS")
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "generated code does not compile:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
