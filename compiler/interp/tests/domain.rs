//! The interpreter keeps the domain of what was written (issue 12, item 2):
//! `exp(log(I3))` simplifies to I3 but is +∞ (outside) for det F ≤ 0 in
//! `psi`, `spectral` and `psi_i2_i3`; the unsimplified control energies and
//! points inside the domain are unchanged; `info().barrier` is right.

use ecc_interp::{InterpEnergy, load_source};
use ecc_runtime::Energy;

/// The four formulas of the issue (each equals I3, or 0, where defined).
const REDUCED: [(&str, f64); 4] = [
    ("psi = exp(log(I3))", 1.0),
    ("psi = sqrt(I3)^2", 1.0),
    ("psi = I3^(1/2)*I3^(1/2)", 1.0),
    ("psi = log(I3) - log(I3)", 0.0),
];

fn energy<const D: usize>(src: &str) -> InterpEnergy<D> {
    load_source::<D>(src, "t.psi", &[]).unwrap_or_else(|e| panic!("{src}: {e}"))
}

fn det<const D: usize>(s: &[f64; D]) -> f64 {
    s.iter().product()
}

fn check<const D: usize>(inside: [f64; D], inverted: [f64; D]) {
    for (src, k) in REDUCED {
        let e = energy::<D>(src);
        assert_eq!(e.psi(&inverted), f64::INFINITY, "{src} at {inverted:?}");
        assert_eq!(e.spectral(&inverted).psi, f64::INFINITY, "{src}");
        let want = k * det(&inside);
        assert!((e.psi(&inside) - want).abs() < 1e-15, "{src}");
        assert!((e.spectral(&inside).psi - want).abs() < 1e-15, "{src}");
        if e.info().svd_free_psi {
            assert_eq!(e.psi_i2_i3(1.0, det(&inverted)), Some(f64::INFINITY));
            assert_eq!(e.psi_i2_i3(1.0, det(&inside)), Some(want));
        }
    }
    // The control: I3 as written is defined for det F < 0 and unchanged.
    let e = energy::<D>("psi = I3");
    assert_eq!(e.psi(&inverted), det(&inverted));
    assert_eq!(e.spectral(&inverted).psi, det(&inverted));
}

#[test]
fn reduced_formulas_are_outside_for_inverted_elements() {
    check::<2>([1.2, 0.5], [1.0, -0.6]);
    check::<3>([1.2, 0.9, 0.5], [1.0, 1.0, -0.6]);
}

#[test]
fn the_boundary_follows_each_condition() {
    // log needs I3 > 0; sqrt needs I3 ≥ 0: at det F = 0 they differ.
    let zero = [1.0, 0.0];
    assert_eq!(energy::<2>("psi = exp(log(I3))").psi(&zero), f64::INFINITY);
    assert_eq!(energy::<2>("psi = sqrt(I3)^2").psi(&zero), 0.0);
    // A division needs only I3 ≠ 0: inverted elements stay inside.
    let e = energy::<2>("psi = I3/I3 + I2");
    assert_eq!(e.psi(&[1.0, -0.5]), 2.25);
    assert_eq!(e.psi(&zero), f64::INFINITY);
}

#[test]
fn barrier_flag_is_the_limit_at_zero_det() {
    for (src, barrier) in [
        ("psi = I3^(1/3)", false),
        ("dim 2\npsi = sqrt(s1^2) + sqrt(s2^2)", false),
        ("psi = log(I3)", false),
        ("psi = exp(log(I3))", false),
        ("psi = -log(I3)", true),
        ("psi = 1/I3", true),
        ("psi = (I2 + I2/I3^2)/2", true),
    ] {
        let e = energy::<2>(src);
        assert_eq!(e.info().barrier, barrier, "{src}");
    }
}

#[test]
fn many_conditions_are_all_tested() {
    // 40 distinct conditions I2 − k/100 > 0: more guard outputs than the
    // stack buffers hold (the allocating path), each one able to fail.
    let terms: Vec<String> = (1..=40)
        .map(|k| format!("exp(log(I2 - {k}/100))"))
        .collect();
    let src = format!("psi = {}", terms.join(" + "));
    let e = energy::<2>(&src);
    // I2 = 0.45 passes all 40; I2 = 0.395 fails only the last (k = 40).
    let s = [0.45f64.sqrt(), 0.0];
    assert!(e.psi(&s).is_finite() && e.spectral(&s).psi.is_finite());
    let s = [0.395f64.sqrt(), 0.0];
    assert_eq!(e.psi(&s), f64::INFINITY);
    assert_eq!(e.spectral(&s).psi, f64::INFINITY);
    let want: f64 = (1..=40).map(|k| 0.45 - k as f64 / 100.0).sum();
    assert!((e.psi(&[0.45f64.sqrt(), 0.0]) - want).abs() < 1e-12);
}
