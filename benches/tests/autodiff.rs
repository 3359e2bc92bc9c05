//! The autodiff baseline computes the same derivatives as ecc: its raw element
//! Hessian (forward-mode dual numbers) equals ecc's raw element Hessian
//! (`Filter::None`) to 1e-10 relative, its gradient and energy likewise, on
//! random and hard elements; its projected Hessian is PSD; outside a barrier's
//! domain it is +∞ like the generated energy; and as a Newton term it drives
//! a small parameterisation to the same minimum as the analytic term.

use std::sync::Arc;

use ecc_benches::autodiff::term::AutodiffTerm;
use ecc_benches::autodiff::{AdEnergy, element_gradient, element_hessian, element_projected};
use ecc_fem::{Elastic, Filter, LinearSolver, NewtonParams, NewtonSolver, Term, Tri};
use ecc_runtime::{Energy, Rest, element_eval};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / scale.max(1e-300)
}

/// Compare the baseline with ecc at one element; returns the worst relative error.
fn compare<const D: usize, const N: usize>(
    ad: AdEnergy,
    e: &dyn Energy<D>,
    rest: &Rest<D>,
    x: &ecc_runtime::Nodes<D>,
) -> f64
where
    ecc_runtime::Space<D>: ecc_runtime::Dim<D>,
{
    let flat: Vec<f64> = x.as_ref().iter().flatten().copied().collect();
    let ev = element_eval(e, rest, x, Filter::None, true);
    let Some((v, g, h)) = element_hessian::<D, N>(ad, rest, &flat) else {
        // the barrier's domain: det F ≤ 0 (`element_eval` itself does not
        // check it; the `Elastic` term does)
        let f = ecc_runtime::element_f(rest, x);
        assert!(
            ad.barrier() && <ecc_runtime::Space<D> as ecc_runtime::Dim<D>>::det(&f) <= 0.0,
            "baseline outside at {f}"
        );
        return 0.0;
    };
    let (v1, g1) = element_gradient::<D, N>(ad, rest, &flat).expect("inside");
    let hs = (0..N * N)
        .map(|k| ev.hess[(k / N, k % N)].abs())
        .fold(0.0, f64::max);
    // at a stationary point (rest) ∇e and e may be 0: scale their errors by
    // the Hessian's size times |x| (the rounding they carry)
    let xs = flat.iter().fold(1.0f64, |a, c| a.max(c.abs()));
    let gs = (0..N).map(|k| ev.grad[k].abs()).fold(hs * xs, f64::max);
    let vs = ev.psi.abs().max(hs * xs * xs);
    let mut worst = rel(v, ev.psi, vs).max(rel(v1, v, vs));
    for i in 0..N {
        worst = worst
            .max(rel(g[i], ev.grad[i], gs))
            .max(rel(g1[i], g[i], gs));
        for j in 0..N {
            worst = worst.max(rel(h[(i, j)], ev.hess[(i, j)], hs));
        }
    }
    worst
}

fn rest2(r: &mut ChaCha8Rng) -> Rest<2> {
    loop {
        let p = std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        if let Ok(rest) = Rest::<2>::new(p)
            && rest.measure > 0.05
        {
            return rest;
        }
    }
}

fn rest3(r: &mut ChaCha8Rng) -> Rest<3> {
    loop {
        let p = std::array::from_fn(|_| std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
        if let Ok(rest) = Rest::<3>::new(p)
            && rest.measure > 0.02
        {
            return rest;
        }
    }
}

/// Deformed nodes with deformation gradient `f`: x_0 = 0, Ds = F Dm.
fn nodes2(rest: &Rest<2>, f: Matrix2<f64>) -> [[f64; 2]; 3] {
    let ds = f * rest.dm_inv.try_inverse().expect("rest is invertible");
    let mut x = [[0.0; 2]; 3];
    for j in 0..2 {
        let c: Vector2<f64> = ds.column(j).into();
        x[j + 1] = [c[0] + 0.3, c[1] - 0.2];
    }
    x[0] = [0.3, -0.2];
    x
}

fn nodes3(rest: &Rest<3>, f: Matrix3<f64>) -> [[f64; 3]; 4] {
    let ds = f * rest.dm_inv.try_inverse().expect("rest is invertible");
    let mut x = [[0.1, 0.2, -0.3]; 4];
    for j in 0..3 {
        let c: Vector3<f64> = ds.column(j).into();
        x[j + 1] = [c[0] + 0.1, c[1] + 0.2, c[2] - 0.3];
    }
    x
}

/// Random F near I plus hard ones (rest, uniform scale, repeated σ, inversion, stretch).
fn fs2(r: &mut ChaCha8Rng) -> Vec<Matrix2<f64>> {
    let mut v = vec![
        Matrix2::identity(),
        Matrix2::identity() * 1.7,
        Matrix2::new(2.0, 0.0, 0.0, 2.0 + 1e-9),
        Matrix2::new(1.0, 0.0, 0.0, -0.5),
        Matrix2::new(30.0, 1.0, 0.0, 0.2),
        Matrix2::new(0.0, -1.0, 1.0, 0.0),
    ];
    v.extend(
        (0..40).map(|_| Matrix2::identity() + Matrix2::from_fn(|_, _| r.gen_range(-0.6..0.6))),
    );
    v
}

fn fs3(r: &mut ChaCha8Rng) -> Vec<Matrix3<f64>> {
    let mut v = vec![
        Matrix3::identity(),
        Matrix3::identity() * 0.6,
        Matrix3::from_diagonal(&Vector3::new(1.5, 1.5, 0.7)),
        Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -0.4)),
        Matrix3::from_diagonal(&Vector3::new(25.0, 0.3, 0.9)),
    ];
    v.extend(
        (0..40).map(|_| Matrix3::identity() + Matrix3::from_fn(|_, _| r.gen_range(-0.5..0.5))),
    );
    v
}

#[test]
fn raw_hessian_matches_ecc_2d() {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let set: [(AdEnergy, Arc<dyn Energy<2>>); 3] = [
        (
            AdEnergy::Sd,
            Arc::new(ecc_energies::SymmetricDirichlet2::new()),
        ),
        (
            AdEnergy::for_name("SNH", 2).unwrap(),
            Arc::new(ecc_energies::StableNeoHookean::new()),
        ),
        (AdEnergy::Arap2, Arc::new(ecc_energies::Arap::new())),
    ];
    for (ad, e) in &set {
        for f in fs2(&mut r) {
            let rest = rest2(&mut r);
            let err = compare::<2, 6>(*ad, &**e, &rest, &nodes2(&rest, f));
            assert!(err <= 1e-10, "{ad:?} at F = {f}: relative error {err:e}");
        }
    }
}

#[test]
fn raw_hessian_matches_ecc_3d() {
    let mut r = ChaCha8Rng::seed_from_u64(8);
    let set: [(AdEnergy, Arc<dyn Energy<3>>); 2] = [
        (
            AdEnergy::Sd,
            Arc::new(ecc_energies::SymmetricDirichlet3::new()),
        ),
        (
            AdEnergy::for_name("SNH", 3).unwrap(),
            Arc::new(ecc_energies::StableNeoHookean::new()),
        ),
    ];
    for (ad, e) in &set {
        for f in fs3(&mut r) {
            let rest = rest3(&mut r);
            let err = compare::<3, 12>(*ad, &**e, &rest, &nodes3(&rest, f));
            assert!(err <= 1e-10, "{ad:?} at F = {f}: relative error {err:e}");
        }
    }
}

#[test]
fn projected_is_psd_and_barrier_is_infinite() {
    let mut r = ChaCha8Rng::seed_from_u64(9);
    let rest = rest2(&mut r);
    // SNH inverted: indefinite raw Hessian, PSD after the projection
    let x = nodes2(&rest, Matrix2::new(1.0, 0.2, 0.0, -0.6));
    let flat: Vec<f64> = x.iter().flatten().copied().collect();
    let snh = AdEnergy::for_name("SNH", 2).unwrap();
    let (_, _, raw) = element_hessian::<2, 6>(snh, &rest, &flat).unwrap();
    let (_, _, p) = element_projected::<2, 6>(snh, &rest, &flat, Filter::Clamp).unwrap();
    assert!(raw.symmetric_eigenvalues().min() < -1e-6);
    let scale = p.amax();
    assert!(p.symmetric_eigenvalues().min() >= -1e-12 * scale);
    // SD is +∞ for det F ≤ 0, as the generated energy
    assert!(element_hessian::<2, 6>(AdEnergy::Sd, &rest, &flat).is_none());
    assert_eq!(AdEnergy::for_name("ARAP", 3), None);
}

/// A 4×4 grid of right triangles, stretched in x.
fn grid() -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let n = 4;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            p.push([i as f64 / n as f64, j as f64 / n as f64, 0.0]);
        }
    }
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    (p, t)
}

#[test]
fn newton_with_autodiff_term_reaches_the_analytic_minimum() {
    let (p, t) = grid();
    let e: Arc<dyn Energy<2>> = Arc::new(ecc_energies::SymmetricDirichlet2::new());
    let start: Vec<[f64; 2]> = p
        .iter()
        .map(|q| [1.6 * q[0] + 0.1 * q[1] * q[1], 0.8 * q[1] + 0.05 * q[0]])
        .collect();
    let solve = |autodiff: bool| {
        let el = Elastic::<dyn Energy<2>, Tri>::surface(e.clone(), &p, &t).unwrap();
        let rest = el.rest().to_vec();
        let inner: Box<dyn Term<2>> = Box::new(el);
        let term: Box<dyn Term<2>> = if autodiff {
            Box::new(AutodiffTerm::new(inner, AdEnergy::Sd, rest))
        } else {
            inner
        };
        let params = NewtonParams {
            tol_abs: 1e-9,
            linear_solver: LinearSolver::Cholesky,
            ..Default::default()
        };
        let mut s = NewtonSolver::new(p.len(), vec![term], &[], params).unwrap();
        let mut x = start.clone();
        let r = s.solve(&mut x).unwrap();
        (r.energy, r.grad_inf, x)
    };
    let (ea, ga, xa) = solve(false);
    let (eb, gb, xb) = solve(true);
    assert!(ga <= 1e-9 && gb <= 1e-9, "gradients {ga:e} {gb:e}");
    assert!((ea - eb).abs() <= 1e-12 * ea.abs(), "energies {ea} {eb}");
    // the minimum is unique up to a rigid motion: compare edge lengths
    let len = |x: &[[f64; 2]], a: usize, b: usize| (x[a][0] - x[b][0]).hypot(x[a][1] - x[b][1]);
    for tri in &t {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let d = (len(&xa, a, b) - len(&xb, a, b)).abs();
            assert!(d < 1e-7, "edge {a}-{b} lengths differ by {d:e}");
        }
    }
}
