//! Two-way domain-decomposed sparse Cholesky: the two halves of a vertex
//! separator are factorised concurrently, the separator densely.
//!
//! With a vertex separator S splitting the unknowns into P₁ and P₂
//! ([`super::separator`]), A[P₁, P₂] = 0 and, with the unknowns ordered
//! (P₁, P₂, S),
//!
//! ```text
//!     ⎡ A₁₁   0   A₁S ⎤
//! A = ⎢  0   A₂₂  A₂S ⎥                                              (1)
//!     ⎣ AS₁  AS₂  ASS ⎦
//! ```
//!
//! **Factorisation.** Bᵢ = A[Pᵢ∪S, Pᵢ∪S] (a principal submatrix of an SPD
//! matrix, so SPD) is factorised by faer, sequentially, both halves at once
//! (`rayon::join`), with Pᵢ in a fill-reducing order (block AMD of its vertex
//! graph) and S last:
//!
//! ```text
//! Bᵢ = ⎡ Aᵢᵢ  AᵢS ⎤ = ⎡ Lᵢ    0       ⎤ ⎡ Lᵢᵀ  L_Siᵀ    ⎤            (2)
//!      ⎣ ASᵢ  ASS ⎦   ⎣ L_Si  L_SS⁽ⁱ⁾ ⎦ ⎣ 0    L_SS⁽ⁱ⁾ᵀ ⎦
//! ```
//!
//! so L_Si = ASᵢ Lᵢ⁻ᵀ and L_SS⁽ⁱ⁾L_SS⁽ⁱ⁾ᵀ = ASS − L_Si L_Siᵀ. The Schur complement
//! of A₁₁ ⊕ A₂₂ in A is then
//!
//! ```text
//! Σ = ASS − L_S1 L_S1ᵀ − L_S2 L_S2ᵀ = L_SS⁽¹⁾L_SS⁽¹⁾ᵀ + L_SS⁽²⁾L_SS⁽²⁾ᵀ − ASS   (3)
//! ```
//!
//! (SPD as a Schur complement of an SPD matrix), factorised densely,
//! Σ = L_Σ L_Σᵀ (faer, on the pool's threads when it is large).
//!
//! **Solve** of A x = b. Forward, per half (concurrently), a lower solve of
//! Bᵢ's factor on [bᵢ; 0] gives [yᵢ; zᵢ] with
//!
//! ```text
//! yᵢ = Lᵢ⁻¹ bᵢ,   L_SS⁽ⁱ⁾ zᵢ = −L_Si yᵢ                                   (4)
//! ```
//!
//! and the separator's reduced right-hand side and unknowns are
//!
//! ```text
//! r_S = b_S − Σᵢ L_Si yᵢ = b_S + Σᵢ L_SS⁽ⁱ⁾ zᵢ,   x_S = L_Σ⁻ᵀ L_Σ⁻¹ r_S          (5)
//! ```
//!
//! Backward, per half, an upper solve of Bᵢ's factor on [yᵢ; L_SS⁽ⁱ⁾ᵀ x_S]:
//! its last block is L_SS⁽ⁱ⁾⁻ᵀ L_SS⁽ⁱ⁾ᵀ x_S = x_S, so its first block is
//!
//! ```text
//! xᵢ = Lᵢ⁻ᵀ (yᵢ − L_Siᵀ x_S) = Aᵢᵢ⁻¹ (bᵢ − AᵢS x_S)                          (6)
//! ```
//!
//! (Lᵢ⁻¹AᵢS = L_Siᵀ by (2)), the block back-substitution of (1).
//!
//! The extra work over one sparse factorisation is the separator's dense
//! block, computed three times (once per half inside Bᵢ, once for Σ) plus the
//! two products of (3): with k = |S|, about k³ flops, small next to the
//! halves when k ≪ n. Each half is sequential and the reductions run in a
//! fixed order, so the result is the same bits run to run for a given
//! number of threads.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::{LltError, cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::matmul::triangular::{BlockStructure, matmul};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, MatMut, MatRef, Par};

use super::separator::{Part, bisect};
use crate::error::FemError;
use crate::linear::ordering::{Supervariables, amd_order};
use crate::pattern::Pattern;

/// Separators at least this many unknowns wide factorise Σ on the pool's
/// threads (below, fork/join costs more than the dense kernels gain).
const DENSE_PARALLEL_MIN: usize = 256;

/// Bᵢ = A[Pᵢ∪S, Pᵢ∪S] of (2): its pattern, symbolic analysis and storage.
struct Half {
    /// Original unknown of each local one: Pᵢ in fill-reducing order, then S.
    unknowns: Vec<usize>,
    /// |Pᵢ|.
    n_p: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Slot in A's values of each entry of Bᵢ's (upper) pattern.
    gather: Vec<usize>,
    vals: Vec<f64>,
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    mem: MemBuffer,
    /// L_SS⁽ⁱ⁾ of (2), k×k column-major (entries outside L's structure stay 0).
    l_ss: Vec<f64>,
    /// The solve vector [yᵢ; zᵢ] of (4), then [xᵢ; x_S] of (6).
    work: Vec<f64>,
    /// L_SS⁽ⁱ⁾ zᵢ of (5).
    t: Vec<f64>,
    flops: f64,
}

fn oom(what: &str) -> FemError {
    FemError::Symbolic(format!("out of memory for {what}"))
}

fn zeros(len: usize, what: &str) -> Result<Vec<f64>, FemError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| oom(what))?;
    v.resize(len, 0.0);
    Ok(v)
}

/// The unknowns of the groups of `part`, the P part in block-AMD order of
/// its induced vertex graph, S in increasing order.
fn ordered_unknowns(
    sv: &Supervariables,
    parts: &[Part],
    part: Part,
) -> Result<Vec<usize>, FemError> {
    let groups: Vec<usize> = (0..sv.len()).filter(|&g| parts[g] == part).collect();
    if part == Part::Separator {
        return Ok(sv.expand(&groups));
    }
    let mut local = vec![usize::MAX; sv.len()];
    groups.iter().enumerate().for_each(|(l, &g)| local[g] = l);
    let (mut cp, mut ri) = (vec![0usize], Vec::new());
    for &g in &groups {
        let nb = &sv.adj[sv.adj_ptr[g]..sv.adj_ptr[g + 1]];
        // neighbours sorted by group, so by local index: upper part then diagonal
        ri.extend(nb.iter().map(|&h| local[h]).filter(|&h| h < local[g]));
        ri.push(local[g]);
        cp.push(ri.len());
    }
    let perm = amd_order(groups.len(), &cp, &ri)?;
    let order: Vec<usize> = perm.iter().map(|&l| groups[l]).collect();
    Ok(sv.expand(&order))
}

/// Upper-triangular CSC pattern of A[unknowns, unknowns] in the local order
/// and the slot in A of each of its entries.
fn sub_pattern(pattern: &Pattern, unknowns: &[usize]) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let n = unknowns.len();
    let mut local = vec![usize::MAX; pattern.n()];
    unknowns.iter().enumerate().for_each(|(l, &u)| local[u] = l);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let mut cols: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for j in 0..pattern.n() {
        let lj = local[j];
        if lj == usize::MAX {
            continue;
        }
        for (slot, &i) in (cp[j]..cp[j + 1]).zip(&ri[cp[j]..cp[j + 1]]) {
            let li = local[i];
            if li != usize::MAX {
                cols[li.max(lj)].push((li.min(lj), slot));
            }
        }
    }
    let (mut col_ptr, mut row_idx, mut gather) = (vec![0usize], Vec::new(), Vec::new());
    for mut col in cols {
        col.sort_unstable();
        row_idx.extend(col.iter().map(|e| e.0));
        gather.extend(col.iter().map(|e| e.1));
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx, gather)
}

/// The supernodal factor of a half (analysed with FORCE_SUPERNODAL).
fn supernodal<'a>(
    symbolic: &'a SymbolicCholesky<usize>,
    l_values: &'a [f64],
) -> SupernodalLltRef<'a, usize, f64> {
    let SymbolicCholeskyRaw::Supernodal(s) = symbolic.raw() else {
        unreachable!("the halves are analysed with FORCE_SUPERNODAL")
    };
    SupernodalLltRef::new(s, l_values)
}

impl Half {
    /// Pattern and symbolic analysis of Bᵢ for part `part` (storage comes
    /// later, in [`Half::allocate`], for the chosen bisection only).
    fn analyse(
        pattern: &Pattern,
        sv: &Supervariables,
        parts: &[Part],
        part: Part,
    ) -> Result<Self, FemError> {
        let mut unknowns = ordered_unknowns(sv, parts, part)?;
        let n_p = unknowns.len();
        unknowns.extend(ordered_unknowns(sv, parts, Part::Separator)?);
        let n = unknowns.len();
        let (col_ptr, row_idx, gather) = sub_pattern(pattern, &unknowns);
        let a = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(a, faer::Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(|e| FemError::Symbolic(format!("{e:?}")))?;
        let flops = super::flops(&symbolic);
        Ok(Half {
            unknowns,
            n_p,
            col_ptr,
            row_idx,
            gather,
            vals: Vec::new(),
            symbolic,
            l_values: Vec::new(),
            mem: MemBuffer::new(StackReq::EMPTY),
            l_ss: Vec::new(),
            work: Vec::new(),
            t: Vec::new(),
            flops,
        })
    }

    fn k(&self) -> usize {
        self.unknowns.len() - self.n_p
    }

    /// Allocate the factor values and all scratch.
    fn allocate(&mut self) -> Result<(), FemError> {
        let (n, k) = (self.unknowns.len(), self.k());
        let req = StackReq::any_of(&[
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
            self.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        self.mem = MemBuffer::try_new(req).map_err(|_| oom("scratch"))?;
        self.l_values = zeros(self.symbolic.len_val(), "a split factor")?;
        self.vals = zeros(self.gather.len(), "a split block")?;
        self.l_ss = zeros(k * k, "the separator block")?;
        self.work = zeros(n, "the solve")?;
        self.t = zeros(k, "the solve")?;
        Ok(())
    }

    fn supernodal(&self) -> SupernodalLltRef<'_, usize, f64> {
        supernodal(&self.symbolic, &self.l_values)
    }

    /// Numeric LLᵀ of Bᵢ (2) on one thread, then copy out L_SS⁽ⁱ⁾. On a
    /// non-positive pivot, its local index.
    fn factorize(&mut self, values: &[f64]) -> Result<(), usize> {
        for (v, &slot) in self.vals.iter_mut().zip(&self.gather) {
            *v = values[slot];
        }
        let n = self.unknowns.len();
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let result = self.symbolic.factorize_numeric_llt::<f64>(
            &mut self.l_values,
            SparseColMatRef::new(sym, &self.vals),
            faer::Side::Upper,
            Default::default(),
            Par::Seq,
            MemStack::new(&mut self.mem),
            Default::default(),
        );
        match result {
            Ok(_) => {
                self.extract_l_ss();
                Ok(())
            }
            Err(LltError::NonPositivePivot { index }) => Err(index),
        }
    }

    /// Copy the rows and columns ≥ |Pᵢ| of L (the trailing block of (2)).
    fn extract_l_ss(&mut self) {
        let (n_p, k) = (self.n_p, self.k());
        let mut l_ss = std::mem::take(&mut self.l_ss);
        let llt = self.supernodal();
        let s = llt.symbolic();
        let first = s.supernode_end().partition_point(|&e| e <= n_p);
        for node in (first..s.n_supernodes()).map(|i| llt.supernode(i)) {
            let (start, val) = (node.start(), node.val());
            let w = val.ncols();
            for c in (0..w).filter(|&c| start + c >= n_p) {
                let col = &mut l_ss[k * (start + c - n_p)..][..k];
                for t in c..w {
                    col[start + t - n_p] = val[(t, c)];
                }
                for (idx, &r) in node.pattern().iter().enumerate() {
                    col[r - n_p] = val[(w + idx, c)];
                }
            }
        }
        self.l_ss = l_ss;
    }

    /// Forward half of the solve: [yᵢ; zᵢ] of (4) in `work` and
    /// t = L_SS⁽ⁱ⁾ zᵢ (5).
    fn forward(&mut self, b: &[f64]) {
        let (n, n_p, k) = (self.unknowns.len(), self.n_p, self.k());
        let mut work = std::mem::take(&mut self.work);
        for (w, &u) in work.iter_mut().zip(&self.unknowns[..n_p]) {
            *w = b[u];
        }
        work[n_p..].fill(0.0);
        supernodal(&self.symbolic, &self.l_values).l_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut work, n, 1),
            Par::Seq,
            MemStack::new(&mut self.mem),
        );
        let z = &work[n_p..];
        self.t.fill(0.0);
        for (c, &zc) in z.iter().enumerate() {
            let col = &self.l_ss[k * c..][..k];
            for r in c..k {
                self.t[r] += col[r] * zc;
            }
        }
        self.work = work;
    }

    /// Backward half of the solve (6): `work` becomes [xᵢ; x_S].
    fn backward(&mut self, x_s: &[f64]) {
        let (n, n_p, k) = (self.unknowns.len(), self.n_p, self.k());
        let mut work = std::mem::take(&mut self.work);
        for (c, u) in work[n_p..].iter_mut().enumerate() {
            let col = &self.l_ss[k * c..][..k];
            *u = (c..k).map(|r| col[r] * x_s[r]).sum();
        }
        supernodal(&self.symbolic, &self.l_values).l_transpose_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut work, n, 1),
            Par::Seq,
            MemStack::new(&mut self.mem),
        );
        self.work = work;
    }
}

/// The two-way split factor of (1)–(3).
pub(crate) struct SplitFactor {
    halves: [Half; 2],
    /// Original unknowns of S, in the order of Σ.
    sep: Vec<usize>,
    /// (row, column, slot in A) of the lower triangle of ASS in Σ's order.
    a_ss: Vec<(usize, usize, usize)>,
    /// Σ of (3), k×k column-major; its lower triangle becomes L_Σ.
    schur: Vec<f64>,
    dense_mem: MemBuffer,
    /// x_S of (5).
    x_s: Vec<f64>,
}

/// A non-positive pivot of the split factorisation, as a position in the
/// order (P₁, P₂, S).
pub(crate) struct SplitPivot(pub usize);

impl SplitFactor {
    /// Bisect the vertex graph of `pattern` and analyse both halves; `None`
    /// if the graph cannot be split. The bisection is aimed at equal flops
    /// of the two halves: a first cut at half the unknowns, then, if the
    /// halves' flops differ by more than 10 %, one cut re-aimed assuming
    /// flops ∝ (unknowns)^1.5 on each side; the cheaper of the two is kept.
    pub(crate) fn analyse(pattern: &Pattern) -> Result<Option<Self>, FemError> {
        let sv = Supervariables::of(pattern);
        let weight: Vec<f64> = sv.start.windows(2).map(|w| (w[1] - w[0]) as f64).collect();
        let mut best: Option<([Half; 2], f64)> = None;
        let mut fraction = 0.5;
        for _ in 0..2 {
            let Some(parts) = bisect(&sv, &weight, fraction) else {
                return Ok(None);
            };
            let halves = [
                Half::analyse(pattern, &sv, &parts, Part::First)?,
                Half::analyse(pattern, &sv, &parts, Part::Second)?,
            ];
            let (f1, f2) = (halves[0].flops, halves[1].flops);
            let cost = f1.max(f2) + (halves[0].k() as f64).powi(3);
            if best.as_ref().is_none_or(|b| cost < b.1) {
                best = Some((halves, cost));
            }
            if f1.max(f2) <= 1.1 * f1.min(f2) {
                break;
            }
            let c1 = f1 / fraction.powf(1.5);
            let c2 = f2 / (1.0 - fraction).powf(1.5);
            let r = (c2 / c1).powf(1.0 / 1.5);
            fraction = (r / (1.0 + r)).clamp(0.1, 0.9);
        }
        let Some((halves, _)) = best else {
            return Ok(None);
        };
        Self::with_halves(pattern, halves).map(Some)
    }

    fn with_halves(pattern: &Pattern, mut halves: [Half; 2]) -> Result<Self, FemError> {
        for h in &mut halves {
            h.allocate()?;
        }
        let sep = halves[0].unknowns[halves[0].n_p..].to_vec();
        let k = sep.len();
        let (col_ptr, row_idx, gather) = sub_pattern(pattern, &sep);
        let mut a_ss = Vec::with_capacity(gather.len());
        for j in 0..k {
            for e in col_ptr[j]..col_ptr[j + 1] {
                a_ss.push((j, row_idx[e], gather[e]));
            }
        }
        let par = Self::dense_par(k);
        let dense_mem =
            MemBuffer::try_new(cholesky_in_place_scratch::<f64>(k, par, Default::default()))
                .map_err(|_| oom("scratch"))?;
        Ok(SplitFactor {
            halves,
            sep,
            a_ss,
            schur: zeros(k * k, "the separator's Schur complement")?,
            dense_mem,
            x_s: zeros(k, "the solve")?,
        })
    }

    fn dense_par(k: usize) -> Par {
        if k >= DENSE_PARALLEL_MIN && rayon::current_num_threads() > 1 {
            Par::rayon(0)
        } else {
            Par::Seq
        }
    }

    /// Number of separator unknowns k.
    pub(crate) fn separator_len(&self) -> usize {
        self.sep.len()
    }

    /// Stored values: both halves' factors and the dense L_Σ.
    pub(crate) fn nnz(&self) -> usize {
        let k = self.sep.len();
        self.halves.iter().map(|h| h.l_values.len()).sum::<usize>() + k * (k + 1) / 2
    }

    /// Estimated flops, in the measure of [`super::flops`] (Σ c² over the
    /// columns): both halves plus ≈ k³ for the three dense k×k terms.
    pub(crate) fn flops(&self) -> f64 {
        self.halves.iter().map(|h| h.flops).sum::<f64>() + (self.sep.len() as f64).powi(3)
    }

    /// Estimated flops of the larger half (the critical path with 2 threads).
    pub(crate) fn critical_flops(&self) -> f64 {
        self.halves[0].flops.max(self.halves[1].flops)
    }

    /// Map a pivot of half `i` (local index) to the order (P₁, P₂, S).
    fn pivot(&self, i: usize, local: usize) -> SplitPivot {
        let (p1, p2) = (self.halves[0].n_p, self.halves[1].n_p);
        let h = &self.halves[i];
        SplitPivot(if local < h.n_p {
            local + if i == 0 { 0 } else { p1 }
        } else {
            p1 + p2 + local - h.n_p
        })
    }

    /// Numeric factorisation of A (upper-triangular `values` on the analysed
    /// pattern): (2) for both halves at once, then (3) and L_Σ.
    pub(crate) fn factorize(&mut self, values: &[f64]) -> Result<(), SplitPivot> {
        let [h1, h2] = &mut self.halves;
        let (r1, r2) = rayon::join(|| h1.factorize(values), || h2.factorize(values));
        if let Err(p) = r1 {
            return Err(self.pivot(0, p));
        }
        if let Err(p) = r2 {
            return Err(self.pivot(1, p));
        }
        let k = self.sep.len();
        if k == 0 {
            return Ok(());
        }
        let par = Self::dense_par(k);
        self.schur.fill(0.0);
        for &(c, r, slot) in &self.a_ss {
            // a_ss holds (column j, row i ≤ j): store at (max, min) = lower
            self.schur[r.max(c) + k * r.min(c)] -= values[slot];
        }
        let mut schur = MatMut::from_column_major_slice_mut(&mut self.schur, k, k);
        for h in &self.halves {
            let l = MatRef::from_column_major_slice(&h.l_ss, k, k);
            matmul(
                schur.as_mut(),
                BlockStructure::TriangularLower,
                Accum::Add,
                l,
                BlockStructure::TriangularLower,
                l.transpose(),
                BlockStructure::TriangularUpper,
                1.0,
                par,
            );
        }
        cholesky_in_place(
            schur,
            Default::default(),
            par,
            MemStack::new(&mut self.dense_mem),
            Default::default(),
        )
        .map(|_| ())
        .map_err(|LltError::NonPositivePivot { index }| {
            SplitPivot(self.halves[0].n_p + self.halves[1].n_p + index)
        })
    }

    /// Solve A x = `rhs` in place with the last successful factorisation,
    /// (4)–(6).
    pub(crate) fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let k = self.sep.len();
        {
            let b: &[f64] = rhs;
            let [h1, h2] = &mut self.halves;
            rayon::join(|| h1.forward(b), || h2.forward(b));
        }
        for (j, x) in self.x_s.iter_mut().enumerate() {
            *x = rhs[self.sep[j]] + self.halves[0].t[j] + self.halves[1].t[j];
        }
        if k > 0 {
            let l = MatRef::from_column_major_slice(&self.schur, k, k);
            let mut x = MatMut::from_column_major_slice_mut(&mut self.x_s, k, 1);
            solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
            solve_upper_triangular_in_place(l.transpose(), x.as_mut(), Par::Seq);
        }
        let [h1, h2] = &mut self.halves;
        let x_s = &self.x_s;
        rayon::join(|| h1.backward(x_s), || h2.backward(x_s));
        for h in &self.halves {
            for (&u, &x) in h.unknowns[..h.n_p].iter().zip(&h.work) {
                rhs[u] = x;
            }
        }
        for (&u, &x) in self.sep.iter().zip(&self.x_s) {
            rhs[u] = x;
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::linear::cholesky::CholeskyFactor;
    use crate::linear::ordering::tests::grid;
    use crate::pattern::{StencilSet, build};
    use rand::{Rng, SeedableRng};

    fn triangles(n_vertices: usize, tris: &[usize], dim: usize) -> (Pattern, usize) {
        let dofs = DofMap::all_free(n_vertices, dim).unwrap();
        let set = StencilSet {
            name: "t",
            arity: 3,
            stencils: tris,
        };
        (build(&[set], &dofs).unwrap().0, n_vertices)
    }

    /// Two disjoint nx×ny triangulated grids (no coupling between them).
    pub(crate) fn two_grids(nx: usize, ny: usize, dim: usize) -> (Pattern, usize) {
        let nv = (nx + 1) * (ny + 1);
        let v = |i: usize, j: usize| i + j * (nx + 1);
        let mut tris = Vec::new();
        for off in [0, nv] {
            for j in 0..ny {
                for i in 0..nx {
                    tris.extend([v(i, j), v(i + 1, j), v(i + 1, j + 1)].map(|x| x + off));
                    tris.extend([v(i, j), v(i + 1, j + 1), v(i, j + 1)].map(|x| x + off));
                }
            }
        }
        triangles(2 * nv, &tris, dim)
    }

    /// One triangle: a complete vertex graph (cannot be bisected).
    pub(crate) fn triangle() -> (Pattern, usize) {
        triangles(3, &[0, 1, 2], 2)
    }

    /// A random SPD matrix on `p`: off-diagonals in [−1, 1], diagonal =
    /// Σ|off-diagonals of the row| + a random positive margin.
    fn random_spd(p: &Pattern, seed: u64) -> Vec<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut v = vec![0.0; p.nnz()];
        let mut row_sum = vec![0.0; p.n()];
        for j in 0..p.n() {
            for e in p.col_ptr()[j]..p.col_ptr()[j + 1] {
                let i = p.row_idx()[e];
                if i != j {
                    v[e] = rng.gen_range(-1.0..1.0);
                    row_sum[i] += f64::abs(v[e]);
                    row_sum[j] += f64::abs(v[e]);
                }
            }
        }
        for j in 0..p.n() {
            v[p.diag_slot(j)] = row_sum[j] + rng.gen_range(0.01..1.0);
        }
        v
    }

    fn rel_residual(p: &Pattern, v: &[f64], x: &[f64], b: &[f64]) -> f64 {
        let mut ax = vec![0.0; p.n()];
        p.sym_matvec(v, x, &mut ax);
        let norm = |u: &[f64]| u.iter().map(|a| a * a).sum::<f64>().sqrt();
        let r: Vec<f64> = ax.iter().zip(b).map(|(a, b)| a - b).collect();
        norm(&r) / norm(b)
    }

    /// Split solve vs the plain factorisation on random SPD values.
    fn agrees_with_plain(p: &Pattern, expect_separator: bool) {
        let mut split = SplitFactor::analyse(p).unwrap().expect("splittable");
        assert_eq!(split.separator_len() > 0, expect_separator);
        let mut plain = CholeskyFactor::analyze(p).unwrap();
        for seed in 0..3 {
            let v = random_spd(p, seed);
            let b: Vec<f64> = (0..p.n())
                .map(|i| (0.37 * i as f64 + seed as f64).sin())
                .collect();
            split.factorize(&v).ok().unwrap();
            plain.factorize(p, &v).unwrap();
            let (mut xs, mut xp) = (b.clone(), b.clone());
            split.solve_in_place(&mut xs);
            assert!(plain.solve_in_place(&mut xp));
            let res = rel_residual(p, &v, &xs, &b);
            assert!(res <= 1e-12, "relative residual {res:e}");
            let scale = xp.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            let diff = xs
                .iter()
                .zip(&xp)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(diff <= 1e-12 * scale, "split vs plain: {diff:e}");
        }
    }

    #[test]
    fn split_solves_agree_with_the_plain_factorisation() {
        agrees_with_plain(&grid(30, 20, 2), true);
        agrees_with_plain(&grid(12, 9, 3), true);
        agrees_with_plain(&grid(3, 2, 1), true);
    }

    #[test]
    fn an_empty_separator_splits_disconnected_halves() {
        agrees_with_plain(&two_grids(7, 6, 2).0, false);
    }

    #[test]
    fn an_unsplittable_graph_is_reported_not_forced() {
        assert!(SplitFactor::analyse(&triangle().0).unwrap().is_none());
    }

    #[test]
    fn an_indefinite_matrix_is_reported_in_either_half_or_the_separator() {
        let p = grid(20, 10, 2);
        let mut split = SplitFactor::analyse(&p).unwrap().unwrap();
        let n = p.n();
        for bad in [0, n / 2, n - 1] {
            let mut v = random_spd(&p, 7);
            v[p.diag_slot(bad)] = -1.0;
            assert!(split.factorize(&v).is_err(), "diagonal {bad} negative");
        }
        // and a correct factorisation afterwards still solves
        let v = random_spd(&p, 8);
        split.factorize(&v).ok().unwrap();
    }

    #[test]
    fn the_split_is_the_same_bits_run_to_run() {
        let p = grid(40, 30, 2);
        let v = random_spd(&p, 3);
        let b: Vec<f64> = (0..p.n()).map(|i| (0.1 * i as f64).cos()).collect();
        let run = || {
            let mut s = SplitFactor::analyse(&p).unwrap().unwrap();
            s.factorize(&v).ok().unwrap();
            let mut x = b.clone();
            s.solve_in_place(&mut x);
            x.iter().map(|a| a.to_bits()).collect::<Vec<_>>()
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let first = pool.install(run);
        for _ in 0..3 {
            assert_eq!(pool.install(run), first);
        }
    }
}
