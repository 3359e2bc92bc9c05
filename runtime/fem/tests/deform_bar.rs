//! ARAP deformation of the IPC bar (bar-2523.mesh) with fixed and moved handles.

mod common;

use std::ops::ControlFlow;
use std::sync::Arc;

use ecc_fem::deform::{HandleDeformation, vertices_where};
use ecc_fem::{NewtonParams, NewtonStatus};
use ecc_mesh::read_tet_mesh;
use ecc_runtime::energies::Arap;

#[test]
fn arap_bar_with_fixed_and_moved_handles_converges() {
    let mesh = read_tet_mesh(common::data("bar-2523.mesh")).unwrap();
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p[0]), b.max(p[0]))
        });
    let left = vertices_where(&mesh.positions, |p| p[0] <= lo + 0.25);
    let right = vertices_where(&mesh.positions, |p| p[0] >= hi - 0.25);
    assert!(!left.is_empty() && !right.is_empty());
    let handles: Vec<usize> = left.iter().chain(&right).copied().collect();
    let mut def =
        HandleDeformation::new(&mesh, Arc::new(Arap), &handles, NewtonParams::default()).unwrap();
    // left end fixed; right end twisted 90° about the bar axis and lifted
    let c = mesh
        .positions
        .iter()
        .fold([0.0; 3], |a, p| [a[0], a[1] + p[1], a[2] + p[2]]);
    let (cy, cz) = (
        c[1] / mesh.positions.len() as f64,
        c[2] / mesh.positions.len() as f64,
    );
    let targets: Vec<[f64; 3]> = handles
        .iter()
        .map(|&h| {
            let p = mesh.positions[h];
            if p[0] <= lo + 0.25 {
                p
            } else {
                let (y, z) = (p[1] - cy, p[2] - cz);
                [p[0] - 1.0, cy - z + 2.0, cz + y]
            }
        })
        .collect();
    let r = def.solve(&targets, 1).unwrap();
    let last = r.substeps.last().unwrap();
    assert!(
        r.converged(),
        "{:?} after {} iterations, |g| {}",
        last.status,
        last.iterations,
        last.grad_inf
    );
    assert!(last.grad_inf <= 1e-4);
    for (&h, t) in handles.iter().zip(&targets) {
        assert_eq!(def.positions()[h], *t, "handle {h} must sit at its target");
    }
    assert!(last.energy > 0.0 && last.energy < last.initial_energy);
    assert_eq!(last.symbolic_analyses, 1);
    println!(
        "bar ARAP: {} iterations, E {:.6e}, |g| {:.2e}, inverted {}, {:.3}s",
        last.iterations, last.energy, last.grad_inf, r.inverted, last.times.total
    );
}

#[test]
fn solve_with_reports_every_step_and_stops_on_break() {
    let mesh = read_tet_mesh(common::data("bar-2523.mesh")).unwrap();
    let lo = mesh
        .positions
        .iter()
        .map(|p| p[0])
        .fold(f64::INFINITY, f64::min);
    let handles = vertices_where(&mesh.positions, |p| p[0] <= lo + 0.25);
    let targets: Vec<[f64; 3]> = handles
        .iter()
        .map(|&h| {
            let p = mesh.positions[h];
            [p[0], p[1] + 0.5, p[2]]
        })
        .collect();
    let new = || {
        HandleDeformation::new(&mesh, Arc::new(Arap), &handles, NewtonParams::default()).unwrap()
    };
    // every Newton step of every substep reaches the callback
    let mut steps = 0;
    let r = new()
        .solve_with(&targets, 2, |_, _| {
            steps += 1;
            ControlFlow::Continue(())
        })
        .unwrap();
    assert!(r.converged());
    assert_eq!(steps, r.iterations());
    // Break after the first step: interrupted, no second substep
    let mut calls = 0;
    let r = new()
        .solve_with(&targets, 2, |_, _| {
            calls += 1;
            ControlFlow::Break(())
        })
        .unwrap();
    assert_eq!(calls, 1);
    assert_eq!(r.substeps.len(), 1);
    assert_eq!(r.substeps[0].status, NewtonStatus::Interrupted);
    assert!(!r.converged());
}
