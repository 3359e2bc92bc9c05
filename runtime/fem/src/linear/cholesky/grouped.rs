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

impl LocalGroups {
    /// The local vertex of each of `blocks`' vertex blocks, `usize::MAX`
    /// for those outside the half.
    fn local_of_blocks(&self, blocks: &VertexBlocks) -> Vec<usize> {
        let mut local = vec![usize::MAX; blocks.start.len() - 1];
        self.block
            .iter()
            .enumerate()
            .for_each(|(g, &b)| local[b] = g);
        local
    }
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
    let local = groups.local_of_blocks(blocks);
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

/// A half's unknowns as whole vertices of `pattern` ([`LocalGroups`]).
pub(super) struct Grouped<'a> {
    blocks: &'a VertexBlocks,
    groups: LocalGroups,
}

/// The half `unknowns` (the first `n_p` being P) as whole vertices, or
/// `None` when `pattern` has no vertex blocks or `unknowns` does not keep
/// them whole (the caller works on the scalar pattern then).
pub(super) fn grouped<'a>(
    pattern: &'a Pattern,
    unknowns: &[usize],
    n_p: usize,
) -> Option<Grouped<'a>> {
    let blocks = pattern.vertex_blocks()?;
    let groups = local_groups(blocks, unknowns, n_p)?;
    Some(Grouped { blocks, groups })
}

/// The supernodes of the P columns of Bᵢ (the first `n_p` of the half's
/// unknowns) and their row patterns, as [`super::half`] uses them, from
/// the vertex graph.
pub(super) fn p_nodes_of_groups(half: &Grouped<'_>, n_p: usize) -> Result<PNodes, FemError> {
    analyse(half, n_p, true)
}

/// [`p_nodes_of_groups`], with faer's relaxation scaled to vertices or
/// (`relaxed` false) none.
fn analyse(half: &Grouped<'_>, n_p: usize, relaxed: bool) -> Result<PNodes, FemError> {
    let Grouped { blocks, groups } = half;
    let unknowns_len = groups.start[groups.block.len()];
    let ng = groups.block.len();
    let (col_ptr, row_idx) = group_pattern(blocks, groups);
    // unknowns per vertex, rounded: the relaxation's widths in vertices,
    // rounded up (on hand.mesh, d = 3, the split factorisation took
    // 0.035–0.039 s against 0.042–0.046 s with the widths rounded down;
    // for d = 2 the two agree)
    let d = ((unknowns_len as f64 / ng.max(1) as f64).round() as usize).max(1);
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
    Ok(p_nodes_expanded(sn, n_p, |g| groups.start[g]))
}

/// [`super::split::lower_p_block`] read from the vertex graph: the lower
/// triangle of the P columns of Bᵢ (local CSC pointers, local rows, slots
/// in A), one vertex pair at a time instead of one entry of A at a time.
///
/// A vertex's unknowns are consecutive in A, coupled to each other and to
/// the same unknowns, so every column of a vertex q holds the rows of a
/// neighbour p < q as one run at the same offset from the column's start
/// (one search per pair of vertices), and q's own rows end the column (the
/// diagonal last). Column l of the result lists its own vertex's rows from
/// l on, then the later local vertices in local order, each vertex's rows
/// ascending: sorted, as the entry-wise construction gives them. The block
/// graph lists both directions, so no scatter into other columns is
/// needed. On the 1M-triangle disk this replaced ≈ 0.2 s a half of the
/// entry-wise construction's counting sort (`lower_p_block` was 4 % of
/// `prepare`'s CPU, 7 % with its page faults, stop 32).
pub(super) fn lower_p_block(
    pattern: &Pattern,
    half: &Grouped<'_>,
    n_p: usize,
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let Grouped { blocks, groups } = half;
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let local = groups.local_of_blocks(blocks);
    let n_pg = groups.start.partition_point(|&s| s < n_p);
    let size = |b: usize| blocks.start[b + 1] - blocks.start[b];
    let neighbours = |b: usize| &blocks.adj[blocks.adj_ptr[b]..blocks.adj_ptr[b + 1]];
    // reserved, not touched: every neighbour counted (the earlier ones
    // too) at the largest size, without reading the neighbours
    let widest = (0..blocks.start.len() - 1).map(size).max().unwrap_or(0);
    let bound: usize = groups.block[..n_pg]
        .iter()
        .map(|&b| size(b) * (size(b) + widest * neighbours(b).len()))
        .sum();
    let mut a_ptr = Vec::with_capacity(n_p + 1);
    a_ptr.push(0);
    let (mut rows, mut slots) = (Vec::with_capacity(bound), Vec::with_capacity(bound));
    // (local vertex, its block, offset of the pair's run in its column)
    let mut later: Vec<(usize, usize, usize)> = Vec::new();
    let offset = |col: usize, row: usize| {
        let column = &ri[cp[col]..cp[col + 1]];
        column.partition_point(|&r| r < row)
    };
    for (g, &b) in groups.block[..n_pg].iter().enumerate() {
        let first = blocks.start[b];
        later.clear();
        // b's columns hold the unknowns of its neighbours before it, in
        // order: their runs' offsets are the sizes summed so far
        let mut before = 0;
        for &c in neighbours(b) {
            let (h, other) = (local[c], blocks.start[c]);
            if h != usize::MAX && h > g {
                // the run of the smaller vertex in the larger one's columns
                let at = if other < first {
                    before
                } else {
                    offset(other, first)
                };
                later.push((h, c, at));
            }
            if other < first {
                before += blocks.start[c + 1] - other;
            }
        }
        later.sort_unstable();
        let own = groups.start[g];
        for k in 0..size(b) {
            let col = first + k;
            for k2 in k..size(b) {
                rows.push(own + k2);
                // row first + k of column first + k2, its own rows last
                slots.push(cp[first + k2 + 1] - 1 - (k2 - k));
            }
            for &(h, c, at) in &later {
                let (other, local_start) = (blocks.start[c], groups.start[h]);
                for i in 0..size(c) {
                    rows.push(local_start + i);
                    slots.push(if other < first {
                        cp[col] + at + i
                    } else {
                        cp[other + i] + at + k
                    });
                }
            }
            a_ptr.push(rows.len());
        }
    }
    (a_ptr, rows, slots)
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

    /// 2D, 3D and scalar grids, and grids with vertices of one size and of
    /// another ([`masked_grid`]).
    fn test_patterns() -> [Pattern; 5] {
        [
            grid(9, 9, 2),
            grid(6, 6, 3),
            grid(12, 12, 1),
            masked_grid(9, 2),
            masked_grid(7, 3),
        ]
    }

    /// Unrelaxed, the expanded supernodes of the vertex graph are exactly
    /// those of faer's analysis of the scalar pattern, with vertices of one
    /// size or of several (fixed components).
    #[test]
    fn expanded_vertex_supernodes_are_the_scalar_ones() {
        let patterns = test_patterns();
        for (case, p) in patterns.iter().enumerate() {
            let (unknowns, n_p) = scrambled_vertices(p, 3);
            let half = grouped(p, &unknowns, n_p).unwrap();
            let (nodes, rows) = analyse(&half, n_p, false).unwrap();
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
        assert!(grouped(&p, &unknowns, 10).is_some());
        assert!(grouped(&p, &unknowns, 11).is_none());
        unknowns.swap(0, 1);
        assert!(grouped(&p, &unknowns, 10).is_none());
    }

    /// The lower P block read from the vertex graph is the entry-wise one
    /// (pointers, rows and slots), for vertices of one size or several, P
    /// and S of several sizes, and vertices in scrambled orders.
    #[test]
    fn vertex_lower_block_is_the_entry_wise_one() {
        let patterns = test_patterns();
        for (case, p) in patterns.iter().enumerate() {
            for seed in [1, 3, 11] {
                let (unknowns, n_p) = scrambled_vertices(p, seed);
                // P also of a third of the vertices (a larger S)
                let b = p.vertex_blocks().unwrap();
                let mut third = 0;
                while third < unknowns.len() / 3 {
                    let u = unknowns[third];
                    let v = b.start.partition_point(|&s| s <= u) - 1;
                    third += b.start[v + 1] - b.start[v];
                }
                for n_p in [n_p, third] {
                    let half = grouped(p, &unknowns, n_p).unwrap();
                    let got = lower_p_block(p, &half, n_p);
                    let want = super::super::split::lower_p_block(p, &unknowns, n_p);
                    assert_eq!(got, want, "case {case} seed {seed} n_p {n_p}");
                }
            }
        }
    }
}
