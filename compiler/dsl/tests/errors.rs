//! Every error kind, rendered (codespan-reporting, no colour) and snapshotted.

use ecc_dsl::{Error, compile, compile_dim};

/// Render the diagnostics of compiling `src` (all dimensions).
fn render(src: &str) -> String {
    match compile(src, "test.psi") {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(d) => d.render("test.psi", src),
    }
}

fn render_dim(src: &str, dim: u8) -> String {
    match compile_dim(src, "test.psi", dim) {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(d) => d.render("test.psi", src),
    }
}

fn kinds(src: &str) -> Vec<Error> {
    compile(src, "test.psi")
        .err()
        .map(|d| d.errors)
        .unwrap_or_default()
}

#[test]
fn syntax_missing_operand() {
    insta::assert_snapshot!(render("param mu = 1\npsi = mu * (I2 - )\n"));
}

#[test]
fn syntax_unbalanced_and_stray_tokens() {
    insta::assert_snapshot!(render("psi = (I2 - 2*I1 + d\n"));
    insta::assert_snapshot!(render("psi = I2 $ I1\n"));
    insta::assert_snapshot!(render("param mu 1.0\npsi = mu*I2\n"));
}

#[test]
fn unknown_identifier_suggests_closest_name() {
    insta::assert_snapshot!(render("param lambda = 1\npsi = lamda*(I2 - d)\n"));
    insta::assert_snapshot!(render("psi = i2 - 2*I1 + d\n"));
}

#[test]
fn unknown_identifier_defined_later() {
    insta::assert_snapshot!(render("psi = K*I2\nlet K = 2\n"));
}

#[test]
fn unknown_function() {
    insta::assert_snapshot!(render("psi = ln(I3)\n"));
    insta::assert_snapshot!(render("psi = pow(I3)\n"));
}

#[test]
fn redefinitions_point_at_both() {
    insta::assert_snapshot!(render("let a = I1\nlet a = I2\npsi = a\n"));
    insta::assert_snapshot!(render("psi = I2\npsi = I1\n"));
    insta::assert_snapshot!(render("param mu = 1\nlet mu = 2\npsi = mu*I2\n"));
}

#[test]
fn reserved_names() {
    insta::assert_snapshot!(render("let I1 = 2\npsi = I1\n"));
    insta::assert_snapshot!(render("param log = 2\npsi = I2\n"));
    // Aliases may be shadowed (the issue's own example does `let J = I3`).
    assert!(compile("let J = I3\nlet IC = I2\npsi = IC - J", "x").is_ok());
}

#[test]
fn missing_psi() {
    insta::assert_snapshot!(render("param mu = 1\nlet a = mu*I2\n"));
    insta::assert_snapshot!(render("# only a comment\n"));
}

#[test]
fn stretch_beyond_dimension() {
    insta::assert_snapshot!(render(
        "dim 2\npsi = (s1 - 1)^2 + (s2 - 1)^2 + (s3 - 1)^2\n"
    ));
    insta::assert_snapshot!(render_dim("psi = s1^2 + s2^2 + s3^2\n", 2));
}

#[test]
fn literal_division_by_zero() {
    insta::assert_snapshot!(render("psi = I2/0\n"));
    insta::assert_snapshot!(render("psi = I1/(2 - 2) + I2/(I3 - I3)\n"));
    insta::assert_snapshot!(render("psi = I2/(d - 3)\n"));
    insta::assert_snapshot!(render("psi = 0^-1*I2\n"));
    insta::assert_snapshot!(render("psi = log(I3 - I3) + I2\n"));
}

#[test]
fn non_isotropic_stretch_energy() {
    insta::assert_snapshot!(render("dim 3\npsi = s1^2 + 2*s2^2 + s3^2\n"));
    insta::assert_snapshot!(render("psi = (s1 - 1)^2 + (s2 - 1)^2\n"));
    // Non-rational: decided numerically.
    insta::assert_snapshot!(render("dim 2\npsi = log(s1) + 2*log(s2)\n"));
}

#[test]
fn parameter_defaults_must_be_finite_constants() {
    insta::assert_snapshot!(render("param mu = I1\npsi = mu*I2\n"));
    insta::assert_snapshot!(render("param k = exp(1000)\npsi = k*I2\n"));
    insta::assert_snapshot!(render("param k = 1/0\npsi = k*I2\n"));
    assert!(compile("param k = sqrt(2)*exp(1)/3\npsi = k*I2", "x").is_ok());
}

#[test]
fn bad_and_mismatched_dimension() {
    insta::assert_snapshot!(render("dim 4\npsi = I2\n"));
    insta::assert_snapshot!(render("dim 2\ndim 3\npsi = I2\n"));
    insta::assert_snapshot!(render_dim("dim 3\npsi = I2\n", 2));
}

#[test]
fn all_errors_of_a_file_are_reported() {
    let src =
        "param mu = 1\nlet a = mu*(I2 - \nlet b = I2/0\npsi = mu*aa + bogus(I1) + b\npsi = I1\n";
    let errs = kinds(src);
    assert!(errs.len() >= 4, "{errs:?}");
    insta::assert_snapshot!(render(src));
}

#[test]
fn semicolons_separate_statements_like_newlines() {
    let src = "param mu = 1.0; let a = mu*I2; psi = a - 2*mu*I1 + mu*d";
    let m = compile(src, "semi").unwrap_or_else(|e| panic!("{}", e.render("semi", src)));
    assert_eq!(m.params[0].name, "mu");
    insta::assert_snapshot!(render("param mu = 1.0; psi = mu*I2 +; let x = 2"));
}

#[test]
fn every_error_variant_is_exercised() {
    // Guard: the snapshots above cover each variant at least once.
    let samples = [
        "psi = (",
        "psi = q",
        "psi = f(I1)",
        "psi = pow(I1)",
        "let a = 1\nlet a = 2\npsi = a",
        "let d = 1\npsi = I1",
        "let a = 1",
        "dim 2\npsi = s3",
        "psi = 1/0",
        "psi = log(0)",
        "dim 2\npsi = s1",
        "param a = I1\npsi = a",
        "param a = exp(1000)\npsi = a",
        "dim 5\npsi = I1",
    ];
    let mut seen: Vec<std::mem::Discriminant<Error>> = Vec::new();
    for s in samples {
        for e in kinds(s) {
            let d = std::mem::discriminant(&e);
            if !seen.contains(&d) {
                seen.push(d);
            }
        }
    }
    if let Err(d) = compile_dim("dim 3\npsi = I1", "x", 2) {
        seen.extend(d.errors.iter().map(std::mem::discriminant));
    }
    seen.sort_by_key(|d| format!("{d:?}"));
    seen.dedup();
    assert_eq!(
        seen.len(),
        15,
        "every Error variant should be produced by some input"
    );
}
