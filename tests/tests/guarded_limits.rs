//! Guarded divided differences in generated code: the limit form and the
//! direct quotient (extrapolated linearly to the same point) agree across
//! the runtime's switch |σi − σj| ≤ τ·max(|σi|, |σj|)
//! (τ = `ecc_runtime::divided::LIMIT_TOL`), and exactly repeated σ give
//! finite values. Checked on the library's stretch energies (Ogden, Hencky,
//! 2D and 3D) and a macro energy with a non-integer power.

use ecc_runtime::Energy;
use ecc_runtime::divided::LIMIT_TOL;

ecc_macros::energy! {
    struct Pow25;
    psi = s1^2.5 + s2^2.5 + s3^2.5 - log(s1*s2*s3);
}

/// Flip of pair slot `k` (3D) at σ with σ_j = σ_i·(1 − gap).
fn flip3(e: &dyn Energy<3>, k: usize, base: [f64; 3], gap: f64) -> f64 {
    let (i, j) = ecc_runtime::PAIRS_3D[k];
    let mut s = base;
    s[j] = s[i] * (1.0 - gap);
    e.spectral(&s).flip[k]
}

fn flip2(e: &dyn Energy<2>, base: f64, other_gap: f64) -> f64 {
    e.spectral(&[base, base * (1.0 - other_gap)]).flip[0]
}

#[test]
fn limit_and_direct_agree_across_the_switch_3d() {
    let energies: Vec<(&str, Box<dyn Energy<3>>)> = vec![
        ("ogden", Box::new(ecc_energies::Ogden::new())),
        ("hencky", Box::new(ecc_energies::Hencky::new())),
        ("pow25", Box::new(Pow25::new())),
    ];
    for (name, e) in &energies {
        for k in 0..3 {
            let base = [1.7, 1.3, 0.9];
            let exact = flip3(e.as_ref(), k, base, 0.0);
            assert!(
                exact.is_finite(),
                "{name} slot {k}: flip at σi = σj must be finite"
            );
            // Just inside the switch (limit form) against the direct quotient
            // just outside, extrapolated linearly back to the same point.
            let inside = flip3(e.as_ref(), k, base, 0.99 * LIMIT_TOL);
            let (o1, o2) = (
                flip3(e.as_ref(), k, base, 1.01 * LIMIT_TOL),
                flip3(e.as_ref(), k, base, 1.03 * LIMIT_TOL),
            );
            let outside = o1 + (o1 - o2);
            let rel = (inside - outside).abs() / inside.abs().max(1.0);
            assert!(
                rel < 1e-8,
                "{name} slot {k}: jump {rel:e} across the switch ({inside} vs {outside})"
            );
            let near = flip3(e.as_ref(), k, base, 1e-9);
            assert!(
                (near - exact).abs() / exact.abs().max(1.0) < 1e-8,
                "{name} slot {k}: 1e-9 gap"
            );
            // Far from the switch the direct quotient is used and smooth.
            let far = flip3(e.as_ref(), k, base, 1e-3);
            assert!(
                (far - exact).abs() / exact.abs().max(1.0) < 1e-2,
                "{name} slot {k}: 1e-3 gap"
            );
        }
    }
}

#[test]
fn limit_and_direct_agree_across_the_switch_2d() {
    let energies: Vec<(&str, Box<dyn Energy<2>>)> = vec![
        ("ogden2", Box::new(ecc_energies::Ogden2::new())),
        ("hencky2", Box::new(ecc_energies::Hencky2::new())),
    ];
    for (name, e) in &energies {
        let exact = flip2(e.as_ref(), 1.3, 0.0);
        assert!(exact.is_finite(), "{name}");
        let inside = flip2(e.as_ref(), 1.3, 0.99 * LIMIT_TOL);
        let (o1, o2) = (
            flip2(e.as_ref(), 1.3, 1.01 * LIMIT_TOL),
            flip2(e.as_ref(), 1.3, 1.03 * LIMIT_TOL),
        );
        let outside = o1 + (o1 - o2);
        let rel = (inside - outside).abs() / inside.abs().max(1.0);
        assert!(rel < 1e-8, "{name}: jump {rel:e} across the switch");
    }
}
