//! Generated Rust keeps the domain of what was written (issue 12, item 2):
//! each `energy!` below simplifies to I3 (or 0), but is +∞ for det F ≤ 0 in
//! `psi`, `spectral` and `psi_i2_i3`, and equal to the written formula
//! inside; the control `I3` is unchanged at det F < 0; `info().barrier`
//! is the limit of Ψ as det F → 0⁺.

use ecc_runtime::Energy;

ecc_macros::energy! { struct ExpLog; psi = exp(log(I3)); }
ecc_macros::energy! { struct SqrtSq; psi = sqrt(I3)^2; }
ecc_macros::energy! { struct HalfHalf; psi = I3^(1/2)*I3^(1/2); }
ecc_macros::energy! { struct LogMinusLog; psi = log(I3) - log(I3); }
ecc_macros::energy! { struct Control; psi = I3; }
ecc_macros::energy! { struct Cbrt; psi = I3^(1/3); }
ecc_macros::energy! { struct AbsLike; dim 2; psi = sqrt(s1^2) + sqrt(s2^2); }
ecc_macros::energy! { struct NegLog; psi = -log(I3); }
ecc_macros::energy! { struct Inv; psi = 1/I3; }
ecc_macros::energy! { struct Sd2; dim 2; psi = (I2 + I2/I3^2)/2; }

fn check<E: Energy<2> + Energy<3>>(e: &E, scale: f64) {
    let (in2, out2) = ([1.2, 0.5], [1.0, -0.6]);
    let (in3, out3) = ([1.2, 0.9, 0.5], [1.0, 1.0, -0.6]);
    assert_eq!(Energy::<2>::psi(e, &out2), f64::INFINITY);
    assert_eq!(Energy::<3>::psi(e, &out3), f64::INFINITY);
    assert_eq!(Energy::<2>::spectral(e, &out2).psi, f64::INFINITY);
    assert_eq!(Energy::<3>::spectral(e, &out3).psi, f64::INFINITY);
    assert_eq!(Energy::<2>::psi(e, &in2), scale * 0.6);
    assert!((Energy::<3>::spectral(e, &in3).psi - scale * 0.54).abs() < 1e-15);
    if let Some(v) = Energy::<2>::psi_i2_i3(e, 1.0, -0.6) {
        assert_eq!(v, f64::INFINITY);
        assert_eq!(Energy::<2>::psi_i2_i3(e, 1.0, 0.6), Some(scale * 0.6));
    }
}

#[test]
fn reduced_formulas_are_outside_at_negative_det() {
    check(&ExpLog, 1.0);
    check(&SqrtSq, 1.0);
    check(&HalfHalf, 1.0);
    check(&LogMinusLog, 0.0);
    // The boundary: log needs I3 > 0, sqrt only I3 ≥ 0.
    assert_eq!(Energy::<2>::psi(&ExpLog, &[1.0, 0.0]), f64::INFINITY);
    assert_eq!(Energy::<2>::psi(&SqrtSq, &[1.0, 0.0]), 0.0);
}

#[test]
fn the_written_control_is_unchanged() {
    assert_eq!(Energy::<2>::psi(&Control, &[1.0, -0.6]), -0.6);
    assert_eq!(Energy::<3>::spectral(&Control, &[1.0, 1.0, -0.6]).psi, -0.6);
}

#[test]
fn barrier_is_the_limit_at_zero_det() {
    assert!(!Energy::<3>::info(&Cbrt).barrier);
    assert!(!Energy::<2>::info(&AbsLike).barrier);
    assert!(!Energy::<3>::info(&ExpLog).barrier);
    assert!(Energy::<3>::info(&NegLog).barrier);
    assert!(Energy::<3>::info(&Inv).barrier);
    assert!(Energy::<2>::info(&Sd2).barrier);
    assert!(Energy::<3>::info(&ecc_energies::NeoHookean::default()).barrier);
    assert!(!Energy::<3>::info(&ecc_energies::StableNeoHookean::default()).barrier);
}
