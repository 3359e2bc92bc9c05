//! Exactness of the preconditioners where they must be exact, breakdown
//! handling, and positive definiteness of M.

use super::block_jacobi::BlockJacobi;
use super::ic0::Ic0;
use super::{Preconditioner, State};
use crate::dofs::DofMap;
use crate::pattern::{Pattern, StencilSet, build};

/// Pattern of `edges` (pairs of vertices) with `dim` unknowns per vertex.
fn pattern(n_vertices: usize, dim: usize, edges: &[usize]) -> Pattern {
    let dofs = DofMap::all_free(n_vertices, dim).unwrap();
    build(
        &[StencilSet {
            name: "e",
            arity: 2,
            stencils: edges,
        }],
        &dofs,
    )
    .unwrap()
    .0
}

/// max |H z − r| for z = M⁻¹ r.
fn residual(p: &Pattern, v: &[f64], m: &State, r: &[f64]) -> f64 {
    let mut z = vec![0.0; r.len()];
    m.apply(r, &mut z);
    let mut hz = vec![0.0; r.len()];
    p.sym_matvec(v, &z, &mut hz);
    hz.iter()
        .zip(r)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

fn rhs(n: usize) -> Vec<f64> {
    (0..n).map(|i| (0.7 * i as f64).sin() + 0.1).collect()
}

/// Path Laplacian + I (tridiagonal: the Cholesky factor has no fill), so
/// IC(0) is the exact Cholesky factor and M⁻¹ = H⁻¹.
#[test]
fn ic0_without_fill_is_the_exact_cholesky_factor() {
    let n = 30;
    let edges: Vec<usize> = (0..n - 1).flat_map(|i| [i, i + 1]).collect();
    let p = pattern(n, 1, &edges);
    let mut v = vec![0.0; p.nnz()];
    for j in 0..n {
        v[p.diag_slot(j)] = 3.0 + (j % 3) as f64;
    }
    for e in edges.chunks(2) {
        v[p.slot(e[0], e[1]).unwrap()] = -1.0 - 0.1 * e[0] as f64 / n as f64;
    }
    let mut m = State::new(Preconditioner::Ic0, &p);
    m.setup(&p, &v);
    let err = residual(&p, &v, &m, &rhs(n));
    assert!(err < 1e-12, "IC(0) of a fill-free matrix: residual {err}");
    let State::Ic0(f) = &m else { unreachable!() };
    assert_eq!((f.shift(), f.restarts()), (0.0, 0));
}

/// 2 unknowns per vertex, no edges: H is block diagonal with 2×2 blocks.
/// Block-Jacobi finds the blocks and inverts them exactly; IC(0) too (no
/// fill); Jacobi does not.
#[test]
fn block_jacobi_and_ic0_invert_a_block_diagonal_matrix() {
    let nv = 7;
    let p = pattern(nv, 2, &[]);
    assert_eq!(p.nnz(), 3 * nv);
    let mut v = vec![0.0; p.nnz()];
    for b in 0..nv {
        v[p.diag_slot(2 * b)] = 2.0 + b as f64;
        v[p.diag_slot(2 * b + 1)] = 1.0 + 0.5 * b as f64;
        v[p.slot(2 * b, 2 * b + 1).unwrap()] = 0.9;
    }
    assert_eq!(BlockJacobi::new(&p).blocks(), nv);
    let r = rhs(2 * nv);
    for kind in [Preconditioner::BlockJacobi, Preconditioner::Ic0] {
        let mut m = State::new(kind, &p);
        m.setup(&p, &v);
        let err = residual(&p, &v, &m, &r);
        assert!(err < 1e-12, "{kind:?}: residual {err}");
    }
    let mut m = State::new(Preconditioner::Jacobi, &p);
    m.setup(&p, &v);
    assert!(residual(&p, &v, &m, &r) > 0.1);
}

/// On a mesh pattern (2D grid, 2 unknowns per vertex) the blocks are the
/// vertices.
#[test]
fn blocks_are_the_vertices_of_a_mesh_pattern() {
    let m = 5;
    let mut edges = Vec::new();
    for i in 0..m {
        for j in 0..m {
            let v = i * m + j;
            if j + 1 < m {
                edges.extend_from_slice(&[v, v + 1]);
            }
            if i + 1 < m {
                edges.extend_from_slice(&[v, v + m]);
            }
        }
    }
    for dim in [2, 3] {
        assert_eq!(
            BlockJacobi::new(&pattern(m * m, dim, &edges)).blocks(),
            m * m
        );
    }
}

/// rᵀ M⁻¹ r > 0 for every r tried.
fn positive_definite(m: &State, n: usize) -> bool {
    (0..n).all(|k| {
        let r: Vec<f64> = (0..n).map(|i| ((i * (k + 3)) as f64).cos()).collect();
        let mut z = vec![0.0; n];
        m.apply(&r, &mut z);
        r.iter().zip(&z).map(|(a, b)| a * b).sum::<f64>() > 0.0
    })
}

/// [[1, c], [c, 1]] with |c| > 1 is indefinite: IC(0) (exact here) breaks
/// down. For c = 2.5, H + α·diag(H) is positive definite from α > 1.5, reached
/// at the fifth shift (1e-3, 1e-2, 0.1, 1, 10); for c = 1e6 no shift in
/// reach works and M falls back to Jacobi; a negative diagonal entry also
/// ends in Jacobi with 1 for it. M stays positive definite in every case.
#[test]
fn ic0_breakdown_shifts_then_falls_back_to_jacobi() {
    let p = pattern(2, 1, &[0, 1]);
    let off = p.slot(0, 1).unwrap();
    let mut v = vec![0.0; p.nnz()];
    v[p.diag_slot(0)] = 1.0;
    v[p.diag_slot(1)] = 1.0;
    for (c, shift, restarts) in [(2.5, 10.0, 5), (1e6, f64::INFINITY, 7)] {
        v[off] = c;
        let mut f = Ic0::new(&p);
        f.factorize(&p, &v);
        assert_eq!((f.shift(), f.restarts()), (shift, restarts), "c = {c}");
        let mut m = State::Ic0(f);
        m.setup(&p, &v);
        assert!(positive_definite(&m, 2), "c = {c}");
    }
    v[off] = 0.5;
    v[p.diag_slot(1)] = -1.0;
    let mut f = Ic0::new(&p);
    f.factorize(&p, &v);
    assert!(f.shift().is_infinite());
    let mut z = [0.0; 2];
    f.apply(&[2.0, 3.0], &mut z);
    assert_eq!(z, [2.0, 3.0]);
    let mut m = State::new(Preconditioner::BlockJacobi, &p);
    m.setup(&p, &v);
    assert!(positive_definite(&m, 2));
}
