//! The `barrier` flag means Ψ → +∞ as det F → 0⁺ (issue 12, item 2): finite
//! powers of vanishing quantities (`I3^(1/3)`, `sqrt(s1^2)`) and cancelled
//! logarithms (`I3*log(I3)`) are not barriers; logs and negative powers of
//! det F, of a stretch or of a product of stretches are.

use ecc_dsl::compile;

fn barrier(src: &str) -> Vec<bool> {
    compile(src, "b")
        .unwrap_or_else(|d| panic!("{src}: {d}"))
        .dims
        .iter()
        .map(|d| d.barrier)
        .collect()
}

#[test]
fn finite_at_zero_det_is_not_a_barrier() {
    for src in [
        "psi = I3^(1/3)",
        "psi = I2 + I3^(2/3)",
        "psi = sqrt(s1^2) + sqrt(s2^2) + sqrt(s3^2)",
        "psi = I3*log(I3)",
        "psi = I3^2*log(I3) + I2",
        "psi = log(I3)",
    ] {
        assert!(barrier(src).iter().all(|b| !b), "{src}: {:?}", barrier(src));
    }
}

#[test]
fn growing_at_zero_det_is_a_barrier() {
    for src in [
        "psi = -log(I3)",
        "psi = I2/I3",
        "psi = I2 + 1/I3^2",
        "psi = log(I3)^2",
        "psi = I3^(-1/3)*I2",
        "psi = log(s1)^2 + log(s2)^2 + log(s3)^2",
        "psi = s1^2 + s2^2 + s3^2 + 1/(s1*s2*s3)",
    ] {
        assert!(barrier(src).iter().all(|b| *b), "{src}: {:?}", barrier(src));
    }
}
