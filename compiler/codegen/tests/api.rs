//! The public API: options, errors, determinism, purity of the output.

use ecc_codegen::{
    CodegenError, GenOptions, Visibility, generate, generate_pretty, report_markdown,
};

fn module(src: &str) -> ecc_dsl::Module {
    ecc_dsl::compile(src, "test").unwrap_or_else(|d| panic!("{}", d.render("test", src)))
}

#[test]
fn output_is_deterministic_and_parses() {
    let m = module("param mu = 2\npsi = mu*(I2 - 2*I1 + d) + log(I3)^2");
    let a = generate_pretty(&m, &GenOptions::named("E")).unwrap_or_else(|e| panic!("{e}"));
    let b = generate_pretty(
        &module("param mu = 2\npsi = mu*(I2 - 2*I1 + d) + log(I3)^2"),
        &GenOptions::named("E"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a, b);
    let tokens = generate(&m, &GenOptions::named("E")).unwrap_or_else(|e| panic!("{e}"));
    assert!(syn::parse2::<syn::File>(tokens).is_ok());
}

#[test]
fn bad_type_names_and_paths_are_errors() {
    let m = module("psi = I2");
    for bad in ["", "struct", "1abc", "a b", "Self"] {
        let err = generate(&m, &GenOptions::named(bad)).err();
        assert_eq!(
            err,
            Some(CodegenError::InvalidTypeName { name: bad.into() }),
            "{bad:?}"
        );
    }
    let opts = GenOptions {
        runtime_path: "::ecc runtime".into(),
        ..GenOptions::named("E")
    };
    assert!(matches!(
        generate(&m, &opts),
        Err(CodegenError::InvalidRuntimePath { .. })
    ));
}

#[test]
fn a_module_without_dimensions_is_an_error() {
    let mut m = module("psi = I2");
    m.dims.clear();
    m.skipped = vec![(2, "test".into())];
    let err = generate(&m, &GenOptions::default()).err();
    assert!(matches!(err, Some(CodegenError::NoDimensions { .. })));
    assert!(
        err.map(|e| e.to_string())
            .unwrap_or_default()
            .contains("2D skipped: test")
    );
}

#[test]
fn malformed_ir_is_an_error_not_a_panic() {
    let mut m = module("psi = I2");
    m.dims[0].spectral.grad.pop();
    assert!(matches!(
        generate(&m, &GenOptions::default()),
        Err(CodegenError::MalformedIr { .. })
    ));
    let mut m = module("psi = I2");
    m.dims[0].psi = ecc_dsl::Id(1_000_000);
    assert!(matches!(
        generate(&m, &GenOptions::default()),
        Err(CodegenError::MalformedIr { .. })
    ));
}

#[test]
fn options_shape_the_output() {
    let m = module("param mu = 1\npsi = mu*I2");
    let opts = GenOptions {
        type_name: "Quad".into(),
        vis: Visibility::Crate,
        runtime_path: "crate".into(),
        doc: Some("A quadratic.".into()),
        energy_name: Some("quadratic".into()),
    };
    let text = generate_pretty(&m, &opts).unwrap_or_else(|e| panic!("{e}"));
    assert!(text.contains("pub(crate) struct Quad {"));
    assert!(text.contains("impl crate::Energy<2> for Quad"));
    assert!(text.contains("/// A quadratic."));
    assert!(text.contains("\"quadratic\""));
    assert!(text.contains("pub mu: f64"));
    let private = generate_pretty(
        &m,
        &GenOptions {
            vis: Visibility::Private,
            ..GenOptions::named("Q")
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(private.contains("\nstruct Q {"));
    assert!(private.contains("#[allow(dead_code)]"));
}

#[test]
fn keyword_and_uppercase_parameter_names_stay_usable() {
    let m = module("param E = 2\nparam nu = 0.3\npsi = E*nu*I2");
    let text = generate_pretty(&m, &GenOptions::named("K")).unwrap_or_else(|e| panic!("{e}"));
    assert!(text.contains("pub E: f64"));
    assert!(text.contains("let e = self.E;"));
    assert!(text.contains("\"E\" => self.E = value"));
}

#[test]
fn report_lists_modes_and_singularities() {
    let m = module("dim 2\npsi = I2/I3");
    let r = report_markdown(&m, "mips");
    assert!(r.starts_with("# Energy `mips`"));
    assert!(r.contains("## 2D"));
    assert!(r.contains("coupled"));
    assert!(r.contains("| twist | (s1, s2) | closed form |"));
    assert!(r.contains("### Singularities"));
    assert!(r.contains("- 3D not compiled"));
}
