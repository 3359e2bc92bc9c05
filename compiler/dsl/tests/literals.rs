//! Number literals must fit an f64: one that overflows to ±∞ (`1e999`) or
//! is nonzero but below the normal range (`1e-400` rounds to 0, `1e-310`
//! would be a subnormal with lost digits) is a located error, in `psi`, in
//! `let`s and in parameter defaults. Without it `psi = 1e999*I2` compiled
//! to Ψ ≡ +∞ and `psi = 1e-400*I2` to Ψ ≡ 0.

use ecc_dsl::{Error, compile};

fn render(src: &str) -> String {
    match compile(src, "test.psi") {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(d) => d.render("test.psi", src),
    }
}

#[test]
fn a_literal_beyond_f64_is_a_located_error() {
    insta::assert_snapshot!(render("psi = 1e999*I2\n"));
    insta::assert_snapshot!(render("param mu = 1.0\npsi = mu*I2 - 2.5e400*I1\n"));
    insta::assert_snapshot!(render("param mu = 1e400\npsi = mu*I2\n"));
}

#[test]
fn a_nonzero_literal_below_the_normal_range_is_a_located_error() {
    insta::assert_snapshot!(render("let k = 1e-400\npsi = k*I2\n"));
    insta::assert_snapshot!(render("psi = 1e-310*I2 + I1\n"));
}

#[test]
fn every_bad_literal_is_reported_with_its_span() {
    let src = "psi = 1e999*I2 + 1e-999*I1";
    let errs = compile(src, "t")
        .err()
        .map(|d| d.errors)
        .unwrap_or_default();
    let spans: Vec<_> = errs
        .iter()
        .filter(|e| matches!(e, Error::NumberNotF64 { .. }))
        .map(|e| &src[e.span().range()])
        .collect();
    assert_eq!(
        spans,
        ["1e999"],
        "the first bad literal stops its statement"
    );
    let src = "let a = 1e999\nlet b = 1e-999\npsi = a*I2 + b*I1";
    let errs = compile(src, "t")
        .err()
        .map(|d| d.errors)
        .unwrap_or_default();
    let spans: Vec<_> = errs
        .iter()
        .filter(|e| matches!(e, Error::NumberNotF64 { .. }))
        .map(|e| &src[e.span().range()])
        .collect();
    assert_eq!(spans, ["1e999", "1e-999"]);
}

#[test]
fn literals_at_the_edges_of_the_range_are_accepted() {
    for src in [
        "psi = 1.7976931348623157e308*I2",
        "psi = 2.2250738585072014e-308*I2 + I1",
        "psi = 1e300*I2 + 1e-300*I1",
        "psi = 0e999*I2 + 0.0*I1 + I3",
        "psi = 000.000e-999 + I2",
    ] {
        assert!(compile(src, "t").is_ok(), "{src}");
    }
}

#[test]
fn a_folded_constant_beyond_f64_is_an_error_at_psi() {
    for (src, overflow) in [
        ("psi = 10^400*I2\n", true),
        ("psi = 1e200*1e200*I2 + I1\n", true),
        ("psi = I2/10^400\n", false),
    ] {
        let errs = compile(src, "t")
            .err()
            .map(|d| d.errors)
            .unwrap_or_default();
        assert!(
            errs.iter().any(
                |e| matches!(e, Error::NumberNotF64 { overflow: o, .. } if *o == overflow)
                    && e.span().range().start == 6
            ),
            "{src}: {errs:?}"
        );
    }
    insta::assert_snapshot!(render("param mu = 1\npsi = mu*I2 + 10^400*I1\n"));
    // intermediate constants may be huge when the result fits
    assert!(compile("psi = 10^400*10^-400*I2 + 1e300*1e-300*I1", "t").is_ok());
}
