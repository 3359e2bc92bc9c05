//! Every built-in and example energy (generated, interpreted, hand-written,
//! `energy!`), in 2D and 3D, at the hard cases — rest, uniform scaling,
//! exactly repeated σ, σ differing by 1e-9 relative, σi + σj ≈ 0 and = 0,
//! σ = 1e-6, inverted, σ = 1e3 — each under random rotations U, V, against
//! the independent double-double reference of `hard_ref` (Ψ from the CAS
//! graph of the `.psi` source, a double-double Jacobi SVD and fourth-order
//! central differences of Ψ(F) in double-double).
//!
//! What is asserted at each point: see `hard_ref::check`. In short:
//!
//! * nothing is NaN: Ψ, ∂Ψ/∂σ, the scaling block, twists and flips;
//! * outside the energy's domain (the reference Ψ is NaN or +∞) Ψ = +∞;
//!   inside it Ψ is finite;
//! * Ψ, vec(∂Ψ/∂F) and the raw Hessian ∂²Ψ/∂f² agree with the reference
//!   within the tolerances of `hard_ref::check`, scaled by the condition number
//!   κ = σmax / ℓ (ℓ: distance to the nearest set where Ψ(F) is not smooth
//!   — det F = 0 for barrier energies, σi + σj = 0 for energies that are
//!   not sign-symmetric; κ = 1 elsewhere). The f64 SVD perturbs σ by
//!   ≈ ε‖F‖, which moves Ψ's derivatives by ≈ ε‖F‖/ℓ relative: κ is the
//!   honest amplification, and still catches any sign or factor-2 error;
//! * every filtered Hessian (Clamp, Abs, ClampEps) is finite, exactly
//!   symmetric, PSD down to its floor, and equal to the numeric projection
//!   of the *reference* Hessian (projection is 1-Lipschitz, so the same
//!   tolerance applies).

mod hard_ref;

use ecc_tests::cases::{compose, hard_cases_2d, hard_cases_3d, rng, rotations2, rotations3};
use hard_ref::check::{Lifted, Run, check_point, lift2, lift3};
use hard_ref::energies::{formulas2, formulas3};

/// The library's hard cases plus a few more extreme ones.
fn cases3() -> Vec<(String, [f64; 3])> {
    let mut v: Vec<(String, [f64; 3])> = hard_cases_3d()
        .into_iter()
        .map(|c| (c.name.to_string(), c.sigma))
        .collect();
    v.push(("all 1e3".into(), [1e3, 1e3, 1e3]));
    v.push(("two at 1e-6".into(), [1.0, 1e-6, 1e-6]));
    v.push(("inverted 1e-6".into(), [1.2, 0.9, -1e-6]));
    v.push(("repeated inverted".into(), [1.1, 0.7, -0.7 * (1.0 - 1e-9)]));
    v.push(("all 1e-9 apart".into(), [1.0, 1.0 - 1e-9, 1.0 - 2e-9]));
    v
}

fn cases2() -> Vec<(String, [f64; 2])> {
    let mut v: Vec<(String, [f64; 2])> = hard_cases_2d()
        .into_iter()
        .map(|c| (c.name.to_string(), c.sigma))
        .collect();
    v.push(("all 1e3".into(), [1e3, 1e3]));
    v.push(("inverted 1e-6".into(), [1.2, -1e-6]));
    v.push(("repeated pair".into(), [0.7, 0.7]));
    v
}

#[test]
fn every_energy_at_the_hard_cases_3d() {
    let formulas = formulas3();
    let mut r = rng(2019);
    let mut run = Run::new();
    for (name, sigma) in cases3() {
        for (k, (u, v)) in rotations3(&mut r, 2).into_iter().enumerate() {
            let f = compose(&u, &sigma, &v);
            let label = format!("{name} σ = {sigma:?} rotation {k}");
            for formula in &formulas {
                let lifts: Vec<Lifted> = formula
                    .impls
                    .iter()
                    .map(|i| lift3(i.energy.as_ref(), &f))
                    .collect();
                check_point(formula, f.as_slice(), &lifts, &label, &mut run);
            }
        }
    }
    run.finish("3D hard cases");
}

#[test]
fn every_energy_at_the_hard_cases_2d() {
    let formulas = formulas2();
    let mut r = rng(2020);
    let mut run = Run::new();
    for (name, sigma) in cases2() {
        for (k, (u, v)) in rotations2(&mut r, 3).into_iter().enumerate() {
            let f = compose(&u, &sigma, &v);
            let label = format!("{name} σ = {sigma:?} rotation {k}");
            for formula in &formulas {
                let lifts: Vec<Lifted> = formula
                    .impls
                    .iter()
                    .map(|i| lift2(i.energy.as_ref(), &f))
                    .collect();
                check_point(formula, f.as_slice(), &lifts, &label, &mut run);
            }
        }
    }
    run.finish("2D hard cases");
}
