//! A locality-preserving vertex order for numbering the unknowns.
//!
//! Mesh files often list vertices in an order unrelated to their position
//! (scans, remeshers, seam cuts). The assembler writes every element's
//! local Hessian into the columns of its vertices' unknowns; with a random
//! numbering those writes land on unrelated cache lines. Numbering unknowns
//! in breadth-first order over the stencil graph (the Cuthill–McKee idea,
//! started from a pseudo-peripheral vertex of each connected component)
//! keeps the vertices of an element close in memory. But the positions x
//! stay in the caller's vertex order, so a renumbering also makes the
//! unknown order differ from the vertex order the term reads x in: it only
//! pays when the given order is poor. [`choose_order`] therefore keeps the
//! identity unless the breadth-first order at least halves the mean index
//! span of a stencil (armadillo_cut_low.obj: 12 976 → 251, renumbered; a
//! row-major grid: 179 → 120, kept). The fill-reducing ordering of the
//! Cholesky factor is computed separately (AMD), so none of this affects
//! the factor.

use crate::pattern::StencilSet;

/// The vertex order for numbering unknowns: breadth-first if it at least
/// halves the mean stencil index span, else the identity (`None`).
pub(crate) fn choose_order(n_vertices: usize, sets: &[StencilSet<'_>]) -> Option<Vec<usize>> {
    let bfs = locality_order(n_vertices, sets);
    let mut rank = vec![0usize; n_vertices];
    for (r, &v) in bfs.iter().enumerate() {
        rank[v] = r;
    }
    let identity = mean_span(sets, |v| v);
    let reordered = mean_span(sets, |v| rank[v]);
    (reordered < 0.5 * identity).then_some(bfs)
}

/// Mean over all stencils of (max − min) of `rank` over the stencil's vertices.
fn mean_span(sets: &[StencilSet<'_>], rank: impl Fn(usize) -> usize) -> f64 {
    let (mut total, mut count) = (0.0, 0usize);
    for set in sets {
        for st in set.stencils.chunks_exact(set.arity) {
            let (lo, hi) = st.iter().fold((usize::MAX, 0), |(lo, hi), &v| {
                (lo.min(rank(v)), hi.max(rank(v)))
            });
            total += (hi - lo) as f64;
            count += 1;
        }
    }
    if count == 0 {
        0.0
    } else {
        total / count as f64
    }
}

/// Vertices in breadth-first order over the graph "two vertices share a
/// stencil"; vertices in no stencil come last, in index order.
pub(crate) fn locality_order(n_vertices: usize, sets: &[StencilSet<'_>]) -> Vec<usize> {
    // vertex → neighbours (CSR, duplicates harmless)
    let mut ptr = vec![0usize; n_vertices + 1];
    for set in sets {
        for st in set.stencils.chunks_exact(set.arity) {
            for &v in st {
                ptr[v + 1] += set.arity - 1;
            }
        }
    }
    for v in 0..n_vertices {
        ptr[v + 1] += ptr[v];
    }
    let mut fill = ptr.clone();
    let mut adj = vec![0u32; ptr[n_vertices]];
    for set in sets {
        for st in set.stencils.chunks_exact(set.arity) {
            for &v in st {
                for &u in st {
                    if u != v {
                        adj[fill[v]] = u as u32;
                        fill[v] += 1;
                    }
                }
            }
        }
    }
    drop(fill);

    let mut order = Vec::with_capacity(n_vertices);
    let mut seen = vec![false; n_vertices];
    let mut scratch_seen = vec![false; n_vertices];
    let mut queue = Vec::new();
    for root in 0..n_vertices {
        if seen[root] || ptr[root] == ptr[root + 1] {
            continue;
        }
        // pseudo-peripheral start: the last vertex reached by a BFS from `root`
        let start = *bfs(root, &ptr, &adj, &mut scratch_seen, &mut queue)
            .last()
            .unwrap_or(&root);
        for &v in &queue {
            scratch_seen[v] = false;
        }
        let comp = bfs(start, &ptr, &adj, &mut seen, &mut queue);
        order.extend_from_slice(comp);
    }
    order.extend((0..n_vertices).filter(|&v| ptr[v] == ptr[v + 1]));
    order
}

/// Breadth-first search from `s` over unvisited vertices, marking `seen`;
/// returns the visit order (stored in `queue`).
fn bfs<'q>(
    s: usize,
    ptr: &[usize],
    adj: &[u32],
    seen: &mut [bool],
    queue: &'q mut Vec<usize>,
) -> &'q [usize] {
    queue.clear();
    queue.push(s);
    seen[s] = true;
    let mut head = 0;
    while head < queue.len() {
        let v = queue[head];
        head += 1;
        for &u in &adj[ptr[v]..ptr[v + 1]] {
            let u = u as usize;
            if !seen[u] {
                seen[u] = true;
                queue.push(u);
            }
        }
    }
    queue
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scrambled_numbering_is_replaced_good_numbering_kept() {
        // a path 0-1-2-…-99 is already local; the same path scrambled is not
        let n = 100;
        let good: Vec<usize> = (0..n - 1).flat_map(|i| [i, i + 1]).collect();
        let sets = [StencilSet {
            name: "e",
            arity: 2,
            stencils: &good,
        }];
        assert!(choose_order(n, &sets).is_none());
        let scramble = |v: usize| (v * 37) % n;
        let bad: Vec<usize> = good.iter().map(|&v| scramble(v)).collect();
        let sets = [StencilSet {
            name: "e",
            arity: 2,
            stencils: &bad,
        }];
        let o = choose_order(n, &sets).expect("scrambled path is renumbered");
        let mut rank = vec![0; n];
        for (r, &v) in o.iter().enumerate() {
            rank[v] = r;
        }
        assert!(bad.chunks(2).all(|e| rank[e[0]].abs_diff(rank[e[1]]) == 1));
    }

    #[test]
    fn order_is_a_permutation_grouping_components() {
        // two separate edges 0-3 and 1-2, an isolated vertex 4, and a path 5-6-7
        let edges = [0usize, 3, 2, 1, 5, 6, 6, 7];
        let sets = [StencilSet {
            name: "e",
            arity: 2,
            stencils: &edges,
        }];
        let o = locality_order(8, &sets);
        let mut sorted = o.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..8).collect::<Vec<_>>());
        let pos = |v: usize| o.iter().position(|&x| x == v).unwrap();
        assert_eq!((pos(0) as i64 - pos(3) as i64).abs(), 1);
        assert_eq!((pos(1) as i64 - pos(2) as i64).abs(), 1);
        assert_eq!(*o.last().unwrap(), 4, "isolated vertices last");
        // the path starts at an end (pseudo-peripheral)
        let p: Vec<usize> = [5, 6, 7].iter().map(|&v| pos(v)).collect();
        assert!(p[1] == p[0] + 1 && p[2] == p[1] + 1 || p[1] + 1 == p[0] && p[2] + 1 == p[1]);
    }
}
