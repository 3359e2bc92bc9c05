//! Compile cost grows near-linearly with the size of the energy (issue 12,
//! item 8). Measured with the deterministic CAS operation count
//! `ecc_dsl::cas::work_count` (machine-independent, so never flaky): 4× the
//! terms must cost well under 16× the work that quadratic behaviour would
//! give. Before the fix the ratios below were ≈ 16 (lowering) and 15.4
//! (stretch polynomial); now ≈ 4 and 5.4. Energies with many distinct
//! transcendental subterms are checked the same way, and for the size of the
//! constants the compile builds (big-number arithmetic is what made them
//! super-linear; the operation count alone did not show it). Wall-clock curves:
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

#[test]
fn distinct_transcendental_subterms_compile_near_linearly() {
    // Every distinct exp/log is a polynomial variable of its own.
    for family in [Family::Exps, Family::Logs, Family::ExpPoly] {
        let ratio = compile_ratio(family, 50);
        assert!(
            ratio < 6.0,
            "{}: 4x the terms, {ratio:.1}x the work",
            family.name()
        );
    }
}

#[test]
fn compiling_builds_no_huge_constants() {
    // Σ_k c_k (I2 − k)² exp(I3/k): coefficients of ≤ 10 bits. Pulling the
    // rational content lcm(1…k)⁻¹ out of the derivatives' sums gave every
    // coefficient ≈ 1.44 n bits (1146-bit constants at n = 400), i.e.
    // quadratic total size and big-number arithmetic everywhere.
    let src = energy(Family::ExpPoly, 200);
    ecc_dsl::cas::reset_largest_number_bits();
    assert!(ecc_dsl::compile(&src, "exppoly").is_ok());
    let bits = ecc_dsl::cas::largest_number_bits();
    assert!(bits <= 64, "a {bits}-bit constant");
}

#[test]
fn a_sum_with_an_unconvertible_term_costs_no_more_than_its_size() {
    // The last term's expansion is too big (900² > poly::MAX_TERMS·64
    // products, refused before any work), so the sum has no rational form;
    // summing the n terms before it one by one to discover that was
    // quadratic in n.
    let mut big = String::from("(0");
    for a in 0..30 {
        for b in 0..30 {
            big.push_str(&format!(" + s1^{a}*s2^{b}"));
        }
    }
    big.push_str(")^2");
    let prove = |n: usize| {
        let mut src = String::from("psi = 0");
        for k in 1..=n {
            src.push_str(&format!(" + exp(I1/{k})/{}", k % 7 + 1));
        }
        src.push_str(&format!(" + {big}\n"));
        work(|| ecc_dsl::testing::prove_zero(&src, 3))
    };
    let ratio = prove(2000) as f64 / prove(500) as f64;
    assert!(ratio < 6.0, "4x the terms, {ratio:.1}x the work");
}
