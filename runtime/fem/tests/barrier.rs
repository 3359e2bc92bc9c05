//! Barrier energies never invert an element: det F > 0 after every step,
//! and the inversion-free bound is what keeps it so.

mod common;

use std::ops::ControlFlow;
use std::sync::Arc;

use common::grid;
use ecc_fem::quality::{count_flipped, min_signed_area};
use ecc_fem::{Elastic, NewtonParams, NewtonSolver, Term, Tri};
use ecc_runtime::energies::SymmetricDirichlet;

/// Fixed boundary at rest, interior squeezed towards the centre: a valid but
/// strongly compressed start that SD must expand without folding.
#[test]
fn symmetric_dirichlet_never_inverts_an_element() {
    let m = 16;
    let (rest, tris) = grid(m);
    let w = m + 1;
    let boundary: Vec<usize> = (0..w * w)
        .filter(|v| v % w == 0 || v % w == m || v / w == 0 || v / w == m)
        .collect();
    for squeeze in [0.5, 0.15] {
        let x0: Vec<[f64; 2]> = rest
            .iter()
            .enumerate()
            .map(|(v, p)| {
                if boundary.contains(&v) {
                    *p
                } else {
                    // squeeze and swirl about the centre
                    let (dx, dy) = (p[0] - 0.5, p[1] - 0.5);
                    let a = 1.2 * (1.0 - 2.0 * dx.abs().max(dy.abs()));
                    let (c, s) = (a.cos(), a.sin());
                    [
                        0.5 + squeeze * (c * dx - s * dy),
                        0.5 + squeeze * (s * dx + c * dy),
                    ]
                }
            })
            .collect();
        assert_eq!(count_flipped(&x0, &tris), 0, "the start must be valid");
        let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(
            Elastic::<_, Tri>::planar(Arc::new(SymmetricDirichlet), &rest, &tris).unwrap(),
        )];
        let params = NewtonParams {
            tol_abs: 1e-8,
            ..Default::default()
        };
        let mut solver = NewtonSolver::new(rest.len(), terms, &boundary, params).unwrap();
        let mut x = x0.clone();
        let mut checked = 0;
        let mut bound_active = 0;
        let r = solver
            .solve_with(&mut x, |rec, x| {
                assert_eq!(
                    count_flipped(x, &tris),
                    0,
                    "step {} inverted an element",
                    rec.iter
                );
                assert!(min_signed_area(x, &tris) > 0.0);
                checked += 1;
                if rec.max_step.is_some_and(|a| a < 1.0 / 0.9) {
                    bound_active += 1;
                }
                ControlFlow::Continue(())
            })
            .unwrap();
        assert!(r.converged(), "squeeze {squeeze}: {:?}", r.status);
        assert_eq!(checked, r.iterations);
        println!(
            "squeeze {squeeze}: {} iterations, bound active in {bound_active}, E {} -> {}",
            r.iterations, r.initial_energy, r.energy
        );
        // the minimiser with the boundary at rest is the identity
        let err = x
            .iter()
            .zip(&rest)
            .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
            .fold(0.0, f64::max);
        assert!(err < 1e-6, "identity not recovered: {err}");
    }
}

/// A stiff soft handle drags an interior vertex far across its one-ring: the
/// quadratic model's full step would fold triangles, so the inversion-free
/// bound must cut the steps; the result is a valid compromise.
#[test]
fn dragged_vertex_is_stopped_by_the_inversion_free_bound() {
    let m = 8;
    let (rest, tris) = grid(m);
    let w = m + 1;
    let boundary: Vec<usize> = (0..w * w)
        .filter(|v| v % w == 0 || v % w == m || v / w == 0 || v / w == m)
        .collect();
    let dragged = 4 * w + 4; // centre vertex at (0.5, 0.5)
    let terms: Vec<Box<dyn Term<2>>> = vec![
        Box::new(Elastic::<_, Tri>::planar(Arc::new(SymmetricDirichlet), &rest, &tris).unwrap()),
        Box::new(ecc_fem::SoftAnchors::new(vec![dragged], vec![[0.95, 0.55]], vec![1e4]).unwrap()),
    ];
    let mut solver =
        NewtonSolver::new(rest.len(), terms, &boundary, NewtonParams::default()).unwrap();
    let mut x = rest.clone();
    let mut bound_cut = 0;
    let r = solver
        .solve_with(&mut x, |rec, x| {
            assert_eq!(
                count_flipped(x, &tris),
                0,
                "step {} inverted an element",
                rec.iter
            );
            if rec.max_step.is_some_and(|a| a < 1.0) {
                bound_cut += 1;
                assert!(rec.step <= 0.9 * rec.max_step.unwrap() + 1e-15);
            }
            ControlFlow::Continue(())
        })
        .unwrap();
    assert!(r.converged(), "{:?}", r.status);
    assert!(
        bound_cut >= 1,
        "the full step never had to be cut by the barrier bound"
    );
    assert!(
        x[dragged][0] > 0.6,
        "the handle moved the vertex: {:?}",
        x[dragged]
    );
    println!(
        "dragged: {} iterations, bound cut {bound_cut} steps, vertex at {:?}",
        r.iterations, x[dragged]
    );
}

/// 3D: symmetric Dirichlet on a tet cube, boundary fixed at rest, interior
/// squeezed and twisted; every accepted step keeps every tet positive.
#[test]
fn symmetric_dirichlet_never_inverts_a_tet() {
    use ecc_fem::Tet;
    use ecc_fem::quality::{count_inverted, min_signed_volume};
    let (rest, tets) = common::tet_grid(4);
    let on_boundary = |p: &[f64; 3]| p.iter().any(|&c| !(1e-9..=1.0 - 1e-9).contains(&c));
    let boundary: Vec<usize> = (0..rest.len()).filter(|&v| on_boundary(&rest[v])).collect();
    let x0: Vec<[f64; 3]> = rest
        .iter()
        .map(|p| {
            if on_boundary(p) {
                *p
            } else {
                let d = [p[0] - 0.5, p[1] - 0.5, p[2] - 0.5];
                let a = 0.8 * (1.0 - 2.0 * d[0].abs().max(d[1].abs()).max(d[2].abs()));
                let (c, s) = (a.cos(), a.sin());
                [
                    0.5 + 0.4 * (c * d[0] - s * d[1]),
                    0.5 + 0.4 * (s * d[0] + c * d[1]),
                    0.5 + 0.4 * d[2],
                ]
            }
        })
        .collect();
    assert_eq!(count_inverted(&x0, &tets), 0, "the start must be valid");
    let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(
        Elastic::<_, Tet>::new(Arc::new(SymmetricDirichlet), &rest, &tets).unwrap(),
    )];
    let mut solver =
        NewtonSolver::new(rest.len(), terms, &boundary, NewtonParams::default()).unwrap();
    let mut x = x0;
    let r = solver
        .solve_with(&mut x, |rec, x| {
            assert_eq!(
                count_inverted(x, &tets),
                0,
                "step {} inverted a tet",
                rec.iter
            );
            assert!(min_signed_volume(x, &tets) > 0.0);
            ControlFlow::Continue(())
        })
        .unwrap();
    assert!(r.converged(), "{:?}", r.status);
    let err = x
        .iter()
        .zip(&rest)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0, f64::max);
    assert!(err < 1e-5, "identity not recovered: {err}");
}
