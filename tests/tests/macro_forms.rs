//! The `energy!` macro in a test crate: both forms, parameters, `set_param`,
//! visibility and docs; macro energies equal the library's for the same
//! formula.

use ecc_runtime::{Energy, ParamError, ScaleBlock};

mod inner {
    ecc_macros::energy! {
        /// Stable Neo-Hookean, as in `energies/psi/snh.psi`.
        pub struct MacroSnh;
        param mu = 1.0;
        param lambda = 10.0;
        let alpha = 1 + mu/lambda - mu/((d + 1)*lambda);
        psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1);
    }

    ecc_macros::energy! {
        pub(crate) struct Mips;
        dim 2;
        psi = I2/I3;
    }
}

use inner::{MacroSnh, Mips};

#[test]
fn expression_form_yields_a_value() {
    let arap = ecc_macros::energy!(I2 - 2 * I1 + d);
    let s = [1.3, 0.9, 0.7];
    let a = Energy::<3>::spectral(&arap, &s);
    let b = Energy::<3>::spectral(&ecc_energies::Arap::new(), &s);
    assert_eq!(a, b);
    assert_eq!(a.scale, ScaleBlock::Diagonal([2.0; 3]));
    assert_eq!(Energy::<3>::name(&arap), "energy");
    assert!(
        Energy::<2>::psi(&arap, &[1.0, 1.0]).abs() < 1e-15,
        "ARAP vanishes at rest"
    );
}

#[test]
fn expression_form_with_statements_and_a_parameter() {
    let mut e = ecc_macros::energy!(param k = 2; psi = k*(I2 - 2*I1 + d));
    assert_eq!(Energy::<3>::params(&e), vec![("k".to_string(), 2.0)]);
    let s = [1.5, 1.0, 1.0];
    assert!((Energy::<3>::psi(&e, &s) - 2.0 * 0.25).abs() < 1e-14);
    Energy::<3>::set_param(&mut e, "k", 3.0).unwrap_or_else(|err| panic!("{err}"));
    assert!((Energy::<3>::psi(&e, &s) - 3.0 * 0.25).abs() < 1e-14);
    assert_eq!(e.k, 3.0, "parameters are public fields");
}

#[test]
fn item_form_defines_a_documented_struct_with_defaults() {
    let e = MacroSnh::new();
    assert_eq!((e.mu, e.lambda), (1.0, 10.0));
    assert_eq!(MacroSnh::default(), e);
    assert!(MacroSnh::SOURCE.contains("psi = mu/2"));
    assert_eq!(Energy::<3>::name(&e), "macro_snh");
    assert!(Energy::<3>::info(&e).svd_free_psi);
    assert!(!Energy::<3>::info(&e).barrier);
    // Same formula, same code: identical to the library's generated SNH.
    let lib = ecc_energies::StableNeoHookean::new();
    for s in [[1.2, 0.9, 0.8], [1.0, 1.0, 1.0], [2.0, 0.5, -0.3]] {
        assert_eq!(
            Energy::<3>::spectral(&e, &s),
            Energy::<3>::spectral(&lib, &s)
        );
    }
    for s in [[1.2, 0.9], [0.7, -0.4]] {
        assert_eq!(
            Energy::<2>::spectral(&e, &s),
            Energy::<2>::spectral(&lib, &s)
        );
    }
}

#[test]
fn set_param_validates_names_and_values() {
    let mut e = MacroSnh::new();
    Energy::<3>::set_param(&mut e, "lambda", 50.0).unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(e.lambda, 50.0);
    assert_eq!(
        Energy::<3>::params(&e),
        vec![("mu".to_string(), 1.0), ("lambda".to_string(), 50.0)]
    );
    match Energy::<3>::set_param(&mut e, "nu", 0.3) {
        Err(ParamError::Unknown { name, known }) => {
            assert_eq!(name, "nu");
            assert_eq!(known, vec!["mu".to_string(), "lambda".to_string()]);
        }
        other => panic!("expected Unknown, got {other:?}"),
    }
    assert!(matches!(
        Energy::<2>::set_param(&mut e, "mu", f64::NAN),
        Err(ParamError::NotFinite { .. })
    ));
    assert_eq!(e.mu, 1.0, "a rejected value leaves the parameter unchanged");
    // A parameter-free energy rejects every name.
    let mut m = Mips::new();
    assert!(matches!(
        Energy::<2>::set_param(&mut m, "mu", 1.0),
        Err(ParamError::Unknown { .. })
    ));
}

#[test]
fn dim_restricts_the_impls_and_coupled_blocks_stay_full() {
    fn is_2d<T: Energy<2>>(_: &T) {}
    let m = Mips::new();
    is_2d(&m);
    let sp = Energy::<2>::spectral(&m, &[1.3, 0.8]);
    assert!(matches!(sp.scale, ScaleBlock::Full(_)));
    assert!(Energy::<2>::info(&m).barrier);
    // Outside the domain Ψ is +∞, never NaN.
    assert_eq!(Energy::<2>::psi(&m, &[1.0, 0.0]), f64::INFINITY);
    assert_eq!(Energy::<2>::spectral(&m, &[1.0, 0.0]).psi, f64::INFINITY);
}
