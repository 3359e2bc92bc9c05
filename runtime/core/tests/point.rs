//! F-space checks for every energy, at the hard cases (under random rotations)
//! and at random F:
//!
//! * gradient and raw Hessian vs central differences of Ψ(F) (`reference::fd_*`),
//! * eigenpairs vs nalgebra's `SymmetricEigen` of the raw Hessian,
//! * filtered Hessians (every `Filter`) symmetric, finite, PSD, and equal to the
//!   numeric projection of the raw Hessian,
//!
//! all by the one checker, `ecc_runtime::reference::check::check_lift`
//! (same tolerances: gradient 1e-7, Hessian 2e-5, eigen/PSD 1e-11).

mod common;

use common::energies::*;
use common::*;
use ecc_runtime::Energy;
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::reference::check::{Worst, check_lift};

/// Gradient vs central differences, relative to max(1, ‖g‖∞). The differences
/// reach ≈1e-10; a sign or factor-2 error gives O(1).
type E3 = (Box<dyn Energy<3>>, bool);
type E2 = (Box<dyn Energy<2>>, bool);

/// (energy, sign-symmetric)
fn energies_3d() -> Vec<E3> {
    vec![
        (Box::new(Arap), false),
        (Box::new(SymmetricDirichlet), true),
        (Box::new(StableNeoHookean::new(1.3, 4.1)), true),
        (Box::new(ArapInv), false),
        (Box::new(Sd3Inv { decoupled: true }), true),
        (Box::new(Sd3Inv { decoupled: false }), true),
        (Box::new(Hencky), true),
        (Box::new(Poly), true),
        (Box::new(ArapStretch), false),
    ]
}

fn energies_2d() -> Vec<E2> {
    vec![
        (Box::new(Arap), false),
        (Box::new(SymmetricDirichlet), true),
        (Box::new(StableNeoHookean::new(1.3, 4.1)), true),
        (Box::new(Mips2), true),
        (Box::new(ArapInv), false),
        (Box::new(Sd2Inv { decoupled: true }), true),
        (Box::new(Sd2Inv { decoupled: false }), true),
        (Box::new(Hencky), true),
        (Box::new(Poly), true),
        (Box::new(ArapStretch), false),
    ]
}

#[test]
fn hard_cases_3d_all_energies() {
    let mut r = rng(21);
    let mut worst = Worst::default();
    for case in hard_cases_3d() {
        for (u, v) in rotations3(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (e, sym) in energies_3d() {
                // Central differences are meaningless across a genuine pole.
                let fd = sym || !case.antipodal;
                let label = format!("{} / {} / σ = {:?}", e.name(), case.name, case.sigma);
                check_lift(e.as_ref(), &f, fd, &label, &mut worst)
                    .unwrap_or_else(|m| panic!("{m}"));
            }
        }
    }
    println!(
        "3D hard cases: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}

#[test]
fn hard_cases_2d_all_energies() {
    let mut r = rng(22);
    let mut worst = Worst::default();
    for case in hard_cases_2d() {
        for (u, v) in rotations2(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (e, sym) in energies_2d() {
                let fd = sym || !case.antipodal;
                let label = format!("{} / {} / σ = {:?}", e.name(), case.name, case.sigma);
                check_lift(e.as_ref(), &f, fd, &label, &mut worst)
                    .unwrap_or_else(|m| panic!("{m}"));
            }
        }
    }
    println!(
        "2D hard cases: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}

#[test]
fn random_f() {
    let mut r = rng(23);
    let mut worst = Worst::default();
    for f in random_f3(&mut r, 12) {
        for (e, _) in energies_3d() {
            let label = format!("{} / random F = {:?}", e.name(), f.as_slice());
            check_lift(e.as_ref(), &f, true, &label, &mut worst).unwrap_or_else(|m| panic!("{m}"));
        }
    }
    for f in random_f2(&mut r, 12) {
        for (e, _) in energies_2d() {
            let label = format!("{} / random F = {:?}", e.name(), f.as_slice());
            check_lift(e.as_ref(), &f, true, &label, &mut worst).unwrap_or_else(|m| panic!("{m}"));
        }
    }
    println!(
        "random F: worst grad {:e}, hess {:e}, eig {:e}",
        worst.grad, worst.hess, worst.eig
    );
}
