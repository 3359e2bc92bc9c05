//! Generated energies against the runtime's hand-written ARAP, Symmetric
//! Dirichlet and Stable Neo-Hookean (to ~1e-12 relative, at the hard cases
//! and random σ), and the F-space checker against deliberately wrong
//! derivatives (so that a passing `generated_fd` means something).

use ecc_energies::{Arap, StableNeoHookean, SymmetricDirichlet2, SymmetricDirichlet3};
use ecc_runtime::energies as hand;
use ecc_runtime::{Energy, EnergyInfo, Spectral};
use ecc_tests::cases::*;
use ecc_tests::close;
use ecc_tests::fcheck::{Worst, check_f};

const TOL: f64 = 1e-12;

fn compare<const D: usize>(
    label: &str,
    a: &Spectral<D>,
    b: &Spectral<D>,
    tol: f64,
) -> Result<(), String> {
    let mut bad = Vec::new();
    let mut chk = |what: String, x: f64, y: f64| {
        if !close(x, y, tol) {
            bad.push(format!("{what}: generated {x:e} vs hand-written {y:e}"));
        }
    };
    chk("psi".into(), a.psi, b.psi);
    for i in 0..D {
        chk(format!("grad[{i}]"), a.grad[i], b.grad[i]);
        for j in 0..D {
            chk(format!("A[{i}][{j}]"), a.scale.get(i, j), b.scale.get(i, j));
        }
    }
    for k in 0..Spectral::<D>::PAIRS {
        chk(format!("twist[{k}]"), a.twist[k], b.twist[k]);
        chk(format!("flip[{k}]"), a.flip[k], b.flip[k]);
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!("{label}:\n  {}", bad.join("\n  ")))
    }
}

/// The hard cases and 200 random σ (seed 49 + d).
fn sigmas<const D: usize>() -> Vec<[f64; D]> {
    let mut r = rng(49 + D as u64);
    let mut v: Vec<[f64; D]> = select::<D>(TESTS).iter().map(|c| c.sigma).collect();
    v.extend((0..200).map(|_| random_sigma::<D>(&mut r)));
    v
}

fn run<const D: usize>(generated: &dyn Energy<D>, hw: &dyn Energy<D>, tol: f64) {
    let mut failures = Vec::new();
    for s in sigmas::<D>() {
        let label = format!("{} at σ = {s:?}", generated.name());
        if let Err(e) = compare(&label, &generated.spectral(&s), &hw.spectral(&s), tol) {
            failures.push(e);
        }
        if !close(generated.psi(&s), hw.psi(&s), tol) {
            failures.push(format!(
                "{label}: psi {} vs {}",
                generated.psi(&s),
                hw.psi(&s)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn arap_matches_hand_written() {
    run::<3>(&Arap::new(), &hand::Arap, TOL);
    run::<2>(&Arap::new(), &hand::Arap, TOL);
    assert_eq!(
        Energy::<3>::info(&Arap::new()),
        Energy::<3>::info(&hand::Arap)
    );
}

#[test]
fn symmetric_dirichlet_matches_hand_written() {
    run::<3>(&SymmetricDirichlet3::new(), &hand::SymmetricDirichlet, TOL);
    run::<2>(&SymmetricDirichlet2::new(), &hand::SymmetricDirichlet, TOL);
    assert_eq!(
        Energy::<3>::info(&SymmetricDirichlet3::new()),
        Energy::<3>::info(&hand::SymmetricDirichlet)
    );
    assert_eq!(
        Energy::<2>::info(&SymmetricDirichlet2::new()),
        Energy::<2>::info(&hand::SymmetricDirichlet)
    );
}

#[test]
fn stable_neo_hookean_matches_hand_written() {
    // Default parameters and others set at run time through `set_param`.
    for (mu, lambda) in [(1.0, 10.0), (1.3, 4.1), (0.2, 250.0)] {
        let mut generated = StableNeoHookean::new();
        Energy::<3>::set_param(&mut generated, "mu", mu).unwrap_or_else(|e| panic!("{e}"));
        Energy::<3>::set_param(&mut generated, "lambda", lambda).unwrap_or_else(|e| panic!("{e}"));
        let hw = hand::StableNeoHookean::new(mu, lambda);
        run::<3>(&generated, &hw, TOL);
        run::<2>(&generated, &hw, TOL);
        assert_eq!(Energy::<3>::info(&generated), Energy::<3>::info(&hw));
        assert_eq!(
            Energy::<2>::psi_i2_i3(&generated, 2.3, 0.7).map(|p| close(
                p,
                Energy::<2>::psi_i2_i3(&hw, 2.3, 0.7).unwrap_or(f64::NAN),
                TOL
            )),
            Some(true)
        );
    }
}

/// A generated energy with one derivative deliberately wrong.
struct Broken {
    inner: StableNeoHookean,
    what: &'static str,
}

impl Energy<3> for Broken {
    fn name(&self) -> &str {
        self.what
    }
    fn psi(&self, s: &[f64; 3]) -> f64 {
        Energy::<3>::psi(&self.inner, s)
    }
    fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
        let mut sp = Energy::<3>::spectral(&self.inner, s);
        match self.what {
            "grad" => sp.grad[1] *= 1.001,
            "twist" => sp.twist[0] += 1e-3,
            _ => sp.flip[2] -= 1e-3,
        }
        sp
    }
    fn info(&self) -> EnergyInfo {
        EnergyInfo::default()
    }
}

#[test]
fn the_checker_catches_wrong_derivatives() {
    let f = compose(&rot3(&mut rng(53)), &[1.4, 1.1, 0.8], &rot3(&mut rng(54)));
    let mut w = Worst::default();
    assert!(check_f(&StableNeoHookean::new(), &f, true, "ok", &mut w).is_ok());
    for what in ["grad", "twist", "flip"] {
        let b = Broken {
            inner: StableNeoHookean::new(),
            what,
        };
        let r = check_f(&b, &f, true, what, &mut w);
        assert!(r.is_err(), "a wrong {what} was not caught");
    }
}
