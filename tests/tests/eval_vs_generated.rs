//! The interpreter (`ecc eval`'s route: CAS derivatives → the runtime's
//! generic invariant/stretch formulas) against the generated energies of
//! ecc-energies (CAS-specialised eigenvalue expressions): the same
//! stretch-space eigensystem and the same F-space gradient and Hessians, at
//! the hard cases under random rotations and at random F, for the whole
//! library in 2D and 3D.

use ecc_interp::InterpEnergy;
use ecc_runtime::{Energy, Filter, Spectral, signed_svd};
use ecc_tests::cases::*;
use ecc_tests::library::{Lib, library2, library3};
use nalgebra::SMatrix;

/// Relative agreement of the two routes: they differ only by rounding (and,
/// near a removable singularity, by the direct quotient vs the limit form,
/// ≈ ε^{2/3} relative; see `ecc_runtime::divided`).
const TOL: f64 = 1e-9;

fn interp<const D: usize>(lib: &Lib<D>) -> InterpEnergy<D> {
    ecc_interp::load_source::<D>(lib.source, &format!("{}.psi", lib.name), &[])
        .unwrap_or_else(|e| panic!("{}: {e}", lib.name))
}

/// Every number of a spectral description, pair slots in use only.
fn flat<const D: usize>(s: &Spectral<D>) -> Vec<f64> {
    let mut v = vec![s.psi];
    v.extend(s.grad);
    v.extend(s.scale.to_dense().iter().flatten());
    let pairs = D * (D - 1) / 2;
    v.extend(&s.twist[..pairs]);
    v.extend(&s.flip[..pairs]);
    v
}

/// max |a − b| / max(1, max |b|), with equal non-finite values accepted and
/// any other non-finite mismatch infinite.
fn err(a: &[f64], b: &[f64]) -> f64 {
    let scale = b
        .iter()
        .filter(|x| x.is_finite())
        .fold(1.0f64, |m, x| m.max(x.abs()));
    let mut worst = 0.0f64;
    for (x, y) in a.iter().zip(b) {
        if !x.is_finite() || !y.is_finite() {
            if !(x == y || (x.is_nan() && y.is_nan())) {
                return f64::INFINITY;
            }
            continue;
        }
        worst = worst.max((x - y).abs() / scale);
    }
    worst
}

fn stretch_space<const D: usize>(libs: Vec<Lib<D>>, cases: Vec<Case<D>>, seed: u64) -> usize {
    let mut r = rng(seed);
    let mut failures = Vec::new();
    let mut points = 0;
    for lib in &libs {
        let it = interp(lib);
        let sym = lib.sign_symmetric();
        let mut sigmas: Vec<(String, [f64; D], bool)> = cases
            .iter()
            .map(|c| (c.name.to_string(), c.sigma, c.antipodal))
            .collect();
        sigmas.extend((0..40).map(|k| (format!("random {k}"), random_sigma::<D>(&mut r), false)));
        for (name, s, antipodal) in sigmas {
            let g = lib.energy.spectral(&s);
            let i = it.spectral(&s);
            // Exactly on a genuine pole both routes are non-finite there;
            // they may disagree on ±∞ vs NaN, which the filters treat alike.
            let pole = antipodal && !sym;
            let e = if pole {
                err(&flat(&i)[..1 + D], &flat(&g)[..1 + D])
            } else {
                err(&flat(&i), &flat(&g))
            };
            assert_eq!(
                Energy::psi(&it, &s).is_finite(),
                g.psi.is_finite(),
                "{} {name}: domain",
                lib.name
            );
            if e > TOL {
                failures.push(format!(
                    "{} {D}D {name} σ={s:?}: {e:e}\n  interp    {:?}\n  generated {:?}",
                    lib.name,
                    flat(&i),
                    flat(&g)
                ));
            }
            points += 1;
        }
    }
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures.join("\n")
    );
    points
}

#[test]
fn same_eigensystem_in_stretch_space_3d() {
    let n = stretch_space::<3>(library3(), hard_cases_3d(), 11);
    assert!(n > 500, "{n}");
}

#[test]
fn same_eigensystem_in_stretch_space_2d() {
    let n = stretch_space::<2>(library2(), hard_cases_2d(), 12);
    assert!(n > 500, "{n}");
}

/// The F-space quantities `ecc eval` prints, from both routes.
fn f_space<const D: usize>(e: &dyn Energy<D>, f: &SMatrix<f64, D, D>) -> Vec<f64> {
    let svd = signed_svd(f);
    let s = e.spectral(&svd.sigma);
    let mut v = vec![s.psi];
    if D == 2 {
        let svd2: &ecc_runtime::Svd<2> = same_dim(&svd);
        let s2: &Spectral<2> = same_dim(&s);
        v.extend(ecc_runtime::gradient_f(svd2, s2).iter());
        for fl in [Filter::None, Filter::Clamp] {
            v.extend(ecc_runtime::hessian_f(svd2, s2, fl).iter());
        }
    } else {
        let svd3: &ecc_runtime::Svd<3> = same_dim(&svd);
        let s3: &Spectral<3> = same_dim(&s);
        v.extend(ecc_runtime::gradient_f(svd3, s3).iter());
        for fl in [Filter::None, Filter::Clamp] {
            v.extend(ecc_runtime::hessian_f(svd3, s3, fl).iter());
        }
    }
    v
}

/// View a `T<D>` as `T<K>` when D == K (a checked downcast), to call the
/// dimension-specific runtime functions from generic code.
fn same_dim<A: 'static, B: 'static>(a: &A) -> &B {
    (a as &dyn std::any::Any)
        .downcast_ref::<B>()
        .expect("same dimension")
}

fn f_space_agreement<const D: usize>(
    libs: Vec<Lib<D>>,
    cases: Vec<Case<D>>,
    fs: Vec<SMatrix<f64, D, D>>,
    rots: Vec<(SMatrix<f64, D, D>, SMatrix<f64, D, D>)>,
) {
    let mut failures = Vec::new();
    for lib in &libs {
        let it = interp(lib);
        let sym = lib.sign_symmetric();
        let mut points: Vec<(String, SMatrix<f64, D, D>)> = Vec::new();
        for c in &cases {
            if c.antipodal && !sym {
                continue; // a genuine pole: non-finite raw Hessians on both routes
            }
            for (k, (u, v)) in rots.iter().enumerate() {
                points.push((format!("{} rot {k}", c.name), compose(u, &c.sigma, v)));
            }
        }
        points.extend(
            fs.iter()
                .enumerate()
                .map(|(k, f)| (format!("random F {k}"), *f)),
        );
        for (name, f) in points {
            let a = f_space::<D>(&it, &f);
            let b = f_space::<D>(lib.energy.as_ref(), &f);
            let e = err(&a, &b);
            if e > TOL {
                failures.push(format!("{} {D}D {name}: {e:e}", lib.name));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn same_gradient_and_hessians_in_f_space_3d() {
    let mut r = rng(21);
    let rots = rotations3(&mut r, 2);
    let fs = random_f3(&mut r, 20);
    f_space_agreement::<3>(library3(), hard_cases_3d(), fs, rots);
}

#[test]
fn same_gradient_and_hessians_in_f_space_2d() {
    let mut r = rng(22);
    let rots = rotations2(&mut r, 2);
    let fs = random_f2(&mut r, 20);
    f_space_agreement::<2>(library2(), hard_cases_2d(), fs, rots);
}
