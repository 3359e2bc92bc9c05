//! The reduced I4 eigensolve (`runtime/core/src/fibre/reduced.rs`, eqs.
//! R1–R4): equal to nalgebra's projection of the raw F5 Hessian on the hard
//! cases of the fibre setting, taken whenever no σ_i + σ_j vanishes, and the
//! spectra that make its block sizes the smallest ones (numeric witnesses).

mod common;

use common::fibre_energies::{I4Only, Mixed};
use common::{compose, rng, rotation};

use ecc_runtime::fibre::{
    FibreDerivs, FibreDim, FibreEnergy, FibrePath, FibreUse, fibre_f, invariant4, unit_fibre,
};
use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Dim, Filter, Space};
use nalgebra::{SMatrix, SVector, SymmetricEigen};

/// ψ = I4 (the bare I4 Hessian).
struct Bare;
impl<const D: usize> FibreEnergy<D> for Bare {
    fn name(&self) -> &str {
        "i4"
    }
    fn fibre(&self, i4: f64, _i5: f64) -> FibreDerivs {
        FibreDerivs {
            psi: i4,
            d4: 1.0,
            ..FibreDerivs::default()
        }
    }
    fn uses(&self) -> FibreUse {
        FibreUse::I4
    }
}

/// (F, a, F has a pole σ_i + σ_j = 0) on the hard cases, with and without
/// random rotations U, V.
fn cases<const D: usize>(seed: u64) -> Vec<(SMatrix<f64, D, D>, SVector<f64, D>, bool)> {
    let mut r = rng(seed);
    let e = |k: usize| SVector::<f64, D>::from_fn(|i, _| if i == k { 1.0 } else { 0.0 });
    let diag = |s: &[f64]| -> [f64; D] { std::array::from_fn(|i| s[i.min(s.len() - 1)]) };
    let mut sig: Vec<([f64; D], usize)> = vec![
        (diag(&[1.0]), 0),                 // rest
        (diag(&[1.7]), 1),                 // uniform scale
        (diag(&[1.4, 1.4, 0.6]), 0),       // repeated pair
        (diag(&[1.9, 0.8, 0.5]), 1),       // generic
        (diag(&[1e-9, 1.0, 1.1]), 0),      // F a ≈ 0, I4 ≈ +0
        (diag(&[1.1, 1.0, -1e-9]), D - 1), // I4 ≈ −0 (sign change)
        (diag(&[1.2, 0.9, -0.4]), D - 1),  // inverted along the fibre
        (diag(&[1.2, 0.9, -0.4]), 0),      // inverted across it
        (diag(&[1e-6, 1e-6, 1e-6]), 0),    // tiny σ
        (diag(&[80.0, 2.0, 0.3]), 0),      // huge stretch
        (diag(&[1.0, 0.5, -0.5]), D - 1),  // pole σ_i + σ_j = 0 (3D; 2D: 1 − 0.5)
    ];
    if D == 2 {
        sig.push((diag(&[0.5, -0.5]), 0)); // pole
        sig.push((diag(&[1.1, -1e-9]), 1)); // I4 ≈ −0 along the inverted axis
    }
    let mut out = Vec::new();
    for (s, k) in sig {
        let pole = (0..D).any(|i| (i + 1..D).any(|j| s[i] + s[j] == 0.0));
        for rotated in [false, true] {
            let (u, v) = if rotated {
                (rotation::<D>(&mut r), rotation::<D>(&mut r))
            } else {
                (SMatrix::identity(), SMatrix::identity())
            };
            let f = compose(&u, &s, &v);
            let along = v * e(k);
            let oblique =
                unit_fibre(&std::array::from_fn::<f64, D, _>(|i| 1.0 + i as f64)).unwrap();
            out.push((f, along, pole));
            out.push((f, v * oblique, pole));
        }
    }
    out
}

fn check<const D: usize, const N: usize>(seed: u64)
where
    Space<D>: Dim<D, FVec = SVector<f64, N>, FMat = SMatrix<f64, N, N>> + FibreDim<D>,
    nalgebra::Const<N>: nalgebra::DimSub<nalgebra::U1>,
    nalgebra::DefaultAllocator:
        nalgebra::allocator::Allocator<nalgebra::DimDiff<nalgebra::Const<N>, nalgebra::U1>>,
{
    let (mut reduced, mut exact_poles) = (0, 0);
    for (f, a, pole) in cases::<D>(seed) {
        for e in [&Bare as &dyn FibreEnergy<D>, &I4Only, &Mixed] {
            let raw = fibre_f(e, &f, &a, Filter::None, true);
            assert_eq!(raw.path, FibrePath::Numeric, "the raw request uses F5");
            for filter in [Filter::Clamp, Filter::ClampEps(1e-3), Filter::Abs] {
                let p = fibre_f(e, &f, &a, filter, true);
                let ctx = format!("{} {filter:?} D={D} F={f:?} a={a:?}", e.name());
                assert!(p.hess.iter().all(|x| x.is_finite()), "{ctx}");
                // exactly on the pole the reduced form is not finite and F5
                // is used; rotated, rounding leaves σ_i + σ_j ≈ 1e-16 and
                // both paths carry the huge but finite twist entries
                if pole && p.path == FibrePath::Numeric {
                    exact_poles += 1;
                    continue;
                }
                assert_eq!(p.path, FibrePath::Reduced, "{ctx}");
                reduced += 1;
                let want = project_psd_numeric(&raw.hess, filter);
                let tol = 1e-11 * raw.hess.abs().max().max(1.0);
                let err = (p.hess - want).abs().max();
                assert!(err <= tol, "{ctx}: {err:e} > {tol:e}\n{}\n{want}", p.hess);
            }
        }
    }
    assert!(reduced > 100, "{reduced}");
    assert!(exact_poles > 0, "no exact pole case");
}

#[test]
fn reduced_projection_equals_the_numeric_one_on_hard_cases_3d() {
    check::<3, 9>(81);
}

#[test]
fn reduced_projection_equals_the_numeric_one_on_hard_cases_2d() {
    check::<2, 4>(82);
}

/// Sorted eigenvalues of the raw F-space Hessian and its largest |λ|.
fn spectrum<const D: usize, const N: usize>(
    e: &dyn FibreEnergy<D>,
    f: &SMatrix<f64, D, D>,
    a: &SVector<f64, D>,
) -> (Vec<f64>, f64)
where
    Space<D>: Dim<D, FVec = SVector<f64, N>, FMat = SMatrix<f64, N, N>> + FibreDim<D>,
{
    let h = fibre_f(e, f, a, Filter::None, true).hess;
    let d = common::dynm(&h);
    let mut l: Vec<f64> = SymmetricEigen::new(d).eigenvalues.iter().copied().collect();
    l.sort_by(f64::total_cmp);
    let m = l.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    (l, m)
}

fn count(l: &[f64], m: f64) -> (usize, usize, usize) {
    let z = 1e-12 * m;
    (
        l.iter().filter(|x| **x > z).count(),
        l.iter().filter(|x| **x < -z).count(),
        l.iter().filter(|x| x.abs() <= z).count(),
    )
}

/// Eq. R3's inertia and eq. R4's null modes at generic points: the bare I4
/// Hessian has d(d−1)/2 positive, d(d−1)/2 negative and d zero eigenvalues;
/// ψ(I4) with ψ44 ≠ 0 has exactly d − 1 zero eigenvalues (the closed-form
/// null modes, so the d² − d + 1 block is the smallest), and ψ(I4, I5) none
/// (no null mode to split off the d² × d² solve).
#[test]
fn spectra_behind_the_block_sizes() {
    let mut r = rng(83);
    for _ in 0..20 {
        let s = [1.3 + r_unit(&mut r), 0.9, 0.4 + 0.2 * r_unit(&mut r)];
        let (u, v) = (rotation::<3>(&mut r), rotation::<3>(&mut r));
        let f = compose(&u, &s, &v);
        let a = rotation::<3>(&mut r).column(0).into_owned();
        assert!(invariant4(&f, &a).abs() > 1e-3);
        let (l, m) = spectrum::<3, 9>(&Bare, &f, &a);
        assert_eq!(count(&l, m), (3, 3, 3), "bare I4 {l:?}");
        let (l, m) = spectrum::<3, 9>(&I4Only, &f, &a);
        assert_eq!(count(&l, m).2, 2, "ψ(I4) {l:?}");
        let (l, m) = spectrum::<3, 9>(&Mixed, &f, &a);
        assert_eq!(count(&l, m).2, 0, "ψ(I4, I5) {l:?}");
    }
    let f2 = SMatrix::<f64, 2, 2>::new(1.3, 0.2, -0.1, 0.7);
    let a2 = unit_fibre(&[0.6, 0.8]).unwrap();
    let (l, m) = spectrum::<2, 4>(&Bare, &f2, &a2);
    assert_eq!(count(&l, m), (1, 1, 2), "bare I4 2D {l:?}");
    let (l, m) = spectrum::<2, 4>(&I4Only, &f2, &a2);
    assert_eq!(count(&l, m).2, 1, "ψ(I4) 2D {l:?}");
    let (l, m) = spectrum::<2, 4>(&Mixed, &f2, &a2);
    assert_eq!(count(&l, m).2, 0, "ψ(I4, I5) 2D {l:?}");
}

fn r_unit(r: &mut rand_chacha::ChaCha8Rng) -> f64 {
    use rand::Rng;
    r.gen_range(0.0..1.0)
}
