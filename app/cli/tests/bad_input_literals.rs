//! The `docs/ERRORS.md` row for number literals outside the f64 range: the
//! `ecc` binary refuses them at the literal (file:line:column) in every
//! command, exit 1, nothing written. Before, `psi = 1e999*I2` compiled to
//! Ψ ≡ +∞ with exit 0.

mod bad_input_support;

use bad_input_support::{Scratch, only_inputs, says};

#[test]
fn psi_literal_outside_the_f64_range() {
    let s = Scratch::new();
    let out = s.join("out.rs");
    for (name, text, parts) in [
        (
            "big.psi",
            "param mu = 1\npsi = mu*I2 + 1e999*I1\n",
            &[
                "number `1e999` does not fit an f64",
                "too large",
                "big.psi:2:15",
            ][..],
        ),
        (
            "tiny.psi",
            "psi = I2 - 2*I1 + 3e-400*I3\n",
            &[
                "number `3e-400` does not fit an f64",
                "too small",
                "tiny.psi:1:19",
            ][..],
        ),
        (
            "param.psi",
            "param mu = 1e400\npsi = mu*I2\n",
            &["number `1e400` does not fit an f64", "param.psi:1:12"][..],
        ),
    ] {
        let f = s.write(name, text);
        for args in [
            vec!["eval", f.as_str(), "--F", "1 0 0; 0 1 0; 0 0 1"],
            vec!["eval", f.as_str(), "--F", "1 0; 0 1", "--json"],
            vec!["check", f.as_str(), "--samples", "1"],
            vec![f.as_str(), "--emit", "rs", "-o", out.as_str()],
        ] {
            says(&s.fails(&args), parts);
        }
    }
    only_inputs(&s, &["big.psi", "tiny.psi", "param.psi"]);
}
