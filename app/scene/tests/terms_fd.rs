//! Every effect term's local gradient and Hessian against central
//! differences of its value (and of its gradient).

use std::sync::Arc;

use ecc_fem::{Filter, Term};
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_scene::spec::{GroundKind, MassKind};
use ecc_scene::terms::{
    Blend, Gravity, Ground, MassMatrix, MassQuadratic, StiffnessDamping, vertex_masses,
};
use ecc_scene::{Body, Counter, Counters};

/// A small tet body (two tets) and a perturbed state.
fn body3() -> (Body<3>, Vec<[f64; 3]>) {
    let rest = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
    ];
    let body = Body::volume(
        rest.clone(),
        &[[0, 1, 2, 3], [1, 2, 3, 4]],
        Arc::new(StableNeoHookean::new(1.0, 5.0)),
    );
    let x = rest
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let k = i as f64;
            [
                p[0] + 0.07 * (k * 1.3).sin(),
                p[1] + 0.05 * (k * 0.7).cos(),
                p[2] - 0.04 * k,
            ]
        })
        .collect();
    (body, x)
}

/// Compare gradient and Hessian of every stencil with central differences.
fn check<const D: usize>(term: &dyn Term<D>, x: &[[f64; D]], tol: f64) {
    let n = term.arity();
    let k = n * D;
    let h = 1e-6;
    for s in 0..term.n_stencils() {
        let st = &term.stencils()[s * n..(s + 1) * n];
        let mut g = vec![0.0; k];
        let mut hs = vec![0.0; k * k];
        let e = term.evaluate(s, x, Filter::None, &mut g, Some(&mut hs));
        assert!(
            (e - term.value(s, x)).abs() <= 1e-12 * e.abs().max(1.0),
            "{}: value vs evaluate",
            term.name()
        );
        for i in 0..k {
            let (a, c) = (st[i / D], i % D);
            let mut xp = x.to_vec();
            let mut xm = x.to_vec();
            xp[a][c] += h;
            xm[a][c] -= h;
            let fd = (term.value(s, &xp) - term.value(s, &xm)) / (2.0 * h);
            let scale = g[i].abs().max(1.0);
            assert!(
                (fd - g[i]).abs() <= tol * scale,
                "{} stencil {s} dof {i}: grad {} vs fd {fd}",
                term.name(),
                g[i]
            );
            let mut gp = vec![0.0; k];
            let mut gm = vec![0.0; k];
            term.evaluate(s, &xp, Filter::None, &mut gp, None);
            term.evaluate(s, &xm, Filter::None, &mut gm, None);
            for j in 0..k {
                let fd = (gp[j] - gm[j]) / (2.0 * h);
                let hv = hs[j * k + i];
                let scale = hv.abs().max(1.0);
                assert!(
                    (fd - hv).abs() <= tol * scale,
                    "{} stencil {s}: H[{j}][{i}] = {hv} vs fd {fd}",
                    term.name()
                );
            }
        }
        for i in 0..k {
            for j in 0..k {
                assert_eq!(
                    hs[i * k + j],
                    hs[j * k + i],
                    "{}: Hessian not symmetric",
                    term.name()
                );
            }
        }
    }
}

#[test]
fn gravity_is_linear_with_exact_weights() {
    let (body, x) = body3();
    let m = vertex_masses(&body, 2.0);
    let total: f64 = m.iter().sum();
    assert!((total - 2.0 * body.total_rest_measure()).abs() < 1e-14);
    let g = Gravity::new(&m, [0.0, -9.81, 1.0], Arc::new(Counters::default()));
    check::<3>(&g, &x, 1e-6);
}

#[test]
fn inertia_lumped_and_consistent() {
    let (body, x) = body3();
    let counters = Arc::new(Counters::default());
    for kind in [MassKind::Lumped, MassKind::Consistent] {
        let m = Arc::new(MassMatrix::build(&body, 3.0, kind, &counters));
        assert!((m.total() - 3.0 * body.total_rest_measure()).abs() < 1e-14);
        let mut q = MassQuadratic::new(
            "inertia",
            Counter::InertiaPass,
            m.clone(),
            5,
            counters.clone(),
        );
        q.weight = 40.0;
        q.target = body.rest.clone();
        check::<3>(&q, &x, 1e-6);
        // ½ vᵀMv of a uniform velocity is ½ m_total |v|²
        let v = vec![[1.0, 2.0, 0.0]; 5];
        assert!(
            (m.kinetic(&v) - 0.5 * m.total() * 5.0).abs() < 1e-12,
            "{kind:?}"
        );
    }
    assert_eq!(counters.values().mass_matrix_builds, 2);
}

#[test]
fn stiffness_damping_is_the_snapshot_quadratic() {
    let (body, x) = body3();
    let counters = Arc::new(Counters::default());
    let mut k = StiffnessDamping::new(body.elastic().unwrap(), 5, counters.clone());
    k.snapshot(&x, Filter::Clamp);
    k.weight = 0.3;
    k.target = body.rest.clone();
    check::<3>(&k, &x, 1e-6);
    assert_eq!(counters.values().stiffness_snapshots, 1);
}

#[test]
fn ground_barrier_and_penalty() {
    let x = vec![
        [0.0, 0.004, 0.0],
        [0.3, 0.0011, 0.2],
        [0.1, 0.5, 0.0],
        [0.0, -0.01, 0.0],
    ];
    let c = Arc::new(Counters::default());
    let barrier = Ground::new(
        vec![0, 1, 2],
        [0.0, 2.0, 0.0],
        0.0,
        GroundKind::Barrier,
        0.01,
        50.0,
        c.clone(),
    );
    check::<3>(&barrier, &x, 1e-5);
    assert_eq!(barrier.value(2, &x), 0.0, "inactive beyond dhat");
    // a vertex at or below the plane is outside the barrier's domain
    let below = Ground::new(
        vec![3],
        [0.0, 1.0, 0.0],
        0.0,
        GroundKind::Barrier,
        0.01,
        50.0,
        c.clone(),
    );
    assert_eq!(below.value(0, &x), f64::INFINITY);
    // the step bound stops exactly at the plane
    let dx = vec![[0.0, -0.008, 0.0]; 4];
    assert!((barrier.max_step(0, &x, &dx) - 0.5).abs() < 1e-12);
    assert_eq!(
        barrier.max_step(2, &x, &dx.iter().map(|d| d.map(|c| -c)).collect::<Vec<_>>()),
        f64::INFINITY
    );
    let penalty = Ground::new(
        vec![0, 3],
        [0.0, 1.0, 0.0],
        0.0,
        GroundKind::Penalty,
        0.01,
        50.0,
        c.clone(),
    );
    check::<3>(&penalty, &x, 1e-5);
    assert!((penalty.value(1, &x) - 0.5 * 50.0 * 1e-4).abs() < 1e-15);
    assert!(c.values().contact_passes > 0);
}

#[test]
fn blend_interpolates_two_rest_shapes() {
    let rest = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
    let tris = [[0, 1, 2], [1, 3, 2]];
    let body = Body::planar(rest.clone(), &tris, Arc::new(SymmetricDirichlet));
    let rest2: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| [1.5 * p[0], p[1] + 0.2 * p[0]])
        .collect();
    let c = Arc::new(Counters::default());
    let mut b = Blend::new(
        body.elastic().unwrap(),
        body.elastic_at(&rest2).unwrap(),
        c.clone(),
    )
    .unwrap();
    let x: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| [1.2 * p[0] + 0.03, 1.1 * p[1] - 0.02 * p[0]])
        .collect();
    for t in [0.0, 0.3, 1.0] {
        b.t = t;
        check::<2>(&b, &x, 1e-5);
    }
    // at t = 1 the second rest shape is the minimiser: zero gradient there
    b.t = 1.0;
    let mut g = [0.0; 6];
    let gsum: f64 = (0..2)
        .map(|s| {
            b.evaluate(s, &rest2, Filter::Clamp, &mut g, None);
            g.iter().map(|v| v.abs()).sum::<f64>()
        })
        .sum();
    assert!(gsum < 1e-12, "{gsum}");
    assert!(c.values().blend_passes > 0);
    // elements must match
    let other = Body::planar(rest.clone(), &[[0, 1, 2]], Arc::new(Arap));
    assert!(Blend::new(body.elastic().unwrap(), other.elastic().unwrap(), c).is_err());
}
