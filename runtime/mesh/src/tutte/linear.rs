//! The interior system of the Tutte embedding, `L_II u_I = −L_IB u_B`
//! (two right-hand sides, u and v), assembled and solved.
//!
//! * **Assembly** straight into compressed columns: a counting sort of the
//!   per-triangle contributions by column, then each (short) column sorted by
//!   row with duplicates summed — linear in the contributions, no global
//!   triplet sort.
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

/// The interior matrix (compressed columns, sorted rows, no duplicates) and
/// the right-hand sides, one row per interior unknown.
pub(super) struct System {
    pub a: SparseColMat<usize, f64>,
    pub rhs: Mat<f64>,
}

fn solve_error(message: String) -> TutteError {
    TutteError::Solve { message }
}

/// The triangles' contributions `(i, j, w)`, handed to a visitor one by
/// one, each time the assembly asks (they are generated again rather than
/// stored: six per triangle were 144 MB on the 1M-triangle disk); the
/// first error stops them.
pub(super) type Contributions<'a> =
    dyn Fn(&mut dyn FnMut(Contribution)) -> Result<(), TutteError> + 'a;

/// Assemble `L_II` and `−L_IB u_B` from the triangles' contributions
/// `(i, j, w)` (row i gains +w on its diagonal and −w at column j), in two
/// passes over them. `interior[v]` is v's unknown or `usize::MAX` on the
/// boundary.
pub(super) fn assemble(
    contributions: &Contributions<'_>,
    interior: &[usize],
    uv: &[[f64; 2]],
    m: usize,
) -> Result<System, TutteError> {
    let mut rhs = Mat::<f64>::zeros(m, 2);
    // one diagonal entry per column, summed apart (a vertex gets a
    // contribution per incident triangle side: half of its column's
    // entries would be diagonal duplicates to sort and sum)
    let mut count = vec![1usize; m + 1];
    count[0] = 0;
    contributions(&mut |(i, j, _)| {
        if interior[i] != usize::MAX && interior[j] != usize::MAX {
            count[interior[j] + 1] += 1;
        }
    })?;
    for c in 0..m {
        count[c + 1] += count[c];
    }
    let mut next = count.clone();
    let mut entries = vec![(0usize, 0.0f64); count[m]];
    let mut diagonal = vec![0.0; m];
    contributions(&mut |(i, j, w)| {
        let r = interior[i];
        if r == usize::MAX {
            return; // boundary rows are fixed
        }
        diagonal[r] += w;
        match interior[j] {
            usize::MAX => {
                rhs[(r, 0)] += w * uv[j][0];
                rhs[(r, 1)] += w * uv[j][1];
            }
            c => {
                entries[next[c]] = (r, -w);
                next[c] += 1;
            }
        }
    })?;
    for (c, d) in diagonal.into_iter().enumerate() {
        entries[next[c]] = (c, d);
    }
    let (col_ptr, row_idx, values) = compress(&count, &mut entries);
    let sym = SymbolicSparseColMat::new_checked(m, m, col_ptr, None, row_idx);
    Ok(System {
        a: SparseColMat::new(sym, values),
        rhs,
    })
}

/// Sort each column's `(row, value)` entries by row and sum duplicates.
fn compress(start: &[usize], entries: &mut [(usize, f64)]) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let m = start.len() - 1;
    let mut col_ptr = Vec::with_capacity(m + 1);
    let mut row_idx = Vec::with_capacity(entries.len());
    let mut values: Vec<f64> = Vec::with_capacity(entries.len());
    col_ptr.push(0);
    for c in 0..m {
        let col = &mut entries[start[c]..start[c + 1]];
        col.sort_unstable_by_key(|e| e.0);
        let first = row_idx.len();
        for &(r, w) in col.iter() {
            if row_idx.len() > first && row_idx.last() == Some(&r) {
                *values.last_mut().unwrap_or(&mut 0.0) += w;
            } else {
                row_idx.push(r);
                values.push(w);
            }
        }
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx, values)
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
        let mut contrib = Vec::new();
        for t in &mesh.triangles {
            let p = t.map(|v| mesh.positions[v]);
            triangle_contributions(TutteWeights::Uniform, *t, p, &mut contrib).unwrap();
        }
        let each = |visit: &mut dyn FnMut(Contribution)| {
            contrib.iter().for_each(|&c| visit(c));
            Ok(())
        };
        let sys = assemble(&each, &interior, &uv, first_outer).unwrap();
        (sys, mesh.positions[..first_outer].to_vec())
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
