//! The interior system of the Tutte embedding, `L_II u_I = −L_IB u_B`
//! (two right-hand sides, u and v), assembled and solved.
//!
//! * **Assembly** straight into compressed columns, column by column: each
//!   interior vertex visits its triangles (a counting sort of the corners),
//!   sums its row's diagonal and right-hand side and sorts its column's few
//!   entries by row, duplicates summed ([`assemble`]) — linear, every array
//!   written in order, no global triplet sort.
//! * **Symmetric weights** (uniform, cotangent): sparse Cholesky (faer,
//!   supernodal) under a **geometric nested dissection** ordering
//!   ([`crate::dissection`], shared with the Newton solver's `geometric`
//!   ordering; for a planar mesh O(n log n) fill and O(n^{3/2})
//!   flops): of the interior graph, or the whole mesh's dissection given
//!   by the caller restricted to the interior
//!   ([`crate::tutte_embedding_in_order`]: the parameterisation computes
//!   one dissection for both). A system that is not positive definite
//!   (cotangent weights with obtuse angles) falls back to LU.
//! * **Mean-value weights** (not symmetric): sparse LU (faer).
//!
//! Measured (`cargo run --release -p ecc-mesh --example setup_timing`, the
//! 1M-triangle bumpy disk, best of 3, old and new binaries alternating on the
//! shared 2-core machine): at load 6–8 the old code (triplet assembly, AMD,
//! faer's default threads) took 4.45–5.61 s and this one 3.55–3.56 s; a second
//! A/B at load 4–5 gave 3.49 / 7.29 s old against 4.10 / 8.24 s new. The load
//! swamps the difference: not shown faster yet, to be re-measured on a quiet
//! machine. Fill: 36.6M factor entries against AMD's 32.4M; the AMD analysis
//! it skips took ≈0.5 s.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::solvers::Solve;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Mat, Par, Side};

use super::weights::Contribution;
use crate::dissection::Graph;
use crate::error::TutteError;
use crate::topology::VertexTriangles;

/// The interior matrix (compressed columns, sorted rows, no duplicates) and
/// the right-hand sides, one row per interior unknown.
pub(super) struct System {
    pub a: SparseColMat<usize, f64>,
    pub rhs: Mat<f64>,
}

fn solve_error(message: String) -> TutteError {
    TutteError::Solve { message }
}

/// The contributions `(i, j, w)` of triangle `t`, appended to `out`
/// (computed again each time they are asked for, rather than stored: six
/// per triangle were 144 MB on the 1M-triangle disk), or the error that
/// stops the assembly.
pub(super) type Contributions<'a> =
    dyn Fn(usize, &mut Vec<Contribution>) -> Result<(), TutteError> + 'a;

/// Assemble `L_II` and `−L_IB u_B` from the triangles' contributions
/// `(i, j, w)` (row i gains +w on its diagonal and −w at column j).
/// `interior[v]` is v's unknown or `usize::MAX` on the boundary.
///
/// Column by column: each interior vertex visits its triangles
/// ([`VertexTriangles`]), takes the contributions in its row (diagonal,
/// right-hand side) and in its column (entries), sorts the column's short
/// list by row and sums duplicates. Every array is written in order, where
/// scattering the contributions into columns first cost more (the
/// 1M-triangle disk, `setup_timing`: 0.18 s → 0.10–0.12 s). The error is
/// the first triangle's, in triangle order, as one pass over the triangles
/// would report it.
pub(super) fn assemble(
    triangles: &[[usize; 3]],
    contributions: &Contributions<'_>,
    interior: &[usize],
    uv: &[[f64; 2]],
    m: usize,
) -> Result<System, TutteError> {
    let around = VertexTriangles::of(triangles, interior.len())?;
    let mut vertex = vec![0usize; m];
    for (v, &c) in interior.iter().enumerate() {
        if let Some(slot) = vertex.get_mut(c) {
            *slot = v;
        }
    }
    let mut rhs = Mat::<f64>::zeros(m, 2);
    let mut col_ptr = Vec::with_capacity(m + 1);
    // a vertex of a disk has about as many neighbours as triangles
    let mut row_idx = Vec::with_capacity(3 * triangles.len() + m);
    let mut values = Vec::with_capacity(3 * triangles.len() + m);
    col_ptr.push(0);
    let (mut contrib, mut column) = (Vec::with_capacity(6), Vec::new());
    for (c, &v) in vertex.iter().enumerate() {
        column.clear();
        let (mut diagonal, mut b) = (0.0, [0.0; 2]);
        for &t in around.around(v) {
            contrib.clear();
            if contributions(t, &mut contrib).is_err() {
                return Err(first_error(triangles.len(), contributions));
            }
            for &(i, j, w) in &contrib {
                if i == v {
                    diagonal += w;
                    if interior[j] == usize::MAX {
                        b = [b[0] + w * uv[j][0], b[1] + w * uv[j][1]];
                    }
                } else if j == v && interior[i] != usize::MAX {
                    column.push((interior[i], -w));
                }
            }
        }
        (rhs[(c, 0)], rhs[(c, 1)]) = (b[0], b[1]);
        column.push((c, diagonal));
        push_column(&mut column, &mut row_idx, &mut values);
        col_ptr.push(row_idx.len());
    }
    // the triangles without an interior corner enter no equation, but a
    // bad weight there is an error all the same
    let outside = |t: &[usize; 3]| t.iter().all(|&v| interior[v] == usize::MAX);
    for (t, _) in triangles.iter().enumerate().filter(|(_, t)| outside(t)) {
        contrib.clear();
        contributions(t, &mut contrib)?;
    }
    let sym = SymbolicSparseColMat::new_checked(m, m, col_ptr, None, row_idx);
    Ok(System {
        a: SparseColMat::new(sym, values),
        rhs,
    })
}

/// The error of the first triangle (in order) whose contributions fail.
fn first_error(n_triangles: usize, contributions: &Contributions<'_>) -> TutteError {
    let mut contrib = Vec::with_capacity(6);
    for t in 0..n_triangles {
        contrib.clear();
        if let Err(e) = contributions(t, &mut contrib) {
            return e;
        }
    }
    solve_error("internal error: a triangle's weights failed, then did not".into())
}

/// Sort a column's `(row, value)` entries by row, sum duplicates and
/// append them.
fn push_column(column: &mut [(usize, f64)], row_idx: &mut Vec<usize>, values: &mut Vec<f64>) {
    column.sort_unstable_by_key(|e| e.0);
    let first = row_idx.len();
    for &(r, w) in column.iter() {
        match values.last_mut() {
            Some(last) if row_idx.len() > first && row_idx.last() == Some(&r) => *last += w,
            _ => {
                row_idx.push(r);
                values.push(w);
            }
        }
    }
}

/// [`crate::dissection::nested_dissection`] of the graph of `a` (symmetric
/// pattern, compressed columns) with vertex coordinates `pos`.
pub(super) fn nested_dissection(a: &SparseColMat<usize, f64>, pos: &[[f64; 3]]) -> Vec<usize> {
    let graph = Graph {
        ptr: a.symbolic().col_ptr(),
        idx: a.symbolic().row_idx(),
    };
    crate::dissection::nested_dissection(graph, pos)
}

/// The vertex order `order` (`order[new] = old vertex`) restricted to the
/// `m` interior unknowns (`interior[v]`, `usize::MAX` on the boundary), or
/// `None` unless `order` is a permutation of the vertices. Dropping the
/// boundary keeps a nested dissection one: a fill path among the interior
/// vertices is one in the whole graph.
pub(super) fn interior_order(order: &[usize], interior: &[usize], m: usize) -> Option<Vec<usize>> {
    if order.len() != interior.len() {
        return None;
    }
    let mut seen = vec![false; order.len()];
    let mut perm = Vec::with_capacity(m);
    for &v in order {
        if std::mem::replace(seen.get_mut(v)?, true) {
            return None;
        }
        if interior[v] != usize::MAX {
            perm.push(interior[v]);
        }
    }
    Some(perm)
}

/// Solve the symmetric system in place by Cholesky in the fill-reducing
/// order `perm` (`perm[new] = old`); `Ok(false)` when it is not positive
/// definite.
pub(super) fn solve_cholesky(sys: &mut System, perm: &[usize]) -> Result<bool, TutteError> {
    let m = sys.a.nrows();
    let inv = crate::dissection::inverse_permutation(perm);
    let ordering = SymmetricOrdering::Custom(PermRef::new_checked(perm, &inv, m));
    let symbolic = factorize_symbolic_cholesky(
        sys.a.symbolic(),
        Side::Lower,
        ordering,
        CholeskySymbolicParams::default(),
    )
    .map_err(|e| solve_error(format!("symbolic Cholesky: {e:?}")))?;
    // sequential: faer's parallel supernodal factorisation is no faster on
    // this 2D system with 2 cores (measured), and the caller may run threads
    let par = Par::Seq;
    let req = StackReq::any_of(&[
        symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        symbolic.solve_in_place_scratch::<f64>(2, par),
    ]);
    let mut mem = MemBuffer::try_new(req)
        .map_err(|_| solve_error("out of memory for the Cholesky scratch".into()))?;
    let mut l_values = vec![0.0; symbolic.len_val()];
    let ok = symbolic
        .factorize_numeric_llt::<f64>(
            &mut l_values,
            sys.a.as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .is_ok();
    if ok {
        LltRef::<'_, usize, f64>::new(&symbolic, &l_values).solve_in_place_with_conj(
            Conj::No,
            sys.rhs.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
    }
    // faer's kernels may leave AVX state dirty on this thread (ecc_util::simd)
    ecc_util::clear_upper_simd();
    Ok(ok)
}

/// Solve the (possibly non-symmetric) system in place by sparse LU.
pub(super) fn solve_lu(sys: &mut System) -> Result<(), TutteError> {
    let lu = sys
        .a
        .sp_lu()
        .map_err(|e| solve_error(format!("sparse LU: {e}")))?;
    lu.solve_in_place(sys.rhs.as_mut());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tutte::weights::triangle_contributions;
    use crate::types::TutteWeights;

    /// The interior system of a generated disk (boundary at its rest positions).
    fn disk_system(rings: usize) -> (System, Vec<[f64; 3]>) {
        let mesh = crate::disk_tri(rings, 1.0);
        let n = mesh.positions.len();
        let first_outer = n - 6 * rings;
        let interior: Vec<usize> = (0..n)
            .map(|v| if v < first_outer { v } else { usize::MAX })
            .collect();
        let uv: Vec<[f64; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
        let each = |f: usize, out: &mut Vec<Contribution>| {
            triangle_contributions(
                TutteWeights::Uniform,
                mesh.triangles[f],
                &mesh.positions,
                out,
            )
            .unwrap();
            Ok(())
        };
        let sys = assemble(&mesh.triangles, &each, &interior, &uv, first_outer).unwrap();
        (sys, mesh.positions[..first_outer].to_vec())
    }

    /// A fan around vertex 0 (ring 1..=6) with an ear `[1, 7, 2]` whose
    /// corners are all on the boundary, positions perturbed.
    fn fan_with_ear() -> (Vec<[usize; 3]>, Vec<[f64; 3]>, Vec<usize>) {
        let mut tris: Vec<[usize; 3]> = (0..6).map(|i| [0, 1 + i, 1 + (i + 1) % 6]).collect();
        tris.insert(2, [1, 7, 2]);
        let mut pos = vec![[0.1, -0.05, 0.02]];
        for i in 0..6 {
            let a = std::f64::consts::TAU * i as f64 / 6.0 + 0.1 * (i % 2) as f64;
            pos.push([a.cos(), a.sin(), 0.1 * i as f64]);
        }
        pos.push([1.2, 0.9, -0.3]);
        let interior = (0..8)
            .map(|v| if v == 0 { 0 } else { usize::MAX })
            .collect();
        (tris, pos, interior)
    }

    /// The assembly equals the dense sum of every triangle's contributions,
    /// for each kind of weights, on a mesh with a vertex-less ear and on a
    /// disk with 37 unknowns.
    #[test]
    fn the_assembly_is_the_dense_sum_of_the_contributions() {
        let mut meshes = vec![fan_with_ear()];
        let disk = crate::disk_tri(4, 1.0);
        let n = disk.positions.len();
        let first_outer = n - 24;
        let mut pos = disk.positions.clone();
        for (v, p) in pos.iter_mut().enumerate() {
            p[2] = 0.1 * (v as f64).sin();
        }
        let interior = (0..n).map(|v| if v < first_outer { v } else { usize::MAX });
        meshes.push((disk.triangles.clone(), pos, interior.collect()));
        for (tris, pos, interior) in &meshes {
            let m = interior.iter().filter(|&&c| c != usize::MAX).count();
            let uv: Vec<[f64; 2]> = pos.iter().map(|p| [p[0] + p[2], p[1]]).collect();
            for weights in [
                TutteWeights::Uniform,
                TutteWeights::Cotangent,
                TutteWeights::MeanValue,
            ] {
                let each = |f: usize, out: &mut Vec<Contribution>| {
                    triangle_contributions(weights, tris[f], pos, out).unwrap();
                    Ok(())
                };
                let sys = assemble(tris, &each, interior, &uv, m).unwrap();
                let (mut dense, mut rhs) = (vec![vec![0.0; m]; m], vec![[0.0; 2]; m]);
                let mut all = Vec::new();
                for f in 0..tris.len() {
                    each(f, &mut all).unwrap();
                }
                for (i, j, w) in all {
                    let Some(r) = Some(interior[i]).filter(|&r| r != usize::MAX) else {
                        continue;
                    };
                    dense[r][r] += w;
                    match interior[j] {
                        usize::MAX => (0..2).for_each(|k| rhs[r][k] += w * uv[j][k]),
                        c => dense[r][c] -= w,
                    }
                }
                let (cp, ri) = (sys.a.symbolic().col_ptr(), sys.a.symbolic().row_idx());
                let mut got = vec![vec![0.0; m]; m];
                for c in 0..m {
                    let rows = &ri[cp[c]..cp[c + 1]];
                    assert!(rows.windows(2).all(|w| w[0] < w[1]), "{weights:?}");
                    for (k, &r) in rows.iter().enumerate() {
                        got[r][c] = sys.a.val()[cp[c] + k];
                    }
                }
                for r in 0..m {
                    for c in 0..m {
                        assert!(
                            (got[r][c] - dense[r][c]).abs() < 1e-13,
                            "{weights:?} {r} {c}"
                        );
                        let structural = dense[r][c] != 0.0 || r == c;
                        assert!(!structural || ri[cp[c]..cp[c + 1]].contains(&r));
                    }
                    for (k, want) in rhs[r].iter().enumerate() {
                        assert!((sys.rhs[(r, k)] - want).abs() < 1e-13, "{weights:?}");
                    }
                }
            }
        }
    }

    /// The error is the first failing triangle's in triangle order, also
    /// when that triangle has no interior corner.
    #[test]
    fn the_first_bad_triangle_is_reported() {
        let (tris, pos, interior) = fan_with_ear();
        let uv = vec![[0.0; 2]; pos.len()];
        for bad in [vec![5, 1], vec![2, 6], vec![2], vec![6, 0]] {
            let each = |f: usize, out: &mut Vec<Contribution>| {
                if bad.contains(&f) {
                    return Err(solve_error(format!("triangle {f}")));
                }
                triangle_contributions(TutteWeights::Uniform, tris[f], &pos, out).unwrap();
                Ok(())
            };
            let first = bad.iter().min().unwrap();
            let e = assemble(&tris, &each, &interior, &uv, 1).err();
            let e = e.unwrap_or_else(|| panic!("{bad:?} passed"));
            assert_eq!(
                e.to_string(),
                solve_error(format!("triangle {first}")).to_string()
            );
        }
    }

    #[test]
    fn dissection_is_a_permutation_with_small_separators() {
        let (sys, pos) = disk_system(30);
        let perm = nested_dissection(&sys.a, &pos);
        let mut seen = vec![false; pos.len()];
        for &v in &perm {
            assert!(!seen[v], "vertex {v} ordered twice");
            seen[v] = true;
        }
        assert!(seen.iter().all(|&s| s));
        // the factor stays within 1.5× AMD's fill (measured: 1.26× here, 1.13×
        // on the 1M-triangle disk, where skipping AMD's analysis pays)
        let sym = |o| {
            factorize_symbolic_cholesky(sys.a.symbolic(), Side::Lower, o, Default::default())
                .unwrap()
                .len_val()
        };
        let inv = crate::dissection::inverse_permutation(&perm);
        let nd = sym(SymmetricOrdering::Custom(PermRef::new_checked(
            &perm,
            &inv,
            perm.len(),
        )));
        let amd = sym(SymmetricOrdering::Amd);
        assert!(nd as f64 <= 1.5 * amd as f64, "fill {nd} vs AMD {amd}");
    }

    #[test]
    fn cholesky_and_lu_agree() {
        let (mut a, pos) = disk_system(20);
        let (mut b, _) = disk_system(20);
        let perm = nested_dissection(&a.a, &pos);
        assert!(solve_cholesky(&mut a, &perm).unwrap());
        solve_lu(&mut b).unwrap();
        for r in 0..pos.len() {
            for c in 0..2 {
                assert!((a.rhs[(r, c)] - b.rhs[(r, c)]).abs() < 1e-12);
            }
            // maximum principle: the interior stays inside the boundary's hull
            assert!(a.rhs[(r, 0)].hypot(a.rhs[(r, 1)]) < 1.0);
        }
    }
}
