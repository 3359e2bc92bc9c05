//! Geometric nested dissection: a fill-reducing ordering of a mesh graph from
//! its vertex positions (George 1973; Gilbert, Miller and Teng 1998 for the
//! geometric separators).
//!
//! The vertices of a subproblem are split at the median of the longest axis
//! of their bounding box. Of the two one-sided vertex separators — the
//! vertices of either half with a neighbour in the other — the smaller is
//! numbered last, both remaining parts are dissected recursively (in
//! parallel above [`PARALLEL_MIN`] vertices), and a part of at most
//! [`LEAF`] vertices keeps the order it comes in. Removing a separator
//! disconnects the halves (an edge between them has an end in each one-sided
//! separator), so the factor of a matrix on this graph has no fill between
//! them. For a planar or surface mesh of bounded aspect ratio the separators
//! have O(√n) vertices, giving O(n log n) fill and O(n^{3/2}) flops; in 3D,
//! O(n^{2/3}) separators and O(n²) flops — the same orders as METIS, at the
//! cost of a few linear passes per level (no coarsening, no refinement).
//!
//! Used by the Tutte solve (its interior Laplacian) and by the Newton
//! solver's Cholesky (`ecc-fem`, the `geometric` ordering of the vertex
//! graph).

use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// Vertices per leaf of the dissection (ordered as they come).
pub const LEAF: usize = 8;

/// Subproblems at least this large dissect their two parts on two threads.
pub const PARALLEL_MIN: usize = 16_384;

/// The graph as compressed adjacency lists: the neighbours of `v` are
/// `idx[ptr[v]..ptr[v + 1]]`; a symmetric pattern (both directions stored).
/// Self loops are allowed and ignored.
#[derive(Clone, Copy)]
pub struct Graph<'a> {
    /// Row pointers, `len() = n + 1`.
    pub ptr: &'a [usize],
    /// Neighbours.
    pub idx: &'a [usize],
}

/// Shared marks: `mark[v] == id` while the subproblem `id` is labelling one
/// of its halves. Every subproblem draws a fresh id, so concurrent siblings
/// never read each other's labels as their own.
struct Marks {
    mark: Vec<AtomicUsize>,
    next_id: AtomicUsize,
}

/// The nested-dissection ordering of `graph` with vertex positions `pos`
/// (`pos.len()` vertices): `perm[new] = old`. Panics if `graph` is shorter
/// than `pos` or names a vertex out of range.
pub fn nested_dissection(graph: Graph<'_>, pos: &[[f64; 3]]) -> Vec<usize> {
    let n = pos.len();
    assert!(
        graph.ptr.len() > n,
        "graph has fewer vertices than positions"
    );
    let marks = Marks {
        mark: (0..n).map(|_| AtomicUsize::new(0)).collect(),
        next_id: AtomicUsize::new(1),
    };
    let mut perm: Vec<usize> = (0..n).collect();
    dissect(graph, pos, &marks, &mut perm);
    perm
}

/// Reorder `verts` in place: first part, second part, separator.
fn dissect(graph: Graph<'_>, pos: &[[f64; 3]], marks: &Marks, verts: &mut [usize]) {
    if verts.len() <= LEAF {
        return;
    }
    let mid = split_at_median(pos, verts);
    let (a, b) = verts.split_at_mut(mid);
    // one-sided separators: the vertices of a half with a neighbour in the other
    let sep_b = move_touching_last(graph, marks, a, b);
    let sep_a = move_touching_last(graph, marks, b, a);
    let (na, nb) = (a.len(), b.len());
    // now: a \ S_a | S_a | b \ S_b | S_b
    let (first, rest) = if sep_b <= sep_a {
        // a | b \ S_b | S_b
        (na, nb - sep_b)
    } else {
        // a \ S_a | b | S_a (the order within b does not matter)
        let first = na - sep_a;
        verts[first..].rotate_left(sep_a);
        (first, nb)
    };
    let (p1, tail) = verts.split_at_mut(first);
    let (p2, _separator) = tail.split_at_mut(rest);
    if p1.len() + p2.len() >= PARALLEL_MIN {
        rayon::join(
            || dissect(graph, pos, marks, p1),
            || dissect(graph, pos, marks, p2),
        );
    } else {
        dissect(graph, pos, marks, p1);
        dissect(graph, pos, marks, p2);
    }
}

/// The vertex graph of a triangle mesh over `n` vertices (an edge per
/// triangle side, both directions, neighbours sorted, no repeats, no self
/// loops) as [`Graph`] storage `(ptr, idx)`; `None` when a triangle names
/// a vertex ≥ `n`.
pub fn triangle_graph(n: usize, triangles: &[[usize; 3]]) -> Option<(Vec<usize>, Vec<usize>)> {
    let mut ptr = vec![0usize; n + 1];
    for t in triangles {
        for &v in t {
            *ptr.get_mut(v + 1)? += 2;
        }
    }
    for v in 0..n {
        ptr[v + 1] += ptr[v];
    }
    let mut next = ptr[..n].to_vec();
    let mut idx = vec![0usize; ptr[n]];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            idx[next[a]] = b;
            next[a] += 1;
            idx[next[b]] = a;
            next[b] += 1;
        }
    }
    // each list sorted and compacted in place (the write never passes the read)
    let mut out = Vec::with_capacity(n + 1);
    out.push(0);
    let mut w = 0;
    for v in 0..n {
        let (s, e) = (ptr[v], ptr[v + 1]);
        idx[s..e].sort_unstable();
        let mut last = usize::MAX;
        for r in s..e {
            let u = idx[r];
            if u != last && u != v {
                idx[w] = u;
                w += 1;
                last = u;
            }
        }
        out.push(w);
    }
    idx.truncate(w);
    Some((out, idx))
}

/// [`nested_dissection`] of a triangle mesh's vertex graph
/// ([`triangle_graph`]) at `positions`: the one order the Tutte start
/// ([`crate::tutte_embedding_in_order`]) and the Newton solver's
/// `geometric` ordering can share instead of each dissecting its own graph
/// of the same vertices. `None` when a triangle names a vertex without a
/// position.
pub fn mesh_dissection(positions: &[[f64; 3]], triangles: &[[usize; 3]]) -> Option<Vec<usize>> {
    let (ptr, idx) = triangle_graph(positions.len(), triangles)?;
    Some(nested_dissection(
        Graph {
            ptr: &ptr,
            idx: &idx,
        },
        positions,
    ))
}

/// The inverse of the permutation `perm` (`inv[perm[new]] = new`), as faer's
/// `PermRef` wants it beside `perm`.
pub fn inverse_permutation(perm: &[usize]) -> Vec<usize> {
    let mut inv = vec![0usize; perm.len()];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    inv
}

/// Partition `verts` at the median of the longest axis of their bounding
/// box; returns the size of the lower half. Vertices on the median's
/// coordinate all go to one side when that leaves each side at least a
/// quarter (a grid row is not cut in two: its separator stays one grid
/// line).
fn split_at_median(pos: &[[f64; 3]], verts: &mut [usize]) -> usize {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &v in verts.iter() {
        for k in 0..3 {
            lo[k] = lo[k].min(pos[v][k]);
            hi[k] = hi[k].max(pos[v][k]);
        }
    }
    let axis = (0..3)
        .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
        .unwrap_or(0);
    let key = |v: usize| pos[v][axis];
    let mid = verts.len() / 2;
    verts.select_nth_unstable_by(mid, |&x, &y| key(x).total_cmp(&key(y)));
    let m = key(verts[mid]);
    // ties of the median: to the back of the lower part, the front of the upper
    let (a, b) = verts.split_at_mut(mid);
    let below = partition(a, |v| key(v) < m);
    let at = partition(b, |v| key(v) == m);
    // the tie block is verts[below..mid + at]: cut at its nearer end if
    // both sides keep a quarter (parts shrink geometrically: the recursion
    // stays O(log n) deep whatever the positions), else inside it
    let (start, end) = (below, mid + at);
    let balanced = |cut: usize| 4 * cut.min(verts.len() - cut) >= verts.len();
    let nearer = if mid - start <= end - mid {
        [start, end]
    } else {
        [end, start]
    };
    nearer.into_iter().find(|&c| balanced(c)).unwrap_or(mid)
}

/// Move the entries of `v` satisfying `first` to the front (not stable);
/// returns how many.
fn partition(v: &mut [usize], first: impl Fn(usize) -> bool) -> usize {
    let mut k = 0;
    for i in 0..v.len() {
        if first(v[i]) {
            v.swap(i, k);
            k += 1;
        }
    }
    k
}

/// Move the vertices of `half` with a neighbour in `other` to the back of
/// `half` (the order within either group is not kept); returns how many
/// there are.
fn move_touching_last(
    graph: Graph<'_>,
    marks: &Marks,
    other: &[usize],
    half: &mut [usize],
) -> usize {
    let id = marks.next_id.fetch_add(1, Relaxed);
    other.iter().for_each(|&v| marks.mark[v].store(id, Relaxed));
    let touches = |v: usize| {
        graph.idx[graph.ptr[v]..graph.ptr[v + 1]]
            .iter()
            .any(|&u| marks.mark[u].load(Relaxed) == id)
    };
    half.len() - partition(half, |v| !touches(v))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangulated n×n grid graph (edges right, up and diagonal) in
    /// compressed form, and its vertex positions.
    fn grid(n: usize) -> (Vec<usize>, Vec<usize>, Vec<[f64; 3]>) {
        let id = |i: usize, j: usize| i + j * n;
        let mut adj = vec![Vec::new(); n * n];
        for j in 0..n {
            for i in 0..n {
                for (a, b) in [(i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                    if a < n && b < n {
                        adj[id(i, j)].push(id(a, b));
                        adj[id(a, b)].push(id(i, j));
                    }
                }
            }
        }
        let mut ptr = vec![0];
        let mut idx = Vec::new();
        for a in &adj {
            idx.extend(a);
            ptr.push(idx.len());
        }
        let pos = (0..n * n)
            .map(|v| [(v % n) as f64, (v / n) as f64, 0.0])
            .collect();
        (ptr, idx, pos)
    }

    /// [`nested_dissection`] of the graph `ptr`/`idx` at `pos`.
    fn dissect(ptr: &[usize], idx: &[usize], pos: &[[f64; 3]]) -> Vec<usize> {
        nested_dissection(Graph { ptr, idx }, pos)
    }

    /// Whether `perm` holds each of 0..n exactly once.
    fn is_permutation(perm: &[usize], n: usize) -> bool {
        let mut sorted = perm.to_vec();
        sorted.sort_unstable();
        sorted.len() == n && sorted.iter().enumerate().all(|(i, &v)| i == v)
    }

    #[test]
    fn inverse_permutation_inverts() {
        let perm = [2, 0, 3, 1];
        let inv = inverse_permutation(&perm);
        assert!((0..4).all(|i| perm[inv[i]] == i && inv[perm[i]] == i));
    }

    #[test]
    fn the_top_separator_of_a_grid_is_one_grid_line() {
        let n = 41;
        let (ptr, idx, pos) = grid(n);
        let perm = dissect(&ptr, &idx, &pos);
        assert!(is_permutation(&perm, n * n));
        let top: Vec<(usize, usize)> = perm[perm.len() - n..]
            .iter()
            .map(|&v| (v % n, v / n))
            .collect();
        let line =
            top.iter().all(|&(i, _)| i == top[0].0) || top.iter().all(|&(_, j)| j == top[0].1);
        assert!(line, "{top:?}");
    }

    /// Above [`PARALLEL_MIN`] the parts are dissected on two threads: the
    /// same permutation as on one.
    #[test]
    fn two_threads_give_the_same_permutation() {
        let n = 200;
        let (ptr, idx, pos) = grid(n);
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| dissect(&ptr, &idx, &pos))
        };
        let one = run(1);
        assert!(n * n >= 2 * PARALLEL_MIN);
        assert_eq!(one, run(2));
        assert!(is_permutation(&one, n * n));
    }

    /// Positions with huge tie blocks (all but a few vertices on one point)
    /// still give a permutation, with balanced cuts.
    #[test]
    fn degenerate_positions_still_dissect() {
        let n = 120;
        let (ptr, idx, mut pos) = grid(n);
        for (v, p) in pos.iter_mut().enumerate() {
            if v % 97 != 0 {
                *p = [0.0; 3];
            }
        }
        let perm = dissect(&ptr, &idx, &pos);
        assert!(is_permutation(&perm, n * n));
    }

    /// The triangle graph of the generated grid is the hand-built grid
    /// graph (each list sorted); the dissection of the mesh is that of the
    /// graph; a vertex out of range is `None`, not a panic.
    #[test]
    fn the_triangle_graph_is_the_grid_graph() {
        let n = 9;
        let mesh = crate::grid_tri(n - 1, n - 1, 1.0, 1.0);
        let (ptr, idx) = triangle_graph(mesh.positions.len(), &mesh.triangles).unwrap();
        let (want_ptr, want_idx, _) = grid(n);
        // the hand-built lists are unsorted: compare as sets per vertex
        assert_eq!(ptr, want_ptr);
        for v in 0..n * n {
            let mut want = want_idx[want_ptr[v]..want_ptr[v + 1]].to_vec();
            want.sort_unstable();
            assert_eq!(idx[ptr[v]..ptr[v + 1]], want[..], "vertex {v}");
        }
        let perm = mesh_dissection(&mesh.positions, &mesh.triangles).unwrap();
        assert_eq!(perm, dissect(&ptr, &idx, &mesh.positions));
        assert!(triangle_graph(3, &[[0, 1, 3]]).is_none());
        assert!(mesh_dissection(&mesh.positions[..4], &mesh.triangles).is_none());
    }
}
