//! The assembled elastic term: patch test, gradient and Hessian against
//! central differences, in 2D and 3D.

mod common;

use std::sync::Arc;

use common::{grid, noise, tet_grid};
use ecc_fem::{Elastic, Filter, NewtonParams, NewtonSolver, Term, Tet, Tri};
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, element_f};

fn solver2(rest: &[[f64; 2]], tris: &[[usize; 3]], e: Arc<dyn Energy<2>>) -> NewtonSolver<2> {
    let t: Vec<Box<dyn Term<2>>> =
        vec![Box::new(Elastic::<_, Tri>::planar(e, rest, tris).unwrap())];
    NewtonSolver::new(rest.len(), t, &[], NewtonParams::default()).unwrap()
}

fn solver3(rest: &[[f64; 3]], tets: &[[usize; 4]], e: Arc<dyn Energy<3>>) -> NewtonSolver<3> {
    let t: Vec<Box<dyn Term<3>>> = vec![Box::new(Elastic::<_, Tet>::new(e, rest, tets).unwrap())];
    NewtonSolver::new(rest.len(), t, &[], NewtonParams::default()).unwrap()
}

fn boundary2(m: usize) -> Vec<bool> {
    let w = m + 1;
    (0..w * w)
        .map(|v| v % w == 0 || v % w == m || v / w == 0 || v / w == m)
        .collect()
}

#[test]
fn patch_test_2d() {
    let m = 6;
    let (rest, tris) = grid(m);
    let a = [[1.3, 0.4], [-0.2, 0.9]];
    let x: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| {
            [
                a[0][0] * p[0] + a[0][1] * p[1] + 0.7,
                a[1][0] * p[0] + a[1][1] * p[1] - 0.2,
            ]
        })
        .collect();
    let on_boundary = boundary2(m);
    let snh: Arc<dyn Energy<2>> = Arc::new(StableNeoHookean {
        mu: 1.0,
        lambda: 10.0,
    });
    for e in [
        Arc::new(SymmetricDirichlet) as Arc<dyn Energy<2>>,
        snh,
        Arc::new(Arap),
    ] {
        let rests: Vec<_> = Elastic::<_, Tri>::planar(e.clone(), &rest, &tris)
            .unwrap()
            .rest()
            .to_vec();
        // every element sees the same F = A
        for (t, r) in tris.iter().zip(&rests) {
            let f = element_f(r, &[x[t[0]], x[t[1]], x[t[2]]]);
            for i in 0..2 {
                for j in 0..2 {
                    assert!((f[(i, j)] - a[i][j]).abs() < 1e-12);
                }
            }
        }
        let mut s = solver2(&rest, &tris, e.clone());
        let ev = s.evaluate(&x, None).unwrap().unwrap();
        let psi_a = e.psi(
            &ecc_runtime::signed_svd(&nalgebra::Matrix2::new(a[0][0], a[0][1], a[1][0], a[1][1]))
                .sigma,
        );
        assert!(
            (ev.energy - psi_a).abs() < 1e-12 * psi_a.abs().max(1.0),
            "E = |Ω| Ψ(A)"
        );
        let scale = ev.gradient.iter().fold(0.0f64, |m, g| m.max(g.abs()));
        for (v, &b) in on_boundary.iter().enumerate() {
            if !b {
                for c in 0..2 {
                    assert!(
                        ev.gradient[2 * v + c].abs() <= 1e-12 * scale.max(1.0),
                        "{}: interior force at {v}",
                        e.name()
                    );
                }
            }
        }
    }
    // ARAP: a rigid motion has zero energy and zero gradient everywhere
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    let y: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| [c * p[0] - s * p[1] + 2.0, s * p[0] + c * p[1] - 1.0])
        .collect();
    let mut arap = solver2(&rest, &tris, Arc::new(Arap));
    let ev = arap.evaluate(&y, None).unwrap().unwrap();
    assert!(ev.energy.abs() < 1e-24);
    assert!(ev.gradient.iter().all(|g| g.abs() < 1e-12));
}

#[test]
fn patch_test_3d() {
    let (rest, tets) = tet_grid(3);
    let a = [[1.1, 0.2, -0.1], [0.05, 0.9, 0.3], [0.0, -0.2, 1.2]];
    let x: Vec<[f64; 3]> = rest
        .iter()
        .map(|p| std::array::from_fn(|i| (0..3).map(|j| a[i][j] * p[j]).sum::<f64>() + 0.1))
        .collect();
    let interior = |p: &[f64; 3]| p.iter().all(|&c| c > 1e-9 && c < 1.0 - 1e-9);
    let e: Arc<dyn Energy<3>> = Arc::new(StableNeoHookean {
        mu: 1.0,
        lambda: 5.0,
    });
    let el = Elastic::<_, Tet>::new(e.clone(), &rest, &tets).unwrap();
    for (t, r) in tets.iter().zip(el.rest()) {
        let f = element_f(r, &[x[t[0]], x[t[1]], x[t[2]], x[t[3]]]);
        for i in 0..3 {
            for j in 0..3 {
                assert!((f[(i, j)] - a[i][j]).abs() < 1e-12);
            }
        }
    }
    let mut s = solver3(&rest, &tets, e);
    let ev = s.evaluate(&x, None).unwrap().unwrap();
    let scale = ev.gradient.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    assert!(scale > 1e-3, "non-trivial stress");
    for (v, p) in rest.iter().enumerate() {
        if interior(p) {
            for c in 0..3 {
                assert!(ev.gradient[3 * v + c].abs() <= 1e-12 * scale);
            }
        }
    }
    // ARAP rigid motion
    let (c, sn) = (0.4f64.cos(), 0.4f64.sin());
    let y: Vec<[f64; 3]> = rest
        .iter()
        .map(|p| [c * p[0] - sn * p[1], sn * p[0] + c * p[1], p[2] + 3.0])
        .collect();
    let mut arap = solver3(&rest, &tets, Arc::new(Arap));
    let ev = arap.evaluate(&y, None).unwrap().unwrap();
    assert!(ev.energy.abs() < 1e-24 && ev.gradient.iter().all(|g| g.abs() < 1e-12));
}

/// Central-difference check of gradient and raw Hessian at x.
fn fd_check<const D: usize>(s: &mut NewtonSolver<D>, x: &[[f64; D]], what: &str) {
    let h = 1e-6;
    let n = x.len() * D;
    let ev = s.evaluate(x, Some(Filter::None)).unwrap().unwrap();
    let gmax = ev.gradient.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    let hess = ev.hessian.unwrap();
    let pat = s.pattern().clone();
    let hmax = hess.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    let mut y = x.to_vec();
    for k in 0..n {
        let (v, c) = (k / D, k % D);
        y[v][c] = x[v][c] + h;
        let ep = s.energy(&y).unwrap();
        let gp = s.evaluate(&y, None).unwrap().unwrap().gradient;
        y[v][c] = x[v][c] - h;
        let em = s.energy(&y).unwrap();
        let gm = s.evaluate(&y, None).unwrap().unwrap().gradient;
        y[v][c] = x[v][c];
        let fd = (ep - em) / (2.0 * h);
        assert!(
            (fd - ev.gradient[k]).abs() <= 1e-6 * gmax.max(1.0),
            "{what}: dE/dx[{k}] {fd} vs {}",
            ev.gradient[k]
        );
        // column k of the Hessian (all DOFs are free here: every DOF has an unknown)
        let uk = s.dofs().unknown(k).unwrap();
        for i in 0..n {
            let fdh = (gp[i] - gm[i]) / (2.0 * h);
            let ui = s.dofs().unknown(i).unwrap();
            let a = pat.slot(ui, uk).map_or(0.0, |p| hess[p]);
            assert!(
                (fdh - a).abs() <= 1e-5 * hmax.max(1.0),
                "{what}: H[{i},{k}] {fdh} vs {a}"
            );
        }
    }
}

#[test]
fn gradient_and_hessian_match_central_differences_2d() {
    let (rest, tris) = grid(3);
    let r = noise(1, 2 * rest.len());
    let x: Vec<[f64; 2]> = rest
        .iter()
        .enumerate()
        .map(|(v, p)| {
            [
                1.2 * p[0] + 0.04 * r[2 * v],
                0.9 * p[1] + 0.3 * p[0] + 0.04 * r[2 * v + 1],
            ]
        })
        .collect();
    let snh: Arc<dyn Energy<2>> = Arc::new(StableNeoHookean {
        mu: 1.0,
        lambda: 4.0,
    });
    for e in [
        Arc::new(SymmetricDirichlet) as Arc<dyn Energy<2>>,
        snh,
        Arc::new(Arap),
    ] {
        let name = e.name().to_string();
        let mut s = solver2(&rest, &tris, e);
        fd_check(&mut s, &x, &name);
    }
}

#[test]
fn gradient_and_hessian_match_central_differences_3d() {
    let (rest, tets) = tet_grid(1);
    let r = noise(2, 3 * rest.len());
    let x: Vec<[f64; 3]> = rest
        .iter()
        .enumerate()
        .map(|(v, p)| std::array::from_fn(|c| p[c] * (1.0 + 0.1 * c as f64) + 0.05 * r[3 * v + c]))
        .collect();
    let snh: Arc<dyn Energy<3>> = Arc::new(StableNeoHookean {
        mu: 1.0,
        lambda: 4.0,
    });
    for e in [
        Arc::new(SymmetricDirichlet) as Arc<dyn Energy<3>>,
        snh,
        Arc::new(Arap),
    ] {
        let name = e.name().to_string();
        let mut s = solver3(&rest, &tets, e);
        fd_check(&mut s, &x, &name);
    }
}

#[test]
fn pcg_and_cholesky_give_the_same_elastic_newton_step() {
    let (rest, tets) = tet_grid(2);
    let fixed: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] < 1e-9).collect();
    let r = noise(3, 3 * rest.len());
    let x0: Vec<[f64; 3]> = rest
        .iter()
        .enumerate()
        .map(|(v, p)| {
            if p[0] < 1e-9 {
                *p
            } else {
                std::array::from_fn(|c| p[c] * (1.0 + 0.2 * p[0]) + 0.02 * r[3 * v + c])
            }
        })
        .collect();
    let mut steps = Vec::new();
    for kind in [ecc_fem::LinearSolver::Cholesky, ecc_fem::LinearSolver::Pcg] {
        let e = Arc::new(StableNeoHookean {
            mu: 1.0,
            lambda: 4.0,
        });
        let t: Vec<Box<dyn Term<3>>> =
            vec![Box::new(Elastic::<_, Tet>::new(e, &rest, &tets).unwrap())];
        let params = NewtonParams {
            linear_solver: kind,
            max_iters: 1,
            pcg_rel_max: 1e-12,
            pcg_rel_min: 1e-12,
            ..Default::default()
        };
        let mut s = NewtonSolver::new(rest.len(), t, &fixed, params).unwrap();
        let mut x = x0.clone();
        let res = s.solve(&mut x).unwrap();
        assert_eq!(res.iterations, 1);
        assert_eq!(res.linear_solver, kind);
        steps.push((x, res.records[0].step));
    }
    assert_eq!(steps[0].1, steps[1].1, "same line-search step");
    let diff = steps[0]
        .0
        .iter()
        .zip(&steps[1].0)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0, f64::max);
    assert!(diff < 1e-8, "Cholesky and PCG steps differ by {diff}");
}
