//! Compile cost grows near-linearly with the size of the energy (issue 12,
//! item 8). Measured with the deterministic CAS operation count
//! `ecc_dsl::cas::work_count` (machine-independent, so never flaky): 4× the
//! terms must cost well under 16× the work that quadratic behaviour would
//! give. Before the fix the ratios below were ≈ 16 (lowering) and 15.4
//! (stretch polynomial); now ≈ 4 and 5.4. Wall-clock curves:
//! docs/benchmarks/compile_time.md (`--example compile_scaling`).

#[path = "../examples/common/scaling_gen.rs"]
mod scaling_gen;

use scaling_gen::{Family, energy};

/// The CAS work of `f()`.
fn work<T>(f: impl FnOnce() -> T) -> u64 {
    let w0 = ecc_dsl::cas::work_count();
    std::hint::black_box(f());
    ecc_dsl::cas::work_count() - w0
}

/// work(4n) / work(n) for the compile of `family`.
fn compile_ratio(family: Family, n: usize) -> f64 {
    let small = energy(family, n);
    let big = energy(family, 4 * n);
    let compile = |src: &str| {
        let m = ecc_dsl::compile(src, "scaling");
        assert!(m.is_ok(), "{}", family.name());
        m
    };
    let w1 = work(|| compile(&small));
    let w4 = work(|| compile(&big));
    w4 as f64 / w1 as f64
}

#[test]
fn lowering_a_long_sum_is_linear() {
    // Adding term by term re-collected the growing sum every time.
    for family in [Family::Inv, Family::Trans] {
        let lower = |n: usize| {
            let src = energy(family, n);
            work(|| ecc_dsl::testing::lower(&src, 3).is_ok())
        };
        let ratio = lower(4000) as f64 / lower(1000) as f64;
        assert!(
            ratio < 6.0,
            "{}: 4x the terms, {ratio:.1}x the work",
            family.name()
        );
    }
}

#[test]
fn compiling_a_long_stretch_polynomial_is_near_linear() {
    // Summing the converted terms copied the growing polynomial every time.
    let ratio = compile_ratio(Family::Sig, 100);
    assert!(ratio < 8.0, "4x the terms, {ratio:.1}x the work");
}
