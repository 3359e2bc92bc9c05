//! The interpreter (what `ecc eval` evaluates) against central differences
//! of Ψ(F) and nalgebra's eigensolver, with PSD filtered Hessians, at the
//! hard cases under random rotations and at random F — every library energy
//! in 2D and 3D, through the same F-space checks the generated code passes
//! (`ecc_tests::fcheck`).

use ecc_interp::InterpEnergy;
use ecc_tests::cases::*;
use ecc_tests::fcheck::{Worst, check_f};
use ecc_tests::library::{library2, library3};

fn interp<const D: usize>(name: &str, source: &str) -> InterpEnergy<D> {
    ecc_interp::load_source::<D>(source, &format!("{name}.psi"), &[])
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn finish(what: &str, failures: Vec<String>, worst: Worst, inside: usize) {
    println!(
        "{what}: {} points ({inside} inside the domain), worst grad {:e}, hess {:e}, eig {:e}",
        worst.points, worst.grad, worst.hess, worst.eig
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
    assert!(inside > 100, "too few points inside the domain: {inside}");
}

#[test]
fn interpreted_energies_at_hard_and_random_f_3d() {
    let mut r = rng(31);
    let rots = rotations3(&mut r, 2);
    let fs = random_f3(&mut r, 6);
    let (mut worst, mut failures, mut inside) = (Worst::default(), Vec::new(), 0);
    for lib in library3() {
        let e = interp::<3>(lib.name, lib.source);
        let sym = lib.sign_symmetric();
        for c in hard_cases_3d() {
            for (k, (u, v)) in rots.iter().enumerate() {
                let f = compose(u, &c.sigma, v);
                let label = format!("{} 3D {} rot {k}", lib.name, c.name);
                // Across a genuine pole differences are meaningless (see cases.rs).
                match check_f(&e, &f, !c.antipodal || sym, &label, &mut worst) {
                    Ok(true) => inside += 1,
                    Ok(false) => {}
                    Err(msg) => failures.push(msg),
                }
            }
        }
        for (k, f) in fs.iter().enumerate() {
            match check_f(
                &e,
                f,
                true,
                &format!("{} 3D random {k}", lib.name),
                &mut worst,
            ) {
                Ok(true) => inside += 1,
                Ok(false) => {}
                Err(msg) => failures.push(msg),
            }
        }
    }
    finish("interp 3D", failures, worst, inside);
}

#[test]
fn interpreted_energies_at_hard_and_random_f_2d() {
    let mut r = rng(32);
    let rots = rotations2(&mut r, 3);
    let fs = random_f2(&mut r, 8);
    let (mut worst, mut failures, mut inside) = (Worst::default(), Vec::new(), 0);
    for lib in library2() {
        let e = interp::<2>(lib.name, lib.source);
        let sym = lib.sign_symmetric();
        for c in hard_cases_2d() {
            for (k, (u, v)) in rots.iter().enumerate() {
                let f = compose(u, &c.sigma, v);
                let label = format!("{} 2D {} rot {k}", lib.name, c.name);
                match check_f(&e, &f, !c.antipodal || sym, &label, &mut worst) {
                    Ok(true) => inside += 1,
                    Ok(false) => {}
                    Err(msg) => failures.push(msg),
                }
            }
        }
        for (k, f) in fs.iter().enumerate() {
            match check_f(
                &e,
                f,
                true,
                &format!("{} 2D random {k}", lib.name),
                &mut worst,
            ) {
                Ok(true) => inside += 1,
                Ok(false) => {}
                Err(msg) => failures.push(msg),
            }
        }
    }
    finish("interp 2D", failures, worst, inside);
}
