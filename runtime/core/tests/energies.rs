//! Hand-written energies: parameters, info flags, fast paths, domain edges.

use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, ParamError};

#[test]
fn parameters_are_plain_fields_and_validated() {
    let mut e = StableNeoHookean::new(1.0, 10.0);
    assert_eq!(
        Energy::<3>::params(&e),
        vec![("mu".to_string(), 1.0), ("lambda".to_string(), 10.0)]
    );
    Energy::<3>::set_param(&mut e, "lambda", 3.0).unwrap();
    assert_eq!(e.lambda, 3.0);
    e.mu = 2.0;
    assert_eq!(Energy::<2>::params(&e)[0].1, 2.0);
    match Energy::<3>::set_param(&mut e, "nu", 0.3) {
        Err(ParamError::Unknown { name, known }) => {
            assert_eq!(name, "nu");
            assert_eq!(known, vec!["mu".to_string(), "lambda".to_string()]);
        }
        other => panic!("expected Unknown, got {other:?}"),
    }
    assert!(matches!(
        Energy::<3>::set_param(&mut e, "mu", f64::NAN),
        Err(ParamError::NotFinite { .. })
    ));
    assert_eq!(e.mu, 2.0, "a rejected value leaves the field unchanged");
    // ARAP and SD have no parameters.
    assert!(Energy::<3>::params(&Arap).is_empty());
    let err = Energy::<2>::set_param(&mut SymmetricDirichlet, "mu", 1.0).unwrap_err();
    assert!(err.to_string().contains("no parameters"), "{err}");
}

#[test]
fn info_flags_and_svd_free_psi() {
    assert!(Energy::<2>::info(&SymmetricDirichlet).barrier);
    assert!(Energy::<3>::info(&SymmetricDirichlet).barrier);
    assert!(Energy::<2>::info(&SymmetricDirichlet).svd_free_psi);
    assert!(!Energy::<3>::info(&SymmetricDirichlet).svd_free_psi);
    assert!(!Energy::<3>::info(&Arap).barrier && !Energy::<3>::info(&Arap).svd_free_psi);
    assert!(Energy::<3>::psi_i2_i3(&Arap, 3.0, 1.0).is_none());
    let snh = StableNeoHookean::new(1.3, 4.1);
    for s in [[1.3, 0.8, 0.5], [1.0, 1.0, -0.4], [2.0, 0.1, 0.1]] {
        let i2 = s.iter().map(|x| x * x).sum::<f64>();
        let j = s[0] * s[1] * s[2];
        let a = Energy::<3>::psi_i2_i3(&snh, i2, j).unwrap();
        assert!((a - Energy::<3>::psi(&snh, &s)).abs() < 1e-13);
        let s2 = [s[0], s[2]];
        let (i2, j) = (s2[0] * s2[0] + s2[1] * s2[1], s2[0] * s2[1]);
        let a = Energy::<2>::psi_i2_i3(&SymmetricDirichlet, i2, j).unwrap();
        assert!((a - Energy::<2>::psi(&SymmetricDirichlet, &s2)).abs() < 1e-12 * a);
    }
}

#[test]
fn domain_edges() {
    // SD: +∞ exactly at det F = 0, the formula value elsewhere (also inverted).
    assert_eq!(
        Energy::<3>::psi(&SymmetricDirichlet, &[1.0, 1.0, 0.0]),
        f64::INFINITY
    );
    assert_eq!(
        Energy::<2>::psi_i2_i3(&SymmetricDirichlet, 1.0, 0.0),
        Some(f64::INFINITY)
    );
    assert_eq!(
        Energy::<3>::spectral(&SymmetricDirichlet, &[1.0, 1.0, 0.0]).psi,
        f64::INFINITY
    );
    assert_eq!(
        Energy::<3>::psi(&SymmetricDirichlet, &[1.0, 1.0, -1.0]),
        3.0
    );
    assert_eq!(Energy::<3>::psi(&SymmetricDirichlet, &[1.0, 1.0, 1.0]), 3.0);
    // Overflow is +∞, never NaN.
    assert_eq!(
        Energy::<3>::psi(&SymmetricDirichlet, &[1.0, 1.0, 1e-200]),
        f64::INFINITY
    );
    // SNH with λ = 0 stays finite (the divergent constant κ²/2λ is dropped).
    let snh = StableNeoHookean::new(1.0, 0.0);
    let sp = Energy::<3>::spectral(&snh, &[1.2, 0.9, 0.8]);
    assert!(sp.psi.is_finite() && sp.grad.iter().all(|g| g.is_finite()));
    assert!(sp.twist.iter().chain(sp.flip.iter()).all(|x| x.is_finite()));
    // ARAP's twist pole is +∞ exactly on σ_i + σ_j = 0 (never NaN; the pole
    // convention of every back end).
    let sp = Energy::<3>::spectral(&Arap, &[1.0, 0.5, -0.5]);
    assert_eq!(sp.twist[0], f64::INFINITY);
    assert!(sp.twist[1].is_finite() && sp.twist[2].is_finite());
}
