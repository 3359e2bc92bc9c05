//! Property tests (proptest) of the front end as a hostile user drives it:
//! any text made of the language's own tokens — most of it nonsense, some
//! of it valid — compiles or fails with diagnostics, never panics; every
//! diagnostic's span lies inside the text on character boundaries, and
//! the rendered report names the file, line and column. Valid energies
//! built from random isotropic formulas always compile, with finite
//! parameter defaults and a Ψ that evaluates to a number or ±∞/NaN (never
//! a panic) at the rest state.
//!
//! Failures are shrunk and saved in `compiler/dsl/tests/prop_front.proptest-regressions`
//! (committed, replayed first on every run). Raw bytes are fuzzed by
//! `fuzz/fuzz_targets/psi.rs` (cargo fuzz).

use proptest::prelude::*;

const TOKENS: &[&str] = &[
    "psi",
    "=",
    "param",
    "let",
    "dim",
    "2",
    "3",
    "I1",
    "I2",
    "I3",
    "IC",
    "IIC",
    "IIIC",
    "J",
    "s1",
    "s2",
    "s3",
    "s4",
    "d",
    "mu",
    "lambda",
    "k",
    "(",
    ")",
    "+",
    "-",
    "*",
    "/",
    "^",
    "log",
    "exp",
    "sqrt",
    "pow",
    "foo",
    ",",
    "\n",
    ";",
    "0",
    "1",
    "0.5",
    ".5",
    "1e300",
    "1e-300",
    "1e999",
    "2.5",
    "10^400",
    " ",
    "  ",
    "#",
    "# comment\n",
    "é",
    "\t",
    "=",
    "==",
    ")(",
    "psi =",
    "1/0",
    "(((",
    ")))",
    "--",
    "^-",
    "∞",
];

/// Text built from tokens (and a few raw characters).
fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(
        prop_oneof![
            8 => prop::sample::select(TOKENS).prop_map(str::to_string),
            1 => any::<char>().prop_map(|c| c.to_string()),
        ],
        0..48,
    )
    .prop_map(|v| v.concat())
}

/// A random isotropic expression in the invariants, parameters and
/// symmetric functions of the stretches (always valid and isotropic).
fn formula() -> impl Strategy<Value = String> {
    let leaf = prop::sample::select(
        &[
            "I1",
            "I2",
            "I3",
            "IC",
            "J",
            "d",
            "mu",
            "lambda",
            "2",
            "0.5",
            "3",
            "(s1 + s2 + s3)",
            "(s1^2 + s2^2 + s3^2)",
            "(s1*s2*s3)",
        ][..],
    )
    .prop_map(str::to_string);
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} + {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} - {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("{a}*{b}")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("{a}/({b} + 2)")),
            (inner.clone(), 1u32..4).prop_map(|(a, n)| format!("({a})^{n}")),
            inner.clone().prop_map(|a| format!("log(1 + ({a})^2)")),
            inner.clone().prop_map(|a| format!("sqrt(1 + ({a})^2)")),
        ]
    })
}

fn check_diagnostics(src: &str, d: &ecc_dsl::Diagnostics) -> Result<(), TestCaseError> {
    prop_assert!(!d.errors.is_empty(), "an error without diagnostics");
    for e in &d.errors {
        let s = e.span();
        prop_assert!(
            s.start <= s.end && s.end <= src.len(),
            "span {s:?} outside {src:?}"
        );
        prop_assert!(
            src.is_char_boundary(s.start) && src.is_char_boundary(s.end),
            "span {s:?} splits a character in {src:?}"
        );
    }
    let text = d.render("soup.psi", src);
    prop_assert!(text.contains("error"), "{text}");
    prop_assert!(text.contains("soup.psi"), "no file name in:\n{text}");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(160))]

    #[test]
    fn any_token_soup_compiles_or_fails_with_located_diagnostics(src in token_soup()) {
        match ecc_dsl::compile(&src, "soup") {
            Ok(m) => {
                prop_assert!(!m.dims.is_empty() || !m.skipped.is_empty());
                prop_assert!(m.param_defaults().iter().all(|v| v.is_finite()), "{src:?}");
            }
            Err(d) => check_diagnostics(&src, &d)?,
        }
    }

    #[test]
    fn any_statement_soup_after_a_valid_energy_is_handled(src in token_soup()) {
        let text = format!("param mu = 1\nparam lambda = 2\npsi = I2 - 2*I1 + d\n{src}");
        if let Err(d) = ecc_dsl::compile(&text, "soup") {
            check_diagnostics(&text, &d)?;
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_isotropic_formulas_compile(f in formula()) {
        let src = format!("param mu = 1.5\nparam lambda = 0.7\npsi = {f}\n");
        let m = ecc_dsl::compile(&src, "random");
        let m = match m {
            Ok(m) => m,
            Err(d) => return Err(TestCaseError::fail(d.render("random.psi", &src))),
        };
        // 3D always; 2D too unless the formula uses s3
        prop_assert!(m.dim(3).is_some(), "{}", src);
        prop_assert_eq!(m.dim(2).is_some(), !f.contains("s3"), "{}", src);
        for ir in &m.dims {
            let env = ecc_dsl::Env::new(ir.dim, &[1.0, 1.0, 1.0], &m.param_defaults());
            // a number, ±∞ or NaN (the formula may divide by zero): just no panic
            let _ = ecc_dsl::eval(&ir.graph, ir.psi, &env);
        }
    }
}
