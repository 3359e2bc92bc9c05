//! The sparsity pattern of the reduced Hessian and the stencil→slot maps.
//!
//! The reduced Hessian H (unknowns × unknowns) is stored as the **upper
//! triangle in compressed sparse columns** (rows sorted, the diagonal is the
//! last entry of each column), exactly what faer's sparse Cholesky reads. An
//! entry (i, j), i ≤ j, exists iff the vertices owning unknowns i and j share
//! a stencil of some term; the diagonal always exists.
//!
//! For every stencil the local Hessian entries (a, b), a ≤ b in local DOF
//! order (packed row-major upper: `(0,0), (0,1), …, (0,k−1), (1,1), …`), map
//! to one global *slot* (an index into the value array), or to `NO_SLOT` when
//! either DOF is fixed. Each Newton iteration only refills values through
//! these maps; nothing is rebuilt.

use rayon::prelude::*;

use crate::colour::{Colouring, colour_stencils};
use crate::dofs::DofMap;
use crate::error::FemError;
use crate::term::MAX_STENCIL_DOFS;

/// Marks a local entry that touches a fixed DOF.
pub(crate) const NO_SLOT: u32 = u32::MAX;

/// Upper-triangular CSC pattern of the reduced Hessian.
#[derive(Clone, Debug)]
pub struct Pattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Unknowns whose vertex is in no stencil (their row/column is empty).
    isolated: Vec<usize>,
    /// The vertex blocks of a built pattern ([`Pattern::vertex_blocks`]).
    blocks: Option<VertexBlocks>,
    /// [`Pattern::id`].
    id: u64,
}

/// A fresh [`Pattern::id`] (never 0).
fn next_id() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// The unknowns of each vertex (consecutive, all coupled to each other and
/// to the same unknowns) and the graph between these blocks: what the
/// fill-reducing orderings work on, known from the assembly instead of
/// rediscovered from the pattern.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VertexBlocks {
    /// `start[b]..start[b + 1]` are the unknowns of block `b`.
    pub start: Vec<usize>,
    /// CSR row pointers of the block graph.
    pub adj_ptr: Vec<usize>,
    /// CSR neighbours of the block graph (sorted per block, no self loops).
    pub adj: Vec<usize>,
}

impl Pattern {
    /// Matrix dimension (number of unknowns).
    pub fn n(&self) -> usize {
        self.n
    }

    /// A number given to each constructed pattern, shared by its clones
    /// and never by another pattern: equal ids mean the same structure
    /// (patterns never change once built), so a symbolic analysis can be
    /// matched to its pattern without keeping a copy of it (120 MB on the
    /// 1M-triangle disk). Equal structures built apart get different ids.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Number of stored entries (upper triangle incl. diagonal).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Column pointers (length n + 1).
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row indices, sorted within each column.
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// Slot of the diagonal entry of column `j`.
    #[inline]
    pub fn diag_slot(&self, j: usize) -> usize {
        self.col_ptr[j + 1] - 1
    }

    /// Unknowns that no stencil touches.
    pub fn isolated(&self) -> &[usize] {
        &self.isolated
    }

    /// The vertex blocks and their graph, for a pattern built from stencils
    /// (`None` for [`Pattern::from_upper_csc`]).
    pub fn vertex_blocks(&self) -> Option<&VertexBlocks> {
        self.blocks.as_ref()
    }

    /// A pattern from a saved upper-triangular CSC structure (for tools
    /// that time a stored matrix, e.g. benches/cholmod): `col_ptr` of length
    /// n + 1 from 0, rows strictly increasing in each column, all ≤ the
    /// column, and the diagonal present (so last). Unknowns whose row and
    /// column hold only the diagonal count as isolated (structurally: a built
    /// pattern also calls isolated the coupled unknowns of an untouched vertex).
    pub fn from_upper_csc(
        n: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
    ) -> Result<Self, FemError> {
        let bad = |m: String| Err(FemError::Symbolic(format!("bad upper CSC pattern: {m}")));
        if col_ptr.len() != n + 1 || col_ptr[0] != 0 || col_ptr[n] != row_idx.len() {
            return bad(format!("{} column pointers for n = {n}", col_ptr.len()));
        }
        let mut coupled = vec![false; n];
        for j in 0..n {
            let (lo, hi) = (col_ptr[j], col_ptr[j + 1]);
            if lo >= hi || hi > row_idx.len() || row_idx[hi - 1] != j {
                return bad(format!("column {j} has no diagonal last"));
            }
            let rows = &row_idx[lo..hi];
            if rows.windows(2).any(|w| w[0] >= w[1]) {
                return bad(format!("rows of column {j} not strictly increasing"));
            }
            for &i in &rows[..rows.len() - 1] {
                coupled[i] = true;
                coupled[j] = true;
            }
        }
        let isolated = (0..n).filter(|&j| !coupled[j]).collect();
        Ok(Pattern {
            n,
            col_ptr,
            row_idx,
            isolated,
            blocks: None,
            id: next_id(),
        })
    }

    /// The slot of entry (i, j), i ≤ j, if it is in the pattern.
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        let lo = self.col_ptr[j];
        let rows = &self.row_idx[lo..self.col_ptr[j + 1]];
        rows.binary_search(&i).ok().map(|p| lo + p)
    }

    /// y = H x for the symmetric matrix whose upper triangle is `values`
    /// (sequential; used for small checks and the model decrease).
    pub fn sym_matvec(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for j in 0..self.n {
            let (lo, hi) = (self.col_ptr[j], self.col_ptr[j + 1]);
            for (&i, &v) in self.row_idx[lo..hi].iter().zip(&values[lo..hi]) {
                y[i] += v * x[j];
                if i != j {
                    y[j] += v * x[i];
                }
            }
        }
    }

    /// xᵀ H x for the symmetric matrix whose upper triangle is `values`
    /// (parallel over columns, deterministic chunked sum).
    pub fn quadratic_form(&self, values: &[f64], x: &[f64], partials: &mut Vec<f64>) -> f64 {
        crate::parallel::sum_indexed(self.n, partials, |j| {
            let mut s = 0.0;
            let (lo, hi) = (self.col_ptr[j], self.col_ptr[j + 1]);
            for (&i, &v) in self.row_idx[lo..hi].iter().zip(&values[lo..hi]) {
                let w = if i == j { 1.0 } else { 2.0 };
                s += w * v * x[i];
            }
            s * x[j]
        })
    }
}

/// Per-term assembly plan: colouring, and per-stencil unknowns and slots
/// stored in *processing order* (position p ↔ stencil `colouring.order[p]`).
#[derive(Clone, Debug)]
pub(crate) struct TermPlan {
    /// Local DOFs per stencil, k = arity·D.
    pub k: usize,
    /// Packed upper local entries per stencil, k(k+1)/2.
    pub n_local: usize,
    /// `positions × k` unknowns of the local DOFs (`u32::MAX` = fixed).
    pub unknowns: Vec<u32>,
    /// `positions × n_local` slots (or `NO_SLOT`).
    pub slots: Vec<u32>,
    pub colouring: Colouring,
}

/// Stencil lists of all terms: (name, arity, flat vertex list).
pub(crate) struct StencilSet<'a> {
    pub name: &'a str,
    pub arity: usize,
    pub stencils: &'a [usize],
}

/// Check one term's stencils (arity, range, repeats, size).
pub(crate) fn validate(
    set: &StencilSet<'_>,
    n_vertices: usize,
    dim: usize,
) -> Result<(), FemError> {
    let term = || set.name.to_string();
    if set.arity == 0 {
        return Err(FemError::ZeroArity { term: term() });
    }
    if !set.stencils.len().is_multiple_of(set.arity) {
        return Err(FemError::BadStencilList {
            term: term(),
            len: set.stencils.len(),
            arity: set.arity,
        });
    }
    let dofs = set.arity * dim;
    if dofs > crate::term::MAX_STENCIL_DOFS {
        return Err(FemError::StencilTooLarge {
            term: term(),
            dofs,
            max: crate::term::MAX_STENCIL_DOFS,
        });
    }
    for (s, st) in set.stencils.chunks_exact(set.arity).enumerate() {
        for (a, &v) in st.iter().enumerate() {
            if v >= n_vertices {
                return Err(FemError::VertexOutOfRange {
                    term: term(),
                    stencil: s,
                    vertex: v,
                    n_vertices,
                });
            }
            if st[..a].contains(&v) {
                return Err(FemError::RepeatedVertex {
                    term: term(),
                    stencil: s,
                    vertex: v,
                });
            }
        }
    }
    Ok(())
}

/// The first unknown of vertex `v` (`u32::MAX` if all its DOFs are fixed).
fn first_unknown(table: &[u32], dim: usize, v: usize) -> u32 {
    (0..dim)
        .map(|c| table[v * dim + c])
        .min()
        .unwrap_or(u32::MAX)
}

/// Vertex adjacency in upper CSC form indexed by first unknown.
struct VertexAdjacency<'a> {
    dofs: &'a DofMap,
    vptr: &'a [usize],
    vrow: &'a [u32],
}

impl VertexAdjacency<'_> {
    /// Emit the rows (unknowns ≤ j of adjacent vertices) of column j, ascending.
    fn column_rows(&self, j: usize, mut emit: impl FnMut(u32)) {
        let dim = self.dofs.dim();
        let table = self.dofs.unknown_table();
        let f = first_unknown(table, dim, self.dofs.dof(j) / dim) as usize;
        for &q in &self.vrow[self.vptr[f]..self.vptr[f + 1]] {
            let u = self.dofs.dof(q as usize) / dim;
            for c in 0..dim {
                let ui = table[u * dim + c];
                if ui != u32::MAX && (ui as usize) <= j {
                    emit(ui);
                }
            }
        }
    }
}

/// Build the pattern and the per-term plans. The DOF map may number its
/// unknowns in any vertex order (vertex by vertex, components ascending).
pub(crate) fn build(
    sets: &[StencilSet<'_>],
    dofs: &DofMap,
) -> Result<(Pattern, Vec<TermPlan>), FemError> {
    let nv = dofs.n_vertices();
    let dim = dofs.dim();
    for set in sets {
        validate(set, nv, dim)?;
    }
    let active: Vec<bool> = (0..nv).map(|v| dofs.vertex_has_free(v)).collect();
    let (vptr, vrow, touched) = vertex_csc(sets, dofs, &active);
    let adj = VertexAdjacency {
        dofs,
        vptr: &vptr,
        vrow: &vrow,
    };
    let mut pattern = dof_pattern(&adj, &touched)?;
    pattern.blocks = Some(vertex_blocks(&adj));
    let plans = sets
        .iter()
        .map(|set| term_plan(set, dofs, &active, &pattern))
        .collect();
    Ok((pattern, plans))
}

/// The vertex-level upper CSC over the `n` unknowns of `dofs`, indexed by
/// first unknown: column f(c) lists, ascending and once each, the first
/// unknowns f(r) ≤ f(c) of the vertices r sharing a stencil with c, and
/// f(c) itself for every active c (its diagonal, last); plus which vertices
/// some stencil touches.
///
/// Unknowns are numbered vertex by vertex (in some vertex order), so a
/// vertex with a free DOF is identified by its first unknown f(v), and
/// f orders vertices exactly as their unknowns are ordered. Built by a
/// counting sort of the stencils' vertex pairs by column (two passes over
/// them), then each short column sorted and deduplicated in place: linear
/// in the pairs, where a global sort of 3.5M pair keys took ≈ 0.1 s of
/// the 1M-triangle disk's setup.
fn vertex_csc(
    sets: &[StencilSet<'_>],
    dofs: &DofMap,
    active: &[bool],
) -> (Vec<usize>, Vec<u32>, Vec<bool>) {
    let (nv, n, dim) = (dofs.n_vertices(), dofs.n_unknowns(), dofs.dim());
    let table = dofs.unknown_table();
    let first = |v: usize| first_unknown(table, dim, v);
    let mut start = vec![0usize; n + 1];
    vertex_pairs_of(sets, active, first, |_, c| start[c as usize + 1] += 1);
    for q in 0..n {
        start[q + 1] += start[q];
    }
    let mut next = start.clone();
    let mut rows = vec![0u32; start[n]];
    vertex_pairs_of(sets, active, first, |r, c| {
        rows[next[c as usize]] = r;
        next[c as usize] += 1;
    });
    drop(next);
    // sort and deduplicate each column, compacting the rows in place
    let mut vptr = vec![0usize; n + 1];
    let mut len = 0;
    for c in 0..n {
        rows[start[c]..start[c + 1]].sort_unstable();
        let mut last = None;
        for i in start[c]..start[c + 1] {
            let r = rows[i];
            if last != Some(r) {
                last = Some(r);
                // start[c] ≥ len: the compacted prefix never overtakes the column
                rows[len] = r;
                len += 1;
            }
        }
        vptr[c + 1] = len;
    }
    rows.truncate(len);
    let mut touched = vec![false; nv];
    for set in sets {
        for &v in set.stencils {
            touched[v] = true;
        }
    }
    (vptr, rows, touched)
}

/// Every pair (f(r), f(c)), f(r) ≤ f(c), of the first unknowns of two
/// active vertices sharing a stencil (once per stencil), then (f(v), f(v))
/// for every active vertex v.
fn vertex_pairs_of(
    sets: &[StencilSet<'_>],
    active: &[bool],
    first: impl Fn(usize) -> u32,
    mut visit: impl FnMut(u32, u32),
) {
    for set in sets {
        for st in set.stencils.chunks_exact(set.arity) {
            for (a, &va) in st.iter().enumerate().filter(|&(_, &v)| active[v]) {
                for &vb in st[a + 1..].iter().filter(|&&v| active[v]) {
                    let (fa, fb) = (first(va), first(vb));
                    visit(fa.min(fb), fa.max(fb));
                }
            }
        }
    }
    for v in (0..active.len()).filter(|&v| active[v]) {
        visit(first(v), first(v));
    }
}

/// The DOF-level upper CSC over unknowns: rows of column j are the unknowns
/// ≤ j of the vertices adjacent to j's vertex, already in ascending order.
/// Unknowns of vertices no stencil touches are listed as isolated.
fn dof_pattern(adj: &VertexAdjacency<'_>, touched: &[bool]) -> Result<Pattern, FemError> {
    let dofs = adj.dofs;
    let (n, dim) = (dofs.n_unknowns(), dofs.dim());
    let mut col_ptr = vec![0usize; n + 1];
    for j in 0..n {
        let mut cnt = 0;
        adj.column_rows(j, |_| cnt += 1);
        col_ptr[j + 1] = col_ptr[j] + cnt;
    }
    let nnz = col_ptr[n];
    if nnz >= NO_SLOT as usize {
        return Err(FemError::TooLarge {
            what: "Hessian nonzero",
            count: nnz,
            max: NO_SLOT as usize - 1,
        });
    }
    let mut row_idx = vec![0usize; nnz];
    for (j, &start) in col_ptr[..n].iter().enumerate() {
        let mut p = start;
        adj.column_rows(j, |ui| {
            row_idx[p] = ui as usize;
            p += 1;
        });
    }
    let isolated: Vec<usize> = (0..n).filter(|&j| !touched[dofs.dof(j) / dim]).collect();
    Ok(Pattern {
        n,
        col_ptr,
        row_idx,
        isolated,
        blocks: None,
        id: next_id(),
    })
}

/// The [`VertexBlocks`] of the vertex adjacency: a block per vertex with a
/// free DOF, in the order of their unknowns, and the symmetric graph of the
/// upper vertex CSC.
fn vertex_blocks(adj: &VertexAdjacency<'_>) -> VertexBlocks {
    let dofs = adj.dofs;
    let (n, dim) = (dofs.n_unknowns(), dofs.dim());
    let vertex = |u: usize| dofs.dof(u) / dim;
    let mut start = Vec::new();
    // block of each vertex's first unknown
    let mut block = vec![usize::MAX; n];
    for (u, b) in block.iter_mut().enumerate() {
        if u == 0 || vertex(u) != vertex(u - 1) {
            *b = start.len();
            start.push(u);
        }
    }
    start.push(n);
    let nb = start.len() - 1;
    let rows = |b: usize| {
        let f = start[b];
        adj.vrow[adj.vptr[f]..adj.vptr[f + 1]]
            .iter()
            .map(|&q| block[q as usize])
    };
    let (adj_ptr, list) = symmetric_graph(nb, rows);
    VertexBlocks {
        start,
        adj_ptr,
        adj: list,
    }
}

/// The symmetric graph (CSR pointers and neighbours, no self loops) of an
/// upper-triangular structure over `n` nodes whose column `j` holds the
/// rows `rows(j)`, ascending and ≤ j. Columns are visited in increasing
/// order, so every list is filled sorted: node i receives its own rows
/// (< i) first, then the columns j > i that hold it, in increasing j.
pub(crate) fn symmetric_graph<I: Iterator<Item = usize>>(
    n: usize,
    rows: impl Fn(usize) -> I,
) -> (Vec<usize>, Vec<usize>) {
    let mut ptr = vec![0usize; n + 1];
    for j in 0..n {
        for i in rows(j).filter(|&i| i != j) {
            ptr[i + 1] += 1;
            ptr[j + 1] += 1;
        }
    }
    for j in 0..n {
        ptr[j + 1] += ptr[j];
    }
    let mut fill = ptr.clone();
    let mut adj = vec![0usize; ptr[n]];
    for j in 0..n {
        for i in rows(j).filter(|&i| i != j) {
            adj[fill[j]] = i;
            fill[j] += 1;
        }
        for i in rows(j).filter(|&i| i != j) {
            adj[fill[i]] = j;
            fill[i] += 1;
        }
    }
    (ptr, adj)
}

/// One term's plan: its stencil colouring, and per stencil (in processing
/// order) the unknown of each local DOF and the pattern slot of each
/// upper-triangle local pair.
fn term_plan(set: &StencilSet<'_>, dofs: &DofMap, active: &[bool], pattern: &Pattern) -> TermPlan {
    let (nv, dim) = (dofs.n_vertices(), dofs.dim());
    let table = dofs.unknown_table();
    let k = set.arity * dim;
    let n_local = k * (k + 1) / 2;
    // colours list their stencils in increasing index order, so the
    // term's own per-stencil data (vertex lists, rest shapes) is streamed
    let colouring = colour_stencils(nv, set.arity, set.stencils, active);
    // per-stencil tables stored in processing order: streamed, not gathered
    let n_st = colouring.order.len();
    let mut unknowns = vec![u32::MAX; n_st * k];
    unknowns
        .par_chunks_mut(k.max(1))
        .zip(colouring.order.par_iter())
        .for_each(|(out, &s)| {
            let st = &set.stencils[s as usize * set.arity..(s as usize + 1) * set.arity];
            for (a, u) in out.iter_mut().enumerate() {
                *u = table[st[a / dim] * dim + a % dim];
            }
        });
    let mut slots = vec![NO_SLOT; n_st * n_local];
    slots
        .par_chunks_mut(n_local.max(1))
        .zip(unknowns.par_chunks(k.max(1)))
        .for_each(|(out, unk)| stencil_slots(pattern, unk, dim, out));
    TermPlan {
        k,
        n_local,
        unknowns,
        slots,
        colouring,
    }
}

/// The pattern slot of each upper local pair (a ≤ b) of one stencil whose
/// local DOF a has the unknown `unk[a]` (`u32::MAX`: fixed), into `out`
/// ([`NO_SLOT`] where a DOF is fixed), with one binary search per pair of
/// distinct vertices instead of one per pair of DOFs (the searches miss
/// the cache: the stencils are visited colour by colour, each colour
/// sweeping the whole pattern; on the 1M-triangle disk 21 searches per
/// triangle took 0.4 s of setup on two threads).
///
/// A vertex's unknowns are consecutive, f, f + 1, … (the DOF map numbers
/// them vertex by vertex, components ascending), and every column of a
/// vertex holds the same rows below f (the unknowns of its neighbours
/// numbered before it). So for unknowns i ≤ j of different vertices, whose
/// first unknowns are fᵢ ≤ fⱼ, entry (i, j) sits as far into column j as
/// (fᵢ, fⱼ) sits into column fⱼ, plus i − fᵢ; and within one vertex,
/// column j = f + c holds those rows, then f, …, j, so (i, j) sits at
/// (its count of rows below f) + i − f, the count being column f's length
/// less its diagonal.
fn stencil_slots(pattern: &Pattern, unk: &[u32], dim: usize, out: &mut [u32]) {
    let (k, cp) = (unk.len(), pattern.col_ptr());
    let arity = k / dim;
    // first unknown of each local vertex (u32::MAX: all fixed)
    let mut first = [u32::MAX; MAX_STENCIL_DOFS];
    for (a, &u) in unk.iter().enumerate() {
        let f = &mut first[a / dim];
        *f = (*f).min(u);
    }
    // position of local pair (a, b), a ≤ b, in the upper row-major order
    let q = |a: usize, b: usize| a * k - a * (a + 1) / 2 + b;
    out.fill(NO_SLOT);
    for va in 0..arity {
        for vb in va..arity {
            let (fa, fb) = (first[va], first[vb]);
            if fa == u32::MAX || fb == u32::MAX {
                continue;
            }
            let (fi, fj) = (fa.min(fb) as usize, fa.max(fb) as usize);
            // a vertex's own block needs no search (its column's diagonal
            // is its last row); other pairs are in the pattern by
            // construction
            let off = if fi == fj {
                Some(pattern.diag_slot(fj) - cp[fj])
            } else {
                pattern.slot(fi, fj).map(|s| s - cp[fj])
            };
            let Some(off) = off else {
                continue;
            };
            for a in va * dim..(va + 1) * dim {
                for b in (vb * dim).max(a)..(vb + 1) * dim {
                    let (ia, ib) = (unk[a], unk[b]);
                    if ia != u32::MAX && ib != u32::MAX {
                        let (i, j) = (ia.min(ib) as usize, ia.max(ib) as usize);
                        out[q(a, b)] = (cp[j] + off + i - fi) as u32;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_upper_csc_checks_the_structure() {
        // [x x .]
        // [  x .]   column 2 holds only its diagonal: isolated
        // [    x]
        let p = Pattern::from_upper_csc(3, vec![0, 1, 3, 4], vec![0, 0, 1, 2]).unwrap();
        assert_eq!((p.n(), p.nnz()), (3, 4));
        assert_eq!(p.isolated(), &[2]);
        assert_eq!(p.slot(1, 0), Some(1));
        let err = |c: Vec<usize>, r: Vec<usize>| {
            format!("{}", Pattern::from_upper_csc(3, c, r).unwrap_err())
        };
        assert!(err(vec![0, 1, 3], vec![0, 0, 1]).contains("column pointers"));
        assert!(err(vec![0, 1, 2, 3], vec![0, 0, 2]).contains("column 1 has no diagonal"));
        assert!(err(vec![0, 1, 3, 4], vec![0, 0, 2, 2]).contains("column 1 has no diagonal"));
        assert!(err(vec![0, 1, 4, 5], vec![0, 0, 0, 1, 2]).contains("not strictly increasing"));
    }

    /// The entries (i, j) of `p`, column by column.
    fn entries(p: &Pattern) -> Vec<(usize, usize)> {
        let mut e = Vec::new();
        for j in 0..p.n() {
            let rows = &p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]];
            e.extend(rows.iter().map(|&i| (i, j)));
        }
        e
    }

    /// The module docs' rule by brute force, sorted by column then row:
    /// (i, j), i ≤ j, for free unknowns of one vertex or of two vertices
    /// sharing a stencil.
    fn coupled_pairs(dofs: &DofMap, arity: usize, stencils: &[usize]) -> Vec<(usize, usize)> {
        let (table, dim) = (dofs.unknown_table(), dofs.dim());
        let free = |v: usize| {
            (0..dim)
                .map(move |c| table[v * dim + c])
                .filter(|&u| u != u32::MAX)
                .map(|u| u as usize)
        };
        let mut set = std::collections::BTreeSet::new();
        let mut couple = |va: usize, vb: usize| {
            for i in free(va) {
                for j in free(vb) {
                    set.insert((i.max(j), i.min(j)));
                }
            }
        };
        (0..dofs.n_vertices()).for_each(|v| couple(v, v));
        for st in stencils.chunks_exact(arity) {
            for &va in st {
                st.iter().for_each(|&vb| couple(va, vb));
            }
        }
        set.into_iter().map(|(j, i)| (i, j)).collect()
    }

    /// The pattern is the module docs' rule (checked by brute force), and
    /// the slots found per vertex pair ([`stencil_slots`]) are those of one
    /// binary search per DOF pair, whatever is fixed (whole vertices, single
    /// components) and however the vertices are numbered.
    #[test]
    fn stencil_slots_are_the_searched_ones() {
        let mut seed = 12345u64;
        let mut rand = |m: usize| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) as usize % m
        };
        let nv = 40;
        for (dim, arity) in [(2, 3), (3, 4), (3, 3), (2, 2)] {
            let mut stencils = Vec::new();
            while stencils.len() < 60 * arity {
                let st: Vec<usize> = (0..arity).map(|_| rand(nv)).collect();
                if (1..arity).all(|a| !st[..a].contains(&st[a])) {
                    stencils.extend(st);
                }
            }
            let mask: Vec<bool> = (0..nv * dim).map(|_| rand(4) == 0).collect();
            let order: Vec<usize> = {
                let mut o: Vec<usize> = (0..nv).collect();
                (0..nv).for_each(|i| o.swap(i, rand(nv)));
                o
            };
            let maps = [
                DofMap::all_free(nv, dim).unwrap(),
                DofMap::from_fixed_vertices(nv, dim, &[0, 7, 8]).unwrap(),
                DofMap::from_dof_mask(nv, dim, &mask).unwrap(),
                DofMap::from_dof_mask(nv, dim, &mask)
                    .unwrap()
                    .renumbered(&order),
            ];
            for dofs in maps {
                let set = StencilSet {
                    name: "s",
                    arity,
                    stencils: &stencils,
                };
                let (p, plans) = build(&[set], &dofs).unwrap();
                assert_eq!(entries(&p), coupled_pairs(&dofs, arity, &stencils));
                let plan = &plans[0];
                let (k, nl) = (plan.k, plan.n_local);
                let mut fixed_pairs = 0;
                for (unk, got) in plan.unknowns.chunks(k).zip(plan.slots.chunks(nl)) {
                    let mut q = 0;
                    for a in 0..k {
                        for b in a..k {
                            let want = match (unk[a], unk[b]) {
                                (u32::MAX, _) | (_, u32::MAX) => NO_SLOT,
                                (i, j) => p.slot(i as usize, j as usize).unwrap() as u32,
                            };
                            fixed_pairs += usize::from(want == NO_SLOT);
                            assert_eq!(got[q], want, "dim {dim}, stencil {unk:?}, pair ({a}, {b})");
                            q += 1;
                        }
                    }
                }
                assert!(dofs.n_fixed() == 0 || fixed_pairs > 0);
            }
        }
    }

    #[test]
    fn two_triangles_pattern() {
        // square 0-1-2-3 split along 0-2; vertex 3 fixed; 2D
        let tris = [0usize, 1, 2, 0, 2, 3];
        let dofs = DofMap::from_fixed_vertices(5, 2, &[3]).unwrap(); // vertex 4 isolated
        let sets = [StencilSet {
            name: "t",
            arity: 3,
            stencils: &tris,
        }];
        let (p, plans) = build(&sets, &dofs).unwrap();
        assert_eq!(p.n(), 8); // vertices 0,1,2,4 free
        // vertices 0,1,2 are all coupled: 6×6 dense upper = 21 entries; vertex 4: 2×2 upper = 3
        assert_eq!(p.nnz(), 21 + 3);
        assert_eq!(p.isolated(), &[6, 7]);
        for j in 0..p.n() {
            assert_eq!(p.row_idx()[p.diag_slot(j)], j);
        }
        let plan = &plans[0];
        assert_eq!(plan.k, 6);
        assert_eq!(plan.n_local, 21);
        assert_eq!(plan.colouring.n_colours(), 2);
        let pos = |s: u32| plan.colouring.order.iter().position(|&t| t == s).unwrap();
        // second triangle: local dofs 4,5 are vertex 3 (fixed)
        let p1 = pos(1);
        let s1 = &plan.slots[21 * p1..21 * (p1 + 1)];
        assert_eq!(s1.iter().filter(|&&x| x == NO_SLOT).count(), 21 - 10);
        assert_eq!(
            &plan.unknowns[6 * p1 + 4..6 * p1 + 6],
            &[u32::MAX, u32::MAX]
        );
        // first triangle, local (0,5) = unknowns (0, 5)
        let p0 = pos(0);
        assert_eq!(plan.slots[21 * p0 + 5] as usize, p.slot(0, 5).unwrap());
    }

    #[test]
    fn invalid_stencils_are_reported() {
        let dofs = DofMap::all_free(3, 2).unwrap();
        let err = |arity: usize, stencils: &[usize]| {
            let set = StencilSet {
                name: "t",
                arity,
                stencils,
            };
            build(&[set], &dofs).unwrap_err()
        };
        assert!(matches!(
            err(3, &[0, 1, 1]),
            FemError::RepeatedVertex {
                stencil: 0,
                vertex: 1,
                ..
            }
        ));
        assert!(matches!(
            err(3, &[0, 1, 7]),
            FemError::VertexOutOfRange { vertex: 7, .. }
        ));
        assert!(matches!(err(3, &[0, 1]), FemError::BadStencilList { .. }));
        assert!(matches!(err(7, &[]), FemError::StencilTooLarge { .. }));
    }

    #[test]
    fn symmetric_products_agree() {
        let tris = [0usize, 1, 2, 1, 3, 2];
        let dofs = DofMap::all_free(4, 2).unwrap();
        let (p, _) = build(
            &[StencilSet {
                name: "t",
                arity: 3,
                stencils: &tris,
            }],
            &dofs,
        )
        .unwrap();
        let vals: Vec<f64> = (0..p.nnz()).map(|i| (i as f64 * 0.7).cos()).collect();
        let x: Vec<f64> = (0..p.n()).map(|i| (i as f64 * 1.3).sin()).collect();
        let mut y = vec![0.0; p.n()];
        p.sym_matvec(&vals, &x, &mut y);
        let xhx: f64 = x.iter().zip(&y).map(|(a, b)| a * b).sum();
        let mut partials = Vec::new();
        assert!((p.quadratic_form(&vals, &x, &mut partials) - xhx).abs() < 1e-12);
    }
}
