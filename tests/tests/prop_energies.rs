//! Property tests (proptest) over random deformation gradients: for every
//! built-in and example energy (generated, interpreted, hand-written,
//! `energy!`), at F = U diag(σ) Vᵀ with random rotations and random signed
//! singular values — magnitudes log-uniform in [0.03, 20], sometimes
//! inverted, sometimes exactly or nearly repeated (gap 1e-9 or 1e-12) —
//! and at F with uniformly random entries, Ψ, the gradient and the raw
//! Hessian agree with the double-double reference and every filtered
//! Hessian is finite, symmetric and PSD (the full list of assertions and
//! the tolerances are in `hard_ref::check`).
//!
//! Case counts are sized for CI (each case checks every energy against a
//! reference computed with ~360 double-double SVDs); set `PROPTEST_CASES`
//! to run more. Failures are shrunk and saved in
//! `tests/proptest-regressions/prop_energies.txt`, which is committed and
//! replayed first on every run.

mod hard_ref;

use std::sync::LazyLock;

use ecc_tests::cases::compose;
use hard_ref::check::{Lifted, Run, check_point, lift2, lift3};
use hard_ref::energies::{Formula, formulas2, formulas3};
use nalgebra::{Matrix2, Matrix3, Quaternion, UnitQuaternion};
use proptest::prelude::*;

static FORMULAS3: LazyLock<Vec<Formula<3>>> = LazyLock::new(formulas3);
static FORMULAS2: LazyLock<Vec<Formula<2>>> = LazyLock::new(formulas2);

/// A rotation in SO(3) from a (non-degenerate) quaternion.
fn rot3() -> impl Strategy<Value = Matrix3<f64>> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-degenerate quaternion", |q| {
            q.iter().map(|x| x * x).sum::<f64>() > 1e-2
        })
        .prop_map(|q| {
            UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
                .to_rotation_matrix()
                .into_inner()
        })
}

fn rot2() -> impl Strategy<Value = Matrix2<f64>> {
    (-std::f64::consts::PI..std::f64::consts::PI)
        .prop_map(|a: f64| Matrix2::new(a.cos(), -a.sin(), a.sin(), a.cos()))
}

/// Signed singular values in the runtime's order, with optional repeats.
fn sigma<const D: usize>() -> impl Strategy<Value = [f64; D]> {
    (
        prop::array::uniform::<_, D>(-1.5f64..1.3),
        any::<bool>(),
        0usize..4,
        0usize..D.max(2) - 1,
    )
        .prop_map(|(exps, inverted, tie, at)| {
            let mut s: [f64; D] = exps.map(|e| 10f64.powf(e));
            s.sort_by(|a, b| b.total_cmp(a));
            // tie 0: none; 1: exactly repeated; 2, 3: 1e-9 / 1e-12 apart
            if tie > 0 {
                let gap = [0.0, 0.0, 1e-9, 1e-12][tie];
                s[at + 1] = s[at] * (1.0 - gap);
            }
            if inverted {
                s[D - 1] = -s[D - 1];
            }
            s
        })
}

fn check3(f: &Matrix3<f64>) -> Result<(), TestCaseError> {
    let mut run = Run::new();
    let label = format!("F = {:?}", f.as_slice());
    for formula in FORMULAS3.iter() {
        let lifts: Vec<Lifted> = formula
            .impls
            .iter()
            .map(|i| lift3(i.energy.as_ref(), f))
            .collect();
        check_point(formula, f.as_slice(), &lifts, &label, &mut run);
    }
    prop_assert!(run.failures.is_empty(), "{}", run.failures.join("\n"));
    Ok(())
}

fn check2(f: &Matrix2<f64>) -> Result<(), TestCaseError> {
    let mut run = Run::new();
    let label = format!("F = {:?}", f.as_slice());
    for formula in FORMULAS2.iter() {
        let lifts: Vec<Lifted> = formula
            .impls
            .iter()
            .map(|i| lift2(i.energy.as_ref(), f))
            .collect();
        check_point(formula, f.as_slice(), &lifts, &label, &mut run);
    }
    prop_assert!(run.failures.is_empty(), "{}", run.failures.join("\n"));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn rotated_singular_values_3d(u in rot3(), v in rot3(), s in sigma::<3>()) {
        check3(&compose(&u, &s, &v))?;
    }

    #[test]
    fn random_entries_3d(e in prop::array::uniform9(-2.0f64..2.0)) {
        check3(&Matrix3::from_column_slice(&e))?;
    }

    #[test]
    fn rotated_singular_values_2d(u in rot2(), v in rot2(), s in sigma::<2>()) {
        check2(&compose(&u, &s, &v))?;
    }

    #[test]
    fn random_entries_2d(e in prop::array::uniform4(-2.0f64..2.0)) {
        check2(&Matrix2::from_column_slice(&e))?;
    }
}
