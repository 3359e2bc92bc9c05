//! One half of the split factorisation ([`super::split`]): the supernodal
//! LLᵀ of Bᵢ = A[Pᵢ∪S, Pᵢ∪S] *stopped before the separator*.
//!
//! With Pᵢ first (fill-reducing order) and S last, Bᵢ = LLᵀ has
//!
//! ```text
//! L = ⎡ Lᵢ    0 ⎤,   Lᵢ Lᵢᵀ = Aᵢᵢ,   L_Si = ASᵢ Lᵢ⁻ᵀ                       (7)
//!     ⎣ L_Si  · ⎦
//! ```
//!
//! and the separator needs from this half only its update
//!
//! ```text
//! Uᵢ = −L_Si L_Siᵀ   (k×k, lower triangle)                                  (8)
//! ```
//!
//! (Σ = ASS + U₁ + U₂, eq. (3) of [`super::split`]). So only the supernodes
//! of the Pᵢ columns are factorised, left-looking as in faer's supernodal
//! LLᵀ (each supernode gathers A's entries, subtracts the updates of its
//! descendants, factorises its diagonal block densely and solves its
//! off-diagonal rows). Their rows in S make up L_Si, and Uᵢ is gathered from
//! them as if S were one more supernode, without factorising it: the
//! separator's k×k dense block is factorised once, in Σ, not in each half.
//! The symbolic structure (supernodes, their row patterns, relaxation) is
//! faer's analysis of the vertex graph of Bᵢ expanded to its unknowns
//! ([`super::grouped`]), or of Bᵢ's scalar pattern where the unknowns are
//! not whole vertex blocks; a supernode straddling Pᵢ and S is cut at |Pᵢ|
//! (its S columns become rows of the cut supernode).
//!
//! **Solves.** Forward on [bᵢ; 0] through the Pᵢ supernodes leaves yᵢ =
//! Lᵢ⁻¹bᵢ in the Pᵢ entries and −L_Si yᵢ in the S entries (the terms of
//! r_S, (5)); backward on [yᵢ; x_S] gives xᵢ = Lᵢ⁻ᵀ(yᵢ − L_Siᵀ x_S), (6).
//! Everything runs on the calling thread in a fixed order (the same bits
//! run to run).
//!
//! **Precision.** The values are of the scalar `T` ([`Real`]): f64, or f32
//! for a mixed-precision factor (A's entries rounded on the gather, the
//! right-hand side rounded on entry to the solves, subnormals flushed while
//! this half works); Uᵢ and the solve's S entries are read back in f64 by
//! [`super::split`], which keeps the separator in double.

use std::ops::Range;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::{Accum, MatMut, MatRef, Par};

use super::real::Real;
use super::split::{lower_p_block, oom, sub_pattern, zeros};
use crate::error::FemError;
use crate::pattern::Pattern;

/// Descendant updates with at most this many multiply-adds are computed by
/// plain loops straight into the target (faer's dense kernels cost more than
/// they save on such small blocks).
const SMALL_UPDATE: usize = 4096;

/// A supernode of the Pᵢ columns: columns `start..end` (local), then the
/// off-diagonal `rows` (ascending local indices ≥ `end`, into `row_idx`);
/// its values are the (end − start + |rows|) × (end − start) column-major
/// block at `val` in `l`.
#[derive(Clone, Debug)]
pub(super) struct Node {
    pub(super) start: usize,
    pub(super) end: usize,
    pub(super) rows: Range<usize>,
    pub(super) val: usize,
}

/// The supernodes of the P columns and the row indices their `rows` index.
pub(super) type PNodes = (Vec<Node>, Vec<usize>);

/// Scratch of [`Half::update_from`]: the product of a large update and
/// the target row of each updating row.
struct Scratch<T> {
    temp: Vec<T>,
    map: Vec<usize>,
}

impl<T> Default for Scratch<T> {
    fn default() -> Self {
        Scratch {
            temp: Vec::new(),
            map: Vec::new(),
        }
    }
}

/// The value storage of a half in the scalar `T`, zeroed (see [`zeros`]).
struct Storage<T> {
    /// Uᵢ, k×k.
    update: Vec<T>,
    /// The solve vector, n entries.
    work: Vec<T>,
    /// Scratch of the dense Cholesky of the widest supernode.
    mem: MemBuffer,
}

impl<T: Real> Storage<T> {
    fn new(nodes: &[Node], k: usize, n: usize) -> Result<Self, FemError> {
        let max_w = nodes.iter().map(|n| n.end - n.start).max().unwrap_or(0);
        let req = cholesky_in_place_scratch::<T>(max_w, Par::Seq, Default::default());
        Ok(Storage {
            update: zeros(k * k, "the separator block")?,
            work: zeros(n, "the solve")?,
            mem: MemBuffer::try_new(req).map_err(|_| oom("scratch"))?,
        })
    }
}

/// Bᵢ = A[Pᵢ∪S, Pᵢ∪S]: structure, factor values of its Pᵢ columns and the
/// separator update Uᵢ of (8), in the scalar `T`.
pub(super) struct Half<T: Real> {
    /// Original unknown of each local one: Pᵢ in fill-reducing order, then S.
    pub(super) unknowns: Vec<usize>,
    /// |Pᵢ|.
    pub(super) n_p: usize,
    nodes: Vec<Node>,
    row_idx: Vec<usize>,
    /// Descendants of node s (the nodes with a row among its columns) are
    /// `desc[desc_ptr[s]..desc_ptr[s + 1]]`; index `nodes.len()` is S.
    desc_ptr: Vec<usize>,
    desc: Vec<usize>,
    /// Lower triangle of Bᵢ's Pᵢ columns: column j holds rows
    /// `a_rows[a_ptr[j]..a_ptr[j + 1]]`, whose values are A's `a_slots`.
    a_ptr: Vec<usize>,
    a_rows: Vec<usize>,
    a_slots: Vec<usize>,
    /// Factor values of the Pᵢ supernodes: empty until [`Half::reserve`].
    l: Vec<T>,
    /// How many values `l` holds once reserved.
    len: usize,
    /// Uᵢ of (8), k×k column-major, lower triangle.
    pub(super) update: Vec<T>,
    /// Row of a supernode's block holding each local row (scratch).
    rel: Vec<usize>,
    /// Scratch of the descendant updates.
    scratch: Scratch<T>,
    mem: MemBuffer,
    /// The solve vector: [yᵢ; −L_Si yᵢ] after [`Half::forward`], [xᵢ; x_S]
    /// after [`Half::backward`].
    pub(super) work: Vec<T>,
    /// Flops Σ c² over the Pᵢ columns (their updates of S included).
    pub(super) flops: f64,
}

/// faer's supernodal analysis of Bᵢ (upper CSC `col_ptr`/`row_idx`, the
/// local order kept).
fn faer_analysis(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
) -> Result<faer::sparse::linalg::cholesky::SymbolicCholesky<usize>, FemError> {
    faer_analysis_relaxed(n, col_ptr, row_idx, Default::default())
}

/// [`faer_analysis`] with the relaxation `supernodal`.
fn faer_analysis_relaxed(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    supernodal: faer::sparse::linalg::SymbolicSupernodalParams<'_>,
) -> Result<faer::sparse::linalg::cholesky::SymbolicCholesky<usize>, FemError> {
    let a = SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx);
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        supernodal_params: supernodal,
        ..Default::default()
    };
    factorize_symbolic_cholesky(a, faer::Side::Upper, SymmetricOrdering::Identity, params)
        .map_err(|e| FemError::Symbolic(format!("{e:?}")))
}

/// The supernodes of the first `n_p` columns of `sn` (cut at `n_p`) and
/// their row patterns.
fn p_nodes(sn: &SymbolicSupernodalCholesky<usize>, n_p: usize) -> PNodes {
    p_nodes_expanded(sn, n_p, |c| c)
}

/// The supernodes of the first `n_p` unknowns and their row patterns, from
/// an analysis `sn` whose column c stands for the unknowns
/// `at(c)..at(c + 1)` (c itself for a scalar analysis, a vertex's unknowns
/// for [`super::grouped`]), cut at `n_p`.
pub(super) fn p_nodes_expanded(
    sn: &SymbolicSupernodalCholesky<usize>,
    n_p: usize,
    at: impl Fn(usize) -> usize,
) -> PNodes {
    let (mut nodes, mut rows, mut val) = (Vec::new(), Vec::new(), 0);
    for s in 0..sn.n_supernodes() {
        let (start, e) = (at(sn.supernode_begin()[s]), at(sn.supernode_end()[s]));
        if start >= n_p {
            break;
        }
        let end = e.min(n_p);
        let r0 = rows.len();
        rows.extend(end..e);
        for &c in sn.supernode(s).pattern() {
            rows.extend(at(c)..at(c + 1));
        }
        let (w, m) = (end - start, end - start + rows.len() - r0);
        nodes.push(Node {
            start,
            end,
            rows: r0..rows.len(),
            val,
        });
        val += m * w;
    }
    (nodes, rows)
}

/// The P supernodes of faer's analysis of the scalar pattern of Bᵢ with
/// the relaxation `relax` (the reference of [`super::grouped`]'s).
#[cfg(test)]
pub(super) fn scalar_p_nodes(
    pattern: &Pattern,
    unknowns: &[usize],
    n_p: usize,
    relax: Option<&[(usize, f64)]>,
) -> PNodes {
    let (col_ptr, row_idx, _) = sub_pattern(pattern, unknowns);
    let params = faer::sparse::linalg::SymbolicSupernodalParams { relax };
    let symbolic = faer_analysis_relaxed(unknowns.len(), &col_ptr, &row_idx, params).unwrap();
    let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
        unreachable!("forced supernodal")
    };
    p_nodes(sn, n_p)
}

/// Descendant lists (CSR by target; target `nodes.len()` is S).
fn descendants(nodes: &[Node], rows: &[usize], n_p: usize) -> (Vec<usize>, Vec<usize>) {
    let mut owner = vec![0usize; n_p];
    for (s, node) in nodes.iter().enumerate() {
        owner[node.start..node.end].fill(s);
    }
    let owner = &owner;
    let targets = |d: usize| {
        let mut last = usize::MAX;
        rows[nodes[d].rows.clone()].iter().filter_map(move |&r| {
            let t = if r < n_p { owner[r] } else { nodes.len() };
            (t != last).then(|| {
                last = t;
                t
            })
        })
    };
    let mut ptr = vec![0usize; nodes.len() + 3];
    for d in 0..nodes.len() {
        targets(d).for_each(|t| ptr[t + 2] += 1);
    }
    for t in 2..ptr.len() {
        ptr[t] += ptr[t - 1];
    }
    let mut desc = vec![0usize; ptr[nodes.len() + 2]];
    for d in 0..nodes.len() {
        for t in targets(d) {
            desc[ptr[t + 1]] = d;
            ptr[t + 1] += 1;
        }
    }
    ptr.pop();
    (ptr, desc)
}

impl<T: Real> Half<T> {
    /// Structure of Bᵢ whose unknowns are `unknowns` (the first `n_p` are
    /// Pᵢ, the rest S, each in elimination order) and all its storage.
    pub(super) fn analyse(
        pattern: &Pattern,
        unknowns: Vec<usize>,
        n_p: usize,
    ) -> Result<Self, FemError> {
        let n = unknowns.len();
        let k = n - n_p;
        let grouped = super::grouped::grouped(pattern, &unknowns, n_p);
        let (nodes, rows) = match &grouped {
            Some(half) => super::grouped::p_nodes_of_groups(half, n_p)?,
            None => {
                let (col_ptr, row_idx, _) = sub_pattern(pattern, &unknowns);
                let symbolic = faer_analysis(n, &col_ptr, &row_idx)?;
                let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
                    unreachable!("the halves are analysed with FORCE_SUPERNODAL")
                };
                p_nodes(sn, n_p)
            }
        };
        let (desc_ptr, desc) = descendants(&nodes, &rows, n_p);
        let (a_ptr, a_rows, a_slots) = match &grouped {
            Some(half) => super::grouped::lower_p_block(pattern, half, n_p),
            None => lower_p_block(pattern, &unknowns, n_p),
        };
        let (mut len, mut flops) = (0, 0.0);
        for node in &nodes {
            let (w, r) = (node.end - node.start, node.rows.len());
            len = node.val + (w + r) * w;
            flops += (0..w).map(|c| ((w - c + r) as f64).powi(2)).sum::<f64>();
        }
        let Storage { update, work, mem } = Storage::new(&nodes, k, n)?;
        Ok(Half {
            unknowns,
            n_p,
            nodes,
            row_idx: rows,
            desc_ptr,
            desc,
            a_ptr,
            a_rows,
            a_slots,
            l: Vec::new(),
            len,
            update,
            rel: vec![0; n],
            scratch: Scratch::default(),
            mem,
            work,
            flops,
        })
    }

    /// The same structure with fresh (zero) storage of the scalar `U`: the
    /// fallback of a mixed-precision factor to double.
    pub(super) fn with_scalar<U: Real>(&self) -> Result<Half<U>, FemError> {
        let (n, k) = (self.unknowns.len(), self.k());
        let Storage { update, work, mem } = Storage::new(&self.nodes, k, n)?;
        Ok(Half {
            l: Vec::new(),
            len: self.len,
            update,
            work,
            mem,
            scratch: Scratch::default(),
            unknowns: self.unknowns.clone(),
            n_p: self.n_p,
            nodes: self.nodes.clone(),
            row_idx: self.row_idx.clone(),
            desc_ptr: self.desc_ptr.clone(),
            desc: self.desc.clone(),
            a_ptr: self.a_ptr.clone(),
            a_rows: self.a_rows.clone(),
            a_slots: self.a_slots.clone(),
            rel: self.rel.clone(),
            flops: self.flops,
        })
    }

    /// Separator size k.
    pub(super) fn k(&self) -> usize {
        self.unknowns.len() - self.n_p
    }

    /// Stored factor values (the Pᵢ supernodes).
    pub(super) fn len_val(&self) -> usize {
        self.len
    }

    /// Factor values allocated so far (0 before [`Half::reserve`]).
    #[cfg(test)]
    pub(super) fn stored(&self) -> usize {
        self.l.len()
    }

    /// Where the factor values are stored (to tell a reallocation).
    #[cfg(test)]
    pub(super) fn stored_at(&self) -> *const T {
        self.l.as_ptr()
    }

    /// Allocate (and zero) the factor values if not yet done. They are
    /// written here, by the first numeric factorisation, not in the
    /// analysis: see [`super::split::SplitFactor::reserve`].
    pub(super) fn reserve(&mut self) -> Result<(), FemError> {
        if self.l.len() != self.len {
            self.l = zeros(self.len, "a split factor")?;
        }
        Ok(())
    }

    /// Numeric LLᵀ of the Pᵢ columns of Bᵢ (7) and Uᵢ (8), on this thread;
    /// on a non-positive pivot, its local index.
    pub(super) fn factorize(&mut self, values: &[f64]) -> Result<(), usize> {
        debug_assert_eq!(self.l.len(), self.len, "factor values not reserved");
        let _flush = T::flush_subnormals();
        for s in 0..self.nodes.len() {
            self.factor_node(s, values)?;
        }
        let (k, n_p, n) = (self.k(), self.n_p, self.unknowns.len());
        let mut update = std::mem::take(&mut self.update);
        let mut scratch = std::mem::take(&mut self.scratch);
        update.fill(T::default());
        let s = self.nodes.len();
        for &d in &self.desc[self.desc_ptr[s]..self.desc_ptr[s + 1]] {
            self.update_from(&mut scratch, d, &self.l, &mut update, k, n_p..n);
        }
        (self.update, self.scratch) = (update, scratch);
        Ok(())
    }

    /// Node `s`: gather A, subtract its descendants' updates, factorise.
    fn factor_node(&mut self, s: usize, values: &[f64]) -> Result<(), usize> {
        let Node {
            start,
            end,
            rows,
            val,
        } = self.nodes[s].clone();
        let w = end - start;
        let m = w + rows.len();
        for (i, &r) in self.row_idx[rows].iter().enumerate() {
            self.rel[r] = w + i;
        }
        let mut l = std::mem::take(&mut self.l);
        let mut scratch = std::mem::take(&mut self.scratch);
        let (head, tail) = l.split_at_mut(val);
        let ls = &mut tail[..m * w];
        ls.fill(T::default());
        for j in start..end {
            let col = &mut ls[(j - start) * m..][..m];
            for e in self.a_ptr[j]..self.a_ptr[j + 1] {
                let i = self.a_rows[e];
                let li = if i < end { i - start } else { self.rel[i] };
                col[li] += T::of(values[self.a_slots[e]]);
            }
        }
        for &d in &self.desc[self.desc_ptr[s]..self.desc_ptr[s + 1]] {
            self.update_from(&mut scratch, d, head, ls, m, start..end);
        }
        let result = dense_node(ls, m, w, MemStack::new(&mut self.mem));
        (self.l, self.scratch) = (l, scratch);
        result.map_err(|index| start + index)
    }

    /// Subtract node `d`'s outer product L_d[rows ≥ cols.start] ·
    /// L_d[rows in cols]ᵀ from the m-row `target` whose columns are `cols`
    /// (rows at or beyond `cols.end` through `rel`); `l` holds node `d`.
    fn update_from(
        &self,
        scratch: &mut Scratch<T>,
        d: usize,
        l: &[T],
        target: &mut [T],
        m: usize,
        cols: Range<usize>,
    ) {
        let node = &self.nodes[d];
        let wd = node.end - node.start;
        let pd = &self.row_idx[node.rows.clone()];
        let md = wd + pd.len();
        let p0 = pd.partition_point(|&r| r < cols.start);
        let nm = pd[p0..].partition_point(|&r| r < cols.end);
        let nb = pd.len() - p0;
        let ld = &l[node.val..][..md * wd];
        let at = |r: usize| {
            let row = pd[p0 + r];
            if row < cols.end {
                row - cols.start
            } else {
                self.rel[row]
            }
        };
        let Scratch { temp, map } = scratch;
        map.clear();
        map.extend((0..nb).map(at));
        if nb * nm * wd <= SMALL_UPDATE {
            // column by column of the product: axpys of L_d's columns into
            // a contiguous column (vectorised), then one scattered
            // subtraction per entry instead of one per column of L_d
            if temp.len() < nb {
                temp.resize(nb, T::default());
            }
            for c in 0..nm {
                let t = &mut temp[c..nb];
                t.fill(T::default());
                for q in 0..wd {
                    let lq = &ld[q * md + wd + p0 + c..][..nb - c];
                    let lc = lq[0];
                    for (t, &l) in t.iter_mut().zip(lq) {
                        *t += l * lc;
                    }
                }
                let col = &mut target[(pd[p0 + c] - cols.start) * m..][..m];
                for (&to, &t) in map[c..].iter().zip(t.iter()) {
                    col[to] -= t;
                }
            }
            return;
        }
        if temp.len() < nb * nm {
            temp.resize(nb * nm, T::default());
        }
        let ldm = MatRef::from_column_major_slice(ld, md, wd);
        let below = ldm.subrows(wd + p0, nb);
        let mid = ldm.subrows(wd + p0, nm);
        let t = MatMut::from_column_major_slice_mut(&mut temp[..nb * nm], nb, nm);
        matmul(t, Accum::Replace, below, mid.transpose(), T::ONE, Par::Seq);
        for c in 0..nm {
            let col = &mut target[(pd[p0 + c] - cols.start) * m..][..m];
            for (&to, t) in map[c..].iter().zip(&temp[c * nb + c..(c + 1) * nb]) {
                col[to] -= t;
            }
        }
    }

    /// Forward solve (see the module docs): `work` = [yᵢ; −L_Si yᵢ].
    pub(super) fn forward(&mut self, b: &[f64]) {
        let _flush = T::flush_subnormals();
        let n_p = self.n_p;
        let work = &mut self.work;
        for (w, &u) in work.iter_mut().zip(&self.unknowns[..n_p]) {
            *w = T::of(b[u]);
        }
        work[n_p..].fill(T::default());
        for node in &self.nodes {
            let (start, w) = (node.start, node.end - node.start);
            let rows = &self.row_idx[node.rows.clone()];
            let m = w + rows.len();
            let ls = &self.l[node.val..][..m * w];
            for c in 0..w {
                let col = &ls[c * m..][..m];
                let xc = work[start + c] / col[c];
                work[start + c] = xc;
                for r in c + 1..w {
                    work[start + r] -= col[r] * xc;
                }
                for (&row, l) in rows.iter().zip(&col[w..]) {
                    work[row] -= l * xc;
                }
            }
        }
    }

    /// Backward solve (6): `work` = [xᵢ; x_S] from [yᵢ; ·] and x_S.
    pub(super) fn backward(&mut self, x_s: &[f64]) {
        let _flush = T::flush_subnormals();
        let work = &mut self.work;
        for (w, &x) in work[self.n_p..].iter_mut().zip(x_s) {
            *w = T::of(x);
        }
        for node in self.nodes.iter().rev() {
            let (start, w) = (node.start, node.end - node.start);
            let rows = &self.row_idx[node.rows.clone()];
            let m = w + rows.len();
            let ls = &self.l[node.val..][..m * w];
            for c in (0..w).rev() {
                let col = &ls[c * m..][..m];
                let mut s = work[start + c];
                for (&row, l) in rows.iter().zip(&col[w..]) {
                    s -= l * work[row];
                }
                for r in c + 1..w {
                    s -= col[r] * work[start + r];
                }
                work[start + c] = s / col[c];
            }
        }
    }
}

/// Dense part of a supernode (m×w column-major `ls`): Cholesky of the w×w
/// diagonal block, then the rows below ← rows below · L⁻ᵀ. On a
/// non-positive pivot, its index in the block.
fn dense_node<T: Real>(
    ls: &mut [T],
    m: usize,
    w: usize,
    stack: &mut MemStack,
) -> Result<(), usize> {
    let node = MatMut::from_column_major_slice_mut(ls, m, w);
    let (mut top, mut bot) = node.split_at_row_mut(w);
    cholesky_in_place(
        top.as_mut(),
        Default::default(),
        Par::Seq,
        stack,
        Default::default(),
    )
    .map_err(|LltError::NonPositivePivot { index }| index)?;
    solve_lower_triangular_in_place(top.as_ref(), bot.as_mut().transpose_mut(), Par::Seq);
    Ok(())
}
