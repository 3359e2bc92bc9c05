//! Exactly on the removable singular sets — σi = σj (flip) and, for
//! sign-symmetric energies, σi = −σj (twist) — the interpreter and the
//! generated code return the limits of the divided differences. The
//! reference is computed *off* the singular set: along σi = m + t,
//! σj = m − t the flip (Ψi − Ψj)/(σi − σj) is even in t, so the
//! Richardson extrapolation (4λ(t/2) − λ(t))/3 at t = 10⁻² m (well outside
//! the runtime's switch band) is the limit up to O(t⁴) ≈ 1e-8; the twist
//! likewise along σi = a + s/2, σj = −a + s/2.

use ecc_interp::InterpEnergy;
use ecc_runtime::{Energy, pair_indices};
use ecc_tests::library::{Lib, library2, library3};

/// λ at σ for pair slot k: (flip, twist).
fn pair<const D: usize>(e: &dyn Energy<D>, s: &[f64; D], k: usize) -> (f64, f64) {
    let sp = e.spectral(s);
    (sp.flip[k], sp.twist[k])
}

/// The divided difference itself, computed from the gradient (no limit logic).
fn quotient<const D: usize>(
    e: &dyn Energy<D>,
    s: &[f64; D],
    i: usize,
    j: usize,
    plus: bool,
) -> f64 {
    let g = e.spectral(s).grad;
    if plus {
        (g[i] + g[j]) / (s[i] + s[j])
    } else {
        (g[i] - g[j]) / (s[i] - s[j])
    }
}

fn richardson(f: impl Fn(f64) -> f64, t: f64) -> f64 {
    (4.0 * f(0.5 * t) - f(t)) / 3.0
}

fn check_flip<const D: usize>(
    name: &str,
    e: &dyn Energy<D>,
    s: [f64; D],
    k: usize,
    failures: &mut Vec<String>,
) {
    let (i, j) = pair_indices::<D>(k);
    assert_eq!(s[i], s[j]);
    let m = s[i];
    let at = |t: f64| {
        let mut x = s;
        x[i] = m + t;
        x[j] = m - t;
        quotient(e, &x, i, j, false)
    };
    let want = richardson(at, 1e-2 * m.abs());
    let got = pair(e, &s, k).0;
    let scale = e
        .spectral(&s)
        .scale
        .to_dense()
        .iter()
        .flatten()
        .fold(1.0f64, |a, x| a.max(x.abs()));
    let err = (got - want).abs();
    if !err.is_finite() || err > 1e-7 * scale {
        failures.push(format!(
            "{name} {D}D flip slot {k} at σ={s:?}: {got} vs limit {want}"
        ));
    }
}

fn check_twist<const D: usize>(
    name: &str,
    e: &dyn Energy<D>,
    s: [f64; D],
    k: usize,
    failures: &mut Vec<String>,
) {
    let (i, j) = pair_indices::<D>(k);
    assert_eq!(s[i], -s[j]);
    let a = s[i];
    let at = |t: f64| {
        let mut x = s;
        x[i] = a + 0.5 * t;
        x[j] = -a + 0.5 * t;
        quotient(e, &x, i, j, true)
    };
    let want = richardson(at, 1e-2 * a.abs());
    let got = pair(e, &s, k).1;
    let scale = e
        .spectral(&s)
        .scale
        .to_dense()
        .iter()
        .flatten()
        .fold(1.0f64, |m, x| m.max(x.abs()));
    let err = (got - want).abs();
    if !err.is_finite() || err > 1e-7 * scale {
        failures.push(format!(
            "{name} {D}D twist slot {k} at σ={s:?}: {got} vs limit {want}"
        ));
    }
}

fn interp<const D: usize>(lib: &Lib<D>) -> InterpEnergy<D> {
    ecc_interp::load_source::<D>(lib.source, &format!("{}.psi", lib.name), &[]).unwrap()
}

#[test]
fn limits_on_the_singular_sets_3d() {
    let mut failures = Vec::new();
    let mut twists = 0;
    for lib in library3() {
        let it = interp(&lib);
        let sym = lib.sign_symmetric();
        for (label, e) in [
            ("interp", &it as &dyn Energy<3>),
            ("generated", lib.energy.as_ref()),
        ] {
            let name = format!("{} ({label})", lib.name);
            check_flip(&name, e, [1.3, 1.3, 0.7], 2, &mut failures);
            check_flip(&name, e, [1.6, 0.9, 0.9], 0, &mut failures);
            for k in 0..3 {
                check_flip(&name, e, [1.2, 1.2, 1.2], k, &mut failures);
            }
            let inverted = [1.3, 0.8, -0.8];
            if sym && e.psi(&inverted).is_finite() {
                check_twist(&name, e, inverted, 0, &mut failures);
                twists += 1;
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} wrong limits:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(twists >= 6, "twist limits checked for {twists} energies");
}

#[test]
fn limits_on_the_singular_sets_2d() {
    let mut failures = Vec::new();
    let mut twists = 0;
    for lib in library2() {
        let it = interp(&lib);
        let sym = lib.sign_symmetric();
        for (label, e) in [
            ("interp", &it as &dyn Energy<2>),
            ("generated", lib.energy.as_ref()),
        ] {
            let name = format!("{} ({label})", lib.name);
            check_flip(&name, e, [1.3, 1.3], 0, &mut failures);
            check_flip(&name, e, [0.6, 0.6], 0, &mut failures);
            let inverted = [0.8, -0.8];
            if sym && e.psi(&inverted).is_finite() {
                check_twist(&name, e, inverted, 0, &mut failures);
                twists += 1;
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} wrong limits:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(twists >= 6, "twist limits checked for {twists} energies");
}
