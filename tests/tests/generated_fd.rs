//! Generated energies (the whole library, from ecc-energies, and energies
//! from the `energy!` macro) against central differences of Ψ(F) and
//! nalgebra's `SymmetricEigen` of the raw Hessian, at the hard cases under
//! random rotations and at random F; filtered Hessians finite, symmetric,
//! PSD and equal to the numeric projection (see `ecc_tests::fcheck`).

use ecc_runtime::Energy;
use ecc_tests::cases::*;
use ecc_tests::fcheck::{Worst, check_f};
use ecc_tests::library::{library2, library3};

ecc_macros::energy! {
    /// Stable Neo-Hookean written in the test, through the item form.
    pub struct MacroSnh;
    param mu = 1.3;
    param lambda = 4.1;
    let alpha = 1 + mu/lambda - mu/((d + 1)*lambda);
    psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1);
}

ecc_macros::energy! {
    /// A stretch energy with a removable flip singularity (guarded).
    struct MacroStretch;
    param k = 0.7;
    psi = k*(s1^2.5 + s2^2.5 + s3^2.5) - log(s1*s2*s3);
}

/// (name, energy, sign-symmetric, positive σ only) in 3D.
fn energies3() -> Vec<(String, Box<dyn Energy<3>>, bool)> {
    let mut v: Vec<(String, Box<dyn Energy<3>>, bool)> = library3()
        .into_iter()
        .map(|l| {
            let sym = l.sign_symmetric();
            (l.name.to_string(), l.energy, sym)
        })
        .collect();
    v.push(("macro snh".into(), Box::new(MacroSnh::new()), true));
    v.push(("macro stretch".into(), Box::new(MacroStretch::new()), false));
    v.push((
        "macro arap".into(),
        Box::new(ecc_macros::energy!(I2 - 2 * I1 + d)),
        false,
    ));
    v
}

fn energies2() -> Vec<(String, Box<dyn Energy<2>>, bool)> {
    let mut v: Vec<(String, Box<dyn Energy<2>>, bool)> = library2()
        .into_iter()
        .map(|l| {
            let sym = l.sign_symmetric();
            (l.name.to_string(), l.energy, sym)
        })
        .collect();
    v.push(("macro snh".into(), Box::new(MacroSnh::new()), true));
    v.push((
        "macro mips".into(),
        Box::new(ecc_macros::energy!(dim 2; psi = I2/I3)),
        true,
    ));
    v
}

fn finish(failures: Vec<String>, what: &str, worst: Worst) {
    println!(
        "{what}: {} points, worst grad {:e}, hess {:e}, eig {:e}",
        worst.points, worst.grad, worst.hess, worst.eig
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn generated_at_hard_cases_3d() {
    let mut r = rng(41);
    let mut worst = Worst::default();
    let mut failures = Vec::new();
    let energies = energies3();
    for case in hard_cases_3d() {
        for (u, v) in rotations3(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (name, e, sym) in &energies {
                let fd = *sym || !case.antipodal;
                let label = format!("{name} / {} / σ = {:?}", case.name, case.sigma);
                if let Err(msg) = check_f(e.as_ref(), &f, fd, &label, &mut worst) {
                    failures.push(msg);
                }
            }
        }
    }
    finish(failures, "3D hard cases", worst);
}

#[test]
fn generated_at_hard_cases_2d() {
    let mut r = rng(42);
    let mut worst = Worst::default();
    let mut failures = Vec::new();
    let energies = energies2();
    for case in hard_cases_2d() {
        for (u, v) in rotations2(&mut r, 2) {
            let f = compose(&u, &case.sigma, &v);
            for (name, e, sym) in &energies {
                let fd = *sym || !case.antipodal;
                let label = format!("{name} / {} / σ = {:?}", case.name, case.sigma);
                if let Err(msg) = check_f(e.as_ref(), &f, fd, &label, &mut worst) {
                    failures.push(msg);
                }
            }
        }
    }
    finish(failures, "2D hard cases", worst);
}

#[test]
fn generated_at_random_f() {
    let mut r = rng(43);
    let mut worst = Worst::default();
    let mut failures = Vec::new();
    let (e3, e2) = (energies3(), energies2());
    for f in random_f3(&mut r, 10) {
        for (name, e, _) in &e3 {
            let label = format!("{name} / random F = {:?}", f.as_slice());
            if let Err(msg) = check_f(e.as_ref(), &f, true, &label, &mut worst) {
                failures.push(msg);
            }
        }
    }
    for f in random_f2(&mut r, 10) {
        for (name, e, _) in &e2 {
            let label = format!("{name} / random F = {:?}", f.as_slice());
            if let Err(msg) = check_f(e.as_ref(), &f, true, &label, &mut worst) {
                failures.push(msg);
            }
        }
    }
    finish(failures, "random F", worst);
}

/// Every energy is checked somewhere in its domain (the loops above skip
/// points where Ψ = +∞, so make sure that is not everywhere).
#[test]
fn every_energy_has_a_finite_domain_point() {
    for (name, e, _) in energies3() {
        assert!(e.psi(&[1.2, 1.0, 0.9]).is_finite(), "{name}");
    }
    for (name, e, _) in energies2() {
        assert!(e.psi(&[1.2, 0.9]).is_finite(), "{name}");
    }
}
