//! The supernodes of a half ([`super::half`]) from faer's analysis of its
//! *vertex graph*, expanded to its unknowns.
//!
//! The unknowns of a mesh vertex form a dense d×d block with one sparsity
//! structure ([`crate::pattern::VertexBlocks`]), and the orderings keep a
//! vertex's unknowns together. So the factor of Bᵢ has the structure of the
//! factor of its vertex graph with every vertex expanded to its unknowns:
//! the d columns of a vertex form a chain of the elimination tree with
//! column counts c·d, c·d − 1, …, and two vertices' columns join one
//! fundamental supernode exactly when the two vertices do in the vertex
//! graph's factor. faer's symbolic analysis of the vertex graph (d² times
//! fewer entries) therefore gives the supernodes; only its relaxation (the
//! merging of small supernodes, counted in columns) is divided by d
//! (rounded up) so the relaxed supernodes are about as wide in unknowns as
//! those of the scalar analysis. On the 1M-triangle disk each half's
//! analysis took 0.3–0.4 s of setup on the scalar pattern, 0.15–0.2 s on
//! the vertex graph.

use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::SymbolicSupernodalParams;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};

use super::half::{PNodes, p_nodes_expanded};
use crate::error::FemError;
use crate::pattern::{Pattern, VertexBlocks};

/// The vertices of a half in its local order: vertex `g` holds the local
/// unknowns `start[g]..start[g + 1]` and is vertex block `block[g]`.
struct LocalGroups {
    start: Vec<usize>,
    block: Vec<usize>,
}

/// The half's unknowns `unknowns` as whole vertex blocks, each block's
/// unknowns consecutive and ascending, and P (the first `n_p`) made of
/// whole blocks; `None` otherwise.
fn local_groups(blocks: &VertexBlocks, unknowns: &[usize], n_p: usize) -> Option<LocalGroups> {
    let (mut start, mut block) = (Vec::new(), Vec::new());
    let mut l = 0;
    while l < unknowns.len() {
        let u = unknowns[l];
        let b = blocks.start.partition_point(|&s| s <= u).checked_sub(1)?;
        let (s, e) = (blocks.start[b], blocks.start[b + 1]);
        let whole = u == s
            && l + (e - s) <= unknowns.len()
            && unknowns[l..l + (e - s)].iter().copied().eq(s..e)
            && (l >= n_p || l + (e - s) <= n_p);
        if !whole {
            return None;
        }
        start.push(l);
        block.push(b);
        l += e - s;
    }
    start.push(l);
    Some(LocalGroups { start, block })
}

/// Upper CSC (pointers, rows) of the vertex graph of the local groups.
fn group_pattern(blocks: &VertexBlocks, groups: &LocalGroups) -> (Vec<usize>, Vec<usize>) {
    let ng = groups.block.len();
    let mut local = vec![usize::MAX; blocks.start.len() - 1];
    groups
        .block
        .iter()
        .enumerate()
        .for_each(|(g, &b)| local[b] = g);
    let rows = |g: usize| {
        let b = groups.block[g];
        blocks.adj[blocks.adj_ptr[b]..blocks.adj_ptr[b + 1]]
            .iter()
            .map(|&nb| local[nb])
            .filter(move |&h| h < g)
    };
    let mut col_ptr = vec![0usize; ng + 1];
    for g in 0..ng {
        col_ptr[g + 1] = col_ptr[g] + rows(g).count() + 1;
    }
    let mut row_idx = vec![0usize; col_ptr[ng]];
    for g in 0..ng {
        let col = &mut row_idx[col_ptr[g]..col_ptr[g + 1]];
        let (diag, below) = col.split_last_mut().expect("a diagonal per column");
        below.iter_mut().zip(rows(g)).for_each(|(r, h)| *r = h);
        below.sort_unstable();
        *diag = g;
    }
    (col_ptr, row_idx)
}

/// The supernodes of the P columns of Bᵢ (`unknowns`, the first `n_p`
/// being P) and their row patterns, as [`super::half`] uses them, from the
/// vertex graph; `None` when `pattern` has no vertex blocks or `unknowns`
/// does not keep them whole (the caller analyses the scalar pattern then).
pub(super) fn p_nodes_of_groups(
    pattern: &Pattern,
    unknowns: &[usize],
    n_p: usize,
) -> Result<Option<PNodes>, FemError> {
    analyse(pattern, unknowns, n_p, true)
}

/// [`p_nodes_of_groups`], with faer's relaxation scaled to vertices or
/// (`relaxed` false) none.
fn analyse(
    pattern: &Pattern,
    unknowns: &[usize],
    n_p: usize,
    relaxed: bool,
) -> Result<Option<PNodes>, FemError> {
    let Some(blocks) = pattern.vertex_blocks() else {
        return Ok(None);
    };
    let Some(groups) = local_groups(blocks, unknowns, n_p) else {
        return Ok(None);
    };
    let ng = groups.block.len();
    let (col_ptr, row_idx) = group_pattern(blocks, &groups);
    // unknowns per vertex, rounded: the relaxation's widths in vertices,
    // rounded up (on hand.mesh, d = 3, the split factorisation took
    // 0.035–0.039 s against 0.042–0.046 s with the widths rounded down;
    // for d = 2 the two agree)
    let d = ((unknowns.len() as f64 / ng.max(1) as f64).round() as usize).max(1);
    // faer's default thresholds (widths in columns)
    let relax: Vec<(usize, f64)> = SymbolicSupernodalParams::default()
        .relax
        .unwrap_or_default()
        .iter()
        .map(|&(w, z)| (if w == usize::MAX { w } else { w.div_ceil(d) }, z))
        .collect();
    let a = SymbolicSparseColMatRef::new_checked(ng, ng, &col_ptr, None, &row_idx);
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        supernodal_params: SymbolicSupernodalParams {
            relax: relaxed.then_some(&relax[..]),
        },
        ..Default::default()
    };
    let symbolic =
        factorize_symbolic_cholesky(a, faer::Side::Upper, SymmetricOrdering::Identity, params)
            .map_err(|e| FemError::Symbolic(format!("{e:?}")))?;
    let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
        unreachable!("the halves are analysed with FORCE_SUPERNODAL")
    };
    Ok(Some(p_nodes_expanded(sn, n_p, |g| groups.start[g])))
}

#[cfg(test)]
mod tests {
    use super::super::half::scalar_p_nodes;
    use super::*;
    use crate::linear::ordering::tests::{grid, grid_with};

    /// A renumbering that keeps every vertex's unknowns together (vertices
    /// in a scrambled order), and the unknowns of all but the last 5
    /// vertices (P; S is the rest).
    fn scrambled_vertices(p: &Pattern, seed: usize) -> (Vec<usize>, usize) {
        let b = p.vertex_blocks().unwrap();
        let nb = b.start.len() - 1;
        let mut order: Vec<usize> = (0..nb).collect();
        for i in 0..nb {
            order.swap(i, (i * 7919 + seed) % nb);
        }
        let size = |v: usize| b.start[v + 1] - b.start[v];
        let n_s: usize = order[nb - 5..].iter().map(|&v| size(v)).sum();
        let unknowns: Vec<usize> = order
            .iter()
            .flat_map(|&v| b.start[v]..b.start[v + 1])
            .collect();
        let n_p = unknowns.len() - n_s;
        (unknowns, n_p)
    }

    /// The triangulated nx×nx grid's pattern with `dim` unknowns per vertex,
    /// every fourth DOF fixed: vertices of `dim` − 1 and `dim` unknowns.
    fn masked_grid(nx: usize, dim: usize) -> Pattern {
        let nv = (nx + 1) * (nx + 1);
        let mask: Vec<bool> = (0..nv * dim).map(|d| d % 4 == 1).collect();
        grid_with(
            nx,
            nx,
            crate::dofs::DofMap::from_dof_mask(nv, dim, &mask).unwrap(),
        )
    }

    /// Unrelaxed, the expanded supernodes of the vertex graph are exactly
    /// those of faer's analysis of the scalar pattern, with vertices of one
    /// size or of several (fixed components).
    #[test]
    fn expanded_vertex_supernodes_are_the_scalar_ones() {
        let patterns = [
            grid(9, 9, 2),
            grid(6, 6, 3),
            grid(12, 12, 1),
            masked_grid(9, 2),
            masked_grid(7, 3),
        ];
        for (case, p) in patterns.iter().enumerate() {
            let (unknowns, n_p) = scrambled_vertices(p, 3);
            let (nodes, rows) = analyse(p, &unknowns, n_p, false).unwrap().unwrap();
            let (want_nodes, want_rows) = scalar_p_nodes(p, &unknowns, n_p, None);
            assert_eq!(nodes.len(), want_nodes.len(), "case {case}");
            for (a, b) in nodes.iter().zip(&want_nodes) {
                assert_eq!((a.start, a.end, a.val), (b.start, b.end, b.val));
                assert_eq!(rows[a.rows.clone()], want_rows[b.rows.clone()]);
            }
        }
    }

    /// Unknowns that split a vertex, or a P that ends inside one, fall back
    /// to the scalar analysis.
    #[test]
    fn split_vertices_fall_back() {
        let p = grid(4, 4, 2);
        let mut unknowns: Vec<usize> = (0..p.n()).collect();
        assert!(p_nodes_of_groups(&p, &unknowns, 10).unwrap().is_some());
        assert!(p_nodes_of_groups(&p, &unknowns, 11).unwrap().is_none());
        unknowns.swap(0, 1);
        assert!(p_nodes_of_groups(&p, &unknowns, 10).unwrap().is_none());
    }
}
