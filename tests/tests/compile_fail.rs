//! Compile-fail tests of the `energy!` macro (trybuild): each bad formula
//! is reported at the offending token (`ui/*.rs`, expected output in
//! `ui/*.stderr`).

#[test]
fn bad_formulas_are_reported_at_the_right_token() {
    let t = trybuild::TestCases::new();
    t.compile_fail("ui/*.rs");
}
