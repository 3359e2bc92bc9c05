//! The exact element projection (`element_eval_projected`, congruence of size
//! d², see `ecc_runtime::element::Congruence`) against a numeric eigensolve of
//! the full 6×6 / 12×12 element Hessian (`reference::project_psd_numeric`), on
//! every hard case × rotations × isotropic and skewed rest shapes; its
//! reduction to the F-space projection when M ∝ I; P(K) = K when H ⪰ 0.

mod common;

use common::energies::{Mips2, Poly};
use common::*;
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{
    Dim, ElemMat, Energy, Filter, Nodes, Rest, Space, element_eval, element_eval_projected,
    element_f, signed_svd,
};
use nalgebra::{DMatrix, SMatrix};

/// Projected element Hessian vs the numeric one, relative to max(1, ‖K_raw‖∞).
const TOL: f64 = 1e-9;

fn dense<const D: usize>(m: &ElemMat<D>) -> DMatrix<f64>
where
    Space<D>: Dim<D>,
{
    let n = <Space<D> as Dim<D>>::NE;
    DMatrix::from_fn(n, n, |i, j| m[(i, j)])
}

/// `project_psd_numeric` of the full element matrix (6×6 or 12×12).
fn numeric<const D: usize>(k: &DMatrix<f64>, filter: Filter) -> DMatrix<f64> {
    match D {
        2 => dynm(&project_psd_numeric::<6>(
            &SMatrix::from_fn(|i, j| k[(i, j)]),
            filter,
        )),
        _ => dynm(&project_psd_numeric::<12>(
            &SMatrix::from_fn(|i, j| k[(i, j)]),
            filter,
        )),
    }
}

/// Rest shapes: the regular simplex (M ∝ I) first, then skewed ones.
fn shapes2() -> Vec<[[f64; 2]; 3]> {
    let h = 3f64.sqrt() / 2.0;
    vec![
        [[0.0, 0.0], [1.0, 0.0], [0.5, h]],
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.4, 0.08]],  // flat, obtuse
        [[0.0, 0.0], [0.05, 0.0], [0.02, 2.0]], // needle
        [[0.3, -0.2], [1.7, 0.4], [-0.5, 0.9]],
    ]
}

fn shapes3() -> Vec<[[f64; 3]; 4]> {
    let s = 1.0 / 2f64.sqrt();
    vec![
        [
            [-1.0, 0.0, -s],
            [1.0, 0.0, -s],
            [0.0, 1.0, s],
            [0.0, -1.0, s],
        ],
        [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [[0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.9, 1.1, 0.05]], // sliver
        [
            [0.0; 3],
            [0.1, 0.0, 0.0],
            [0.0, 0.1, 0.0],
            [0.03, 0.02, 3.0],
        ], // needle
        [
            [0.2, 0.1, 0.0],
            [1.3, -0.4, 0.2],
            [0.1, 1.1, -0.3],
            [0.5, 0.4, 1.6],
        ],
    ]
}

/// x_n = F p_n (translations do not matter: every quantity is invariant).
fn deform<const D: usize>(p: &Nodes<D>, f: &SMatrix<f64, D, D>) -> Nodes<D>
where
    Space<D>: Dim<D>,
{
    let y: Vec<[f64; D]> = p
        .as_ref()
        .iter()
        .map(|q| {
            let v = f * SMatrix::<f64, D, 1>::from_fn(|i, _| q[i]);
            std::array::from_fn(|i| v[i])
        })
        .collect();
    let idx: Vec<usize> = (0..y.len()).collect();
    <Space<D> as Dim<D>>::gather(&y, &idx)
}

/// The projector onto ker B (the d translations): (1/K) (1 1ᵀ ⊗ I_d).
fn translations<const D: usize>() -> DMatrix<f64> {
    let n = D * (D + 1);
    DMatrix::from_fn(n, n, |i, j| {
        if i % D == j % D {
            1.0 / (D + 1) as f64
        } else {
            0.0
        }
    })
}

/// What `element_eval_projected` must return for `filter`: the numeric
/// projection of the raw K, with the ClampEps floor ε·μ_max·|q| on range(Bᵀ)
/// and 0 on the translations.
fn expected<const D: usize>(raw: &DMatrix<f64>, rest: &Rest<D>, filter: Filter) -> DMatrix<f64>
where
    Space<D>: Dim<D>,
{
    match filter {
        Filter::ClampEps(eps) => {
            let floor = eps * rest.congruence().mu_max * rest.measure;
            numeric::<D>(raw, Filter::ClampEps(floor)) - translations::<D>() * floor
        }
        f => numeric::<D>(raw, f),
    }
}

/// Returns how many (case, shape, rotation) points were compared.
fn check_energy<const D: usize>(e: &dyn Energy<D>, shapes: &[Nodes<D>]) -> usize
where
    Space<D>: Dim<D>,
{
    let mut rng = rng(11);
    let rots: Vec<_> = (0..3)
        .map(|_| (rotation::<D>(&mut rng), rotation::<D>(&mut rng)))
        .collect();
    let filters = [
        Filter::Clamp,
        Filter::Abs,
        Filter::ClampEps(1e-3),
        Filter::None,
    ];
    let mut compared = 0;
    for case in select::<D>(TESTS) {
        for (u, v) in &rots {
            let f = compose(u, &case.sigma, v);
            for p in shapes {
                let rest = Rest::<D>::new(*p).unwrap();
                let cg = rest.congruence();
                let x = deform(p, &f);
                let raw = element_eval(e, &rest, &x, Filter::None, true);
                let k = dense::<D>(&raw.hess);
                for filter in filters {
                    let got = element_eval_projected(e, &rest, &cg, &x, filter, true);
                    let what = format!("{} {} {:?} shape {:?}", e.name(), case.name, filter, p);
                    assert_eq!(got.psi.to_bits(), raw.psi.to_bits(), "{what}: psi");
                    assert_eq!(got.grad, raw.grad, "{what}: gradient");
                    let h = dense::<D>(&got.hess);
                    assert!(
                        h.iter().all(|v| v.is_finite()) || filter.is_raw(),
                        "{what}: {h}"
                    );
                    if !k.iter().all(|v| v.is_finite()) {
                        // A pole of the energy (ARAP's twist at σi + σj = 0):
                        // the mode is dropped, the rest stays PSD.
                        let min = h.clone().symmetric_eigenvalues().min();
                        assert!(filter.is_raw() || min > -1e-9 * h.amax(), "{what}: {min}");
                        continue;
                    }
                    let want = expected::<D>(&k, &rest, filter);
                    // A backward-stable eigensolve: accurate relative to the raw K.
                    let err = (&h - &want).amax() / k.amax().max(1.0);
                    assert!(err < TOL, "{what}: error {err:e}\n{h}\n{want}");
                    compared += 1;
                }
            }
        }
    }
    compared
}

fn energies2() -> Vec<Box<dyn Energy<2>>> {
    vec![
        Box::new(Arap),
        Box::new(SymmetricDirichlet),
        Box::new(StableNeoHookean::new(1.3, 4.1)),
        Box::new(Poly),
        Box::new(Mips2),
    ]
}

fn energies3() -> Vec<Box<dyn Energy<3>>> {
    vec![
        Box::new(Arap),
        Box::new(SymmetricDirichlet),
        Box::new(StableNeoHookean::new(1.3, 4.1)),
        Box::new(Poly),
    ]
}

#[test]
fn matches_numeric_projection_of_the_element_hessian_2d() {
    for e in energies2() {
        let n = check_energy::<2>(&*e, &shapes2());
        assert!(n > 500, "{}: only {n} comparisons", e.name());
    }
}

#[test]
fn matches_numeric_projection_of_the_element_hessian_3d() {
    for e in energies3() {
        let n = check_energy::<3>(&*e, &shapes3());
        assert!(n > 500, "{}: only {n} comparisons", e.name());
    }
}

/// On the regular simplex M = m I, so the exact projection is the F-space one.
fn isotropic_equals_f_space<const D: usize>(e: &dyn Energy<D>, regular: Nodes<D>) -> usize
where
    Space<D>: Dim<D>,
{
    let rest = Rest::<D>::new(regular).unwrap();
    let cg = rest.congruence();
    assert!(cg.cond() < 1.0 + 1e-12, "cond(M) = {}", cg.cond());
    let mut rng = rng(5);
    let mut indefinite = 0;
    for case in select::<D>(TESTS) {
        let f = compose(
            &rotation::<D>(&mut rng),
            &case.sigma,
            &rotation::<D>(&mut rng),
        );
        let x = deform(&regular, &f);
        for filter in [Filter::Clamp, Filter::Abs, Filter::ClampEps(1e-2)] {
            let a = dense::<D>(&element_eval(e, &rest, &x, filter, true).hess);
            let b = dense::<D>(&element_eval_projected(e, &rest, &cg, &x, filter, true).hess);
            let raw = dense::<D>(&element_eval(e, &rest, &x, Filter::None, true).hess);
            let err = (&a - &b).amax() / raw.amax().max(1.0);
            assert!(
                err < 1e-11,
                "{} {} {filter:?}: {err:e}",
                e.name(),
                case.name
            );
        }
        let raw = element_eval(e, &rest, &x, Filter::None, true).hess;
        let clamped = element_eval(e, &rest, &x, Filter::Clamp, true).hess;
        indefinite += usize::from(raw != clamped);
    }
    indefinite
}

#[test]
fn equals_f_space_projection_when_metric_is_isotropic() {
    let (r2, r3) = (shapes2()[0], shapes3()[0]);
    let mut indefinite = 0;
    for e in energies2() {
        indefinite += isotropic_equals_f_space::<2>(&*e, r2);
    }
    for e in energies3() {
        indefinite += isotropic_equals_f_space::<3>(&*e, r3);
    }
    assert!(
        indefinite > 20,
        "only {indefinite} indefinite cases exercised"
    );
}

/// H ⪰ 0 at every analytic eigenvalue ⇒ P(K) = K, bit for bit (no eigensolve).
fn psd_unchanged<const D: usize>(e: &dyn Energy<D>, shapes: &[Nodes<D>]) -> usize
where
    Space<D>: Dim<D>,
{
    let mut rng = rng(9);
    let mut hits = 0;
    for case in select::<D>(TESTS) {
        let f = compose(
            &rotation::<D>(&mut rng),
            &case.sigma,
            &rotation::<D>(&mut rng),
        );
        for p in shapes {
            let rest = Rest::<D>::new(*p).unwrap();
            let x = deform(p, &f);
            let svd = signed_svd(&element_f(&rest, &x));
            let (vals, _) = ecc_runtime::eigen_f(&svd, &e.spectral(&svd.sigma));
            if !vals.as_ref().iter().all(|l| l.is_finite() && *l >= 0.0) {
                continue;
            }
            let raw = element_eval(e, &rest, &x, Filter::None, true);
            for filter in [Filter::Clamp, Filter::Abs] {
                let got = element_eval_projected(e, &rest, &rest.congruence(), &x, filter, true);
                assert_eq!(got.hess, raw.hess, "{} {} {filter:?}", e.name(), case.name);
            }
            hits += 1;
        }
    }
    hits
}

#[test]
fn positive_semidefinite_hessian_is_returned_unprojected() {
    let mut hits = 0;
    for e in energies2() {
        hits += psd_unchanged::<2>(&*e, &shapes2());
    }
    for e in energies3() {
        hits += psd_unchanged::<3>(&*e, &shapes3());
    }
    assert!(hits > 50, "only {hits} PSD points");
}

#[test]
fn metric_is_b_times_b_transpose() {
    // G = B Bᵀ = M ⊗ I: M_jl = Σ_n β_nj β_nl with β_0 = −Σ β_n.
    for p in shapes3() {
        let rest = Rest::<3>::new(p).unwrap();
        let m = ecc_runtime::element::metric(&rest.dm_inv);
        let b: Vec<[f64; 3]> = (0..4)
            .map(|n| {
                std::array::from_fn(|j| match n {
                    0 => -(0..3).map(|k| rest.dm_inv[(k, j)]).sum::<f64>(),
                    _ => rest.dm_inv[(n - 1, j)],
                })
            })
            .collect();
        for j in 0..3 {
            for l in 0..3 {
                let want: f64 = b.iter().map(|r| r[j] * r[l]).sum();
                assert!((m[(j, l)] - want).abs() < 1e-12 * want.abs().max(1.0));
            }
        }
        let cg = rest.congruence();
        let back = cg.sqrt_m * cg.sqrt_m;
        assert!((back - m).amax() < 1e-12 * m.amax(), "M^½ M^½ = M");
        assert!(cg.mu_min > 0.0 && cg.mu_max >= cg.mu_min);
    }
}
