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
//! matrix, so SPD), with Pᵢ in the fill-reducing order and S last, has the
//! Cholesky factor
//!
//! ```text
//! Bᵢ = ⎡ Aᵢᵢ  AᵢS ⎤ = ⎡ Lᵢ    0       ⎤ ⎡ Lᵢᵀ  L_Siᵀ    ⎤            (2)
//!      ⎣ ASᵢ  ASS ⎦   ⎣ L_Si  L_SS⁽ⁱ⁾ ⎦ ⎣ 0    L_SS⁽ⁱ⁾ᵀ ⎦
//! ```
//!
//! with L_Si = ASᵢ Lᵢ⁻ᵀ. Each half factorises only its Pᵢ columns, Lᵢ and
//! L_Si, and gathers Uᵢ = −L_Si L_Siᵀ from them ([`super::half`], (7)–(8)),
//! sequentially, both halves at once (`rayon::join`); L_SS⁽ⁱ⁾ is never
//! formed. The Schur complement of A₁₁ ⊕ A₂₂ in A is then
//!
//! ```text
//! Σ = ASS − L_S1 L_S1ᵀ − L_S2 L_S2ᵀ = ASS + U₁ + U₂                          (3)
//! ```
//!
//! (SPD as a Schur complement of an SPD matrix), factorised densely,
//! Σ = L_Σ L_Σᵀ (faer, on the pool's threads when it is large).
//!
//! **Solve** of A x = b. Forward, per half (concurrently), the lower solve
//! through the Pᵢ columns of Bᵢ's factor on [bᵢ; 0] gives
//!
//! ```text
//! yᵢ = Lᵢ⁻¹ bᵢ   and   zᵢ = −L_Si yᵢ                                          (4)
//! ```
//!
//! and the separator's reduced right-hand side and unknowns are
//!
//! ```text
//! r_S = b_S − Σᵢ L_Si yᵢ = b_S + z₁ + z₂,   x_S = L_Σ⁻ᵀ L_Σ⁻¹ r_S              (5)
//! ```
//!
//! Backward, per half, the upper solve through the Pᵢ columns on [yᵢ; x_S]:
//!
//! ```text
//! xᵢ = Lᵢ⁻ᵀ (yᵢ − L_Siᵀ x_S) = Aᵢᵢ⁻¹ (bᵢ − AᵢS x_S)                          (6)
//! ```
//!
//! (Lᵢ⁻¹AᵢS = L_Siᵀ by (2)), the block back-substitution of (1).
//!
//! The extra work over one sparse factorisation is the separator's dense
//! Cholesky, k³/3 flops (k = |S|), once, where the plain factorisation
//! spends about as much on S's columns: the halves' work is exactly their
//! share of the plain factorisation's (their updates of S included). Each
//! half is sequential and the reductions run in a fixed order, so the result
//! is the same bits run to run for a given number of threads.
//!
//! **Precision.** The halves hold their factors in the scalar `T`
//! ([`super::real`]); Σ, L_Σ and x_S are always f64 (the dense separator is
//! a small part of the work, and it keeps the halves' updates Uᵢ summed in
//! double).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{MatMut, MatRef, Par};

use super::FactorizeError;
use super::half::Half;
use super::real::Real;
use super::tree::{Part, Tree, split};
use crate::error::FemError;
use crate::pattern::Pattern;

/// Separators at least this many unknowns wide factorise Σ on the pool's
/// threads (below, fork/join costs more than the dense kernels gain).
const DENSE_PARALLEL_MIN: usize = 256;

pub(super) fn oom(what: &str) -> FemError {
    FemError::Symbolic(format!("out of memory for {what}"))
}

/// `len` zeros, or an out-of-memory error naming `what`; every page is
/// written here (see [`SplitFactor::reserve`] for when).
pub(super) fn zeros<T: Clone + Default>(len: usize, what: &str) -> Result<Vec<T>, FemError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| oom(what))?;
    v.resize(len, T::default());
    Ok(v)
}

/// Upper-triangular CSC pattern of A[unknowns, unknowns] in the local order
/// and the slot in A of each of its entries.
pub(super) fn sub_pattern(
    pattern: &Pattern,
    unknowns: &[usize],
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    block_csc(pattern, unknowns, unknowns.len(), |li, lj| {
        Some((li.max(lj), li.min(lj)))
    })
}

/// Lower-triangular CSC of the first `n_p` columns of A[unknowns,
/// unknowns] in the local order, and the slot in A of each entry.
pub(super) fn lower_p_block(
    pattern: &Pattern,
    unknowns: &[usize],
    n_p: usize,
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    block_csc(pattern, unknowns, n_p, |li, lj| {
        (li.min(lj) < n_p).then(|| (li.min(lj), li.max(lj)))
    })
}

/// CSC over `cols` columns (pointers, rows, slots in A) of the entries of
/// A[unknowns, unknowns] (local indices) that `place` puts at some
/// (column, row), each column sorted by row.
fn block_csc(
    pattern: &Pattern,
    unknowns: &[usize],
    cols: usize,
    place: impl Fn(usize, usize) -> Option<(usize, usize)>,
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let mut local = vec![usize::MAX; pattern.n()];
    unknowns.iter().enumerate().for_each(|(l, &u)| local[u] = l);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    // (column, row, slot) of every placed entry inside the block: the upper
    // columns of its unknowns, their rows inside it
    let entries = |visit: &mut dyn FnMut(usize, usize, usize)| {
        for (lj, &j) in unknowns.iter().enumerate() {
            for (slot, &i) in (cp[j]..cp[j + 1]).zip(&ri[cp[j]..cp[j + 1]]) {
                let li = local[i];
                if li != usize::MAX
                    && let Some((c, r)) = place(li, lj)
                {
                    visit(c, r, slot);
                }
            }
        }
    };
    // counting sort by column, then each column by row
    let mut col_ptr = vec![0usize; cols + 1];
    entries(&mut |c, _, _| col_ptr[c + 1] += 1);
    for c in 0..cols {
        col_ptr[c + 1] += col_ptr[c];
    }
    let mut next = col_ptr[..cols].to_vec();
    let mut entry = vec![(0usize, 0usize); col_ptr[cols]];
    entries(&mut |c, r, slot| {
        entry[next[c]] = (r, slot);
        next[c] += 1;
    });
    for c in 0..cols {
        entry[col_ptr[c]..col_ptr[c + 1]].sort_unstable();
    }
    let row_idx = entry.iter().map(|e| e.0).collect();
    let gather = entry.iter().map(|e| e.1).collect();
    (col_ptr, row_idx, gather)
}

/// The two-way split factor of (1)–(3), its halves in the scalar `T`.
pub(crate) struct SplitFactor<T: Real> {
    halves: [Half<T>; 2],
    /// Original unknowns of S, in the order of Σ.
    sep: Vec<usize>,
    /// (row, column, slot in A) of the lower triangle of ASS in Σ's order.
    a_ss: Vec<(usize, usize, usize)>,
    /// Σ of (3), k×k column-major; its lower triangle becomes L_Σ.
    schur: Vec<f64>,
    dense_mem: MemBuffer,
    /// x_S of (5).
    x_s: Vec<f64>,
    /// See [`SplitFactor::phases`].
    phases: [f64; 4],
}

impl<T: Real> SplitFactor<T> {
    /// Split the supernodal tree of the plain analysis `symbolic` of
    /// `pattern` ([`super::tree`]) and analyse both halves; `None` if the
    /// plain factor is simplicial or (unless `force`) no split is estimated
    /// to pay.
    #[cfg(test)]
    pub(crate) fn analyse(
        pattern: &Pattern,
        symbolic: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
        force: bool,
    ) -> Result<Option<Self>, FemError> {
        use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
        let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
            return Ok(None);
        };
        let perm = symbolic.perm().map(|p| p.arrays().0);
        Self::analyse_tree(pattern, perm, &Tree::of_supernodal(sn), force)
    }

    /// Split `tree`, the supernodal elimination tree of `pattern` in the
    /// fill-reducing order `perm` (`perm[new] = old`, `None`: identity),
    /// and analyse both halves; `None` if (unless `force`) no split is
    /// estimated to pay.
    pub(crate) fn analyse_tree(
        pattern: &Pattern,
        perm: Option<&[usize]>,
        tree: &Tree,
        force: bool,
    ) -> Result<Option<Self>, FemError> {
        let Some(cut) = split(tree, force) else {
            return Ok(None);
        };
        let old = |new: usize| perm.map_or(new, |p| p[new]);
        let columns = |part: Part| -> Vec<usize> {
            (0..cut.len())
                .filter(|&k| cut[k] == part)
                .flat_map(|k| tree.begin[k]..tree.end[k])
                .map(old)
                .collect()
        };
        let sep = columns(Part::Separator);
        let half = |part| {
            let mut unknowns = columns(part);
            let n_p = unknowns.len();
            unknowns.extend_from_slice(&sep);
            Half::analyse(pattern, unknowns, n_p)
        };
        // independent analyses: both at once (setup of the 1M-triangle disk)
        let (first, second) = rayon::join(|| half(Part::First), || half(Part::Second));
        let halves = [first?, second?];
        Self::with_halves(pattern, halves).map(Some)
    }

    fn with_halves(pattern: &Pattern, halves: [Half<T>; 2]) -> Result<Self, FemError> {
        let sep = halves[0].unknowns[halves[0].n_p..].to_vec();
        let k = sep.len();
        let (col_ptr, row_idx, gather) = sub_pattern(pattern, &sep);
        let mut a_ss = Vec::with_capacity(gather.len());
        for j in 0..k {
            for e in col_ptr[j]..col_ptr[j + 1] {
                a_ss.push((j, row_idx[e], gather[e]));
            }
        }
        Self::with_separator(halves, sep, a_ss)
    }

    /// The split of `halves` with separator `sep` (ASS at `a_ss`) and fresh
    /// storage for Σ, its dense factorisation and x_S.
    fn with_separator(
        halves: [Half<T>; 2],
        sep: Vec<usize>,
        a_ss: Vec<(usize, usize, usize)>,
    ) -> Result<Self, FemError> {
        let k = sep.len();
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
            phases: [0.0; 4],
        })
    }

    /// The same split with fresh storage in the scalar `U` (the fallback of
    /// a mixed-precision factor to double); `self` is left as it was.
    pub(crate) fn with_scalar<U: Real>(&self) -> Result<SplitFactor<U>, FemError> {
        let [h1, h2] = &self.halves;
        let halves = [h1.with_scalar()?, h2.with_scalar()?];
        SplitFactor::with_separator(halves, self.sep.clone(), self.a_ss.clone())
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
        self.halves.iter().map(|h| h.len_val()).sum::<usize>() + k * (k + 1) / 2
    }

    /// Bytes of the stored values (the halves' in `T`, L_Σ's k×k in f64).
    pub(crate) fn bytes(&self) -> usize {
        let k = self.sep.len();
        let halves = self.halves.iter().map(|h| h.len_val()).sum::<usize>();
        halves * std::mem::size_of::<T>() + k * k * std::mem::size_of::<f64>()
    }

    /// Flops Σ_{j<k} (k − j)² ≈ k³/3 of the dense L_Σ, in the measure of
    /// [`super::flops`].
    fn dense_flops(&self) -> f64 {
        (1..=self.sep.len()).map(|c| (c as f64).powi(2)).sum()
    }

    /// Estimated flops, in the measure of [`super::flops`] (Σ c² over the
    /// columns): both halves' Pᵢ columns (their S updates included) plus
    /// the dense L_Σ.
    pub(crate) fn flops(&self) -> f64 {
        self.halves.iter().map(|h| h.flops).sum::<f64>() + self.dense_flops()
    }

    /// Estimated flops of the critical path with 2 threads: the larger
    /// half, then L_Σ.
    pub(crate) fn critical_flops(&self) -> f64 {
        self.halves[0].flops.max(self.halves[1].flops) + self.dense_flops()
    }

    /// A pivot of half `i` (local index) as a position in the order
    /// (P₁, P₂, S).
    fn pivot(&self, i: usize, local: usize) -> FactorizeError {
        let (p1, p2) = (self.halves[0].n_p, self.halves[1].n_p);
        let h = &self.halves[i];
        FactorizeError::not_positive(if local < h.n_p {
            local + if i == 0 { 0 } else { p1 }
        } else {
            p1 + p2 + local - h.n_p
        })
    }

    /// Allocate and zero both halves' factor values, each on its thread, if
    /// not yet done: the first [`SplitFactor::factorize`] does.
    ///
    /// Not in the analysis, where they were before: there the zeros were
    /// written while the rest of a parameterisation's setup (its Tutte
    /// factorisation) ran on the same two cores, and the 2 × 250 MB of the
    /// 1M-triangle disk took 0.25–1.17 s of wall (first touches of fresh
    /// pages); written here, with both cores free, 0.12–0.14 s
    /// (docs/benchmarks/million.md, "Setup at stop 33"). Left to the
    /// factorisation's own first writes (untouched `calloc` pages) it was
    /// worse (2026-12-02): 3.6 s for the first factorisation against 1.5 s
    /// for the later ones; transparent huge pages (`madvise`) did not help
    /// (direct compaction on fault).
    fn reserve(&mut self) -> Result<(), FemError> {
        let [h1, h2] = &mut self.halves;
        let (r1, r2) = rayon::join(|| h1.reserve(), || h2.reserve());
        r1.and(r2)
    }

    /// Numeric factorisation of A (upper-triangular `values` on the analysed
    /// pattern): (2) for both halves at once, then (3) and L_Σ. A
    /// non-positive pivot is reported in the order (P₁, P₂, S); storage that
    /// cannot be allocated ([`SplitFactor::reserve`]) as
    /// [`FactorizeError::Symbolic`].
    pub(crate) fn factorize(&mut self, values: &[f64]) -> Result<(), FactorizeError> {
        self.reserve().map_err(FactorizeError::Symbolic)?;
        let t0 = std::time::Instant::now();
        let [h1, h2] = &mut self.halves;
        let timed = |h: &mut Half<T>| {
            let t = std::time::Instant::now();
            let r = h.factorize(values);
            (r, t.elapsed().as_secs_f64())
        };
        let ((r1, d1), (r2, d2)) = rayon::join(|| timed(h1), || timed(h2));

        if let Err(p) = r1 {
            return Err(self.pivot(0, p));
        }
        if let Err(p) = r2 {
            return Err(self.pivot(1, p));
        }
        let k = self.sep.len();
        let t1 = std::time::Instant::now();
        if k == 0 {
            self.phases = [d1, d2, t1.duration_since(t0).as_secs_f64(), 0.0];
            return Ok(());
        }
        let par = Self::dense_par(k);
        let (u1, u2) = (&self.halves[0].update, &self.halves[1].update);
        for c in 0..k {
            let at = k * c + c..k * (c + 1);
            for ((s, a), b) in self.schur[at.clone()]
                .iter_mut()
                .zip(&u1[at.clone()])
                .zip(&u2[at])
            {
                *s = (*a).into() + (*b).into();
            }
        }
        for &(c, r, slot) in &self.a_ss {
            // a_ss holds (column j, row i ≤ j): store at (max, min) = lower
            self.schur[r.max(c) + k * r.min(c)] += values[slot];
        }
        let schur = MatMut::from_column_major_slice_mut(&mut self.schur, k, k);
        cholesky_in_place(
            schur,
            Default::default(),
            par,
            MemStack::new(&mut self.dense_mem),
            Default::default(),
        )
        .map_err(|LltError::NonPositivePivot { index }| {
            FactorizeError::not_positive(self.halves[0].n_p + self.halves[1].n_p + index)
        })?;
        self.phases = [
            d1,
            d2,
            t1.duration_since(t0).as_secs_f64(),
            t1.elapsed().as_secs_f64(),
        ];
        Ok(())
    }

    /// Seconds of the last successful factorisation: half 1, half 2 (each
    /// on its thread), both halves (the join) and the separator's Schur
    /// complement and dense factorisation.
    pub(crate) fn phases(&self) -> [f64; 4] {
        self.phases
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
        let [z1, z2] = [0, 1].map(|i| &self.halves[i].work[self.halves[i].n_p..]);
        for (j, x) in self.x_s.iter_mut().enumerate() {
            *x = rhs[self.sep[j]] + z1[j].into() + z2[j].into();
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
                rhs[u] = x.into();
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
    use faer::sparse::SymbolicSparseColMatRef;
    use faer::sparse::linalg::SupernodalThreshold;
    use faer::sparse::linalg::cholesky::{
        CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky,
    };
    use rand::{Rng, SeedableRng};

    /// `zeros` gives zeros, an empty vector for 0, and a typed error (no
    /// abort) for a size no allocator can give.
    #[test]
    fn zeros_are_zero_and_an_impossible_size_is_an_error() {
        assert!(zeros::<f64>(0, "nothing").unwrap().is_empty());
        let v = zeros::<f64>(1 << 20, "a megavalue").unwrap();
        assert_eq!(v.len(), 1 << 20);
        assert!(v.iter().all(|&x| x.to_bits() == 0));
        let e = zeros::<f64>(usize::MAX / 4, "a huge factor").unwrap_err();
        assert!(
            format!("{e}").contains("out of memory for a huge factor"),
            "{e}"
        );
    }

    /// The counting-sort `sub_pattern` against a direct construction:
    /// every entry of A[u, u] once, columns sorted, slots pointing at A.
    #[test]
    fn sub_pattern_is_the_principal_submatrix() {
        let p = grid(7, 5, 2);
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let mut unknowns: Vec<usize> = (0..p.n()).filter(|_| rng.gen_bool(0.6)).collect();
        // an arbitrary local order
        for i in (1..unknowns.len()).rev() {
            unknowns.swap(i, rng.gen_range(0..=i));
        }
        let (col_ptr, row_idx, gather) = sub_pattern(&p, &unknowns);
        let n = unknowns.len();
        assert_eq!(col_ptr.len(), n + 1);
        let mut expected = Vec::new();
        for (lj, &j) in unknowns.iter().enumerate() {
            for (li, &i) in unknowns.iter().enumerate().filter(|&(li, _)| li <= lj) {
                let (r, c) = (i.min(j), i.max(j));
                let col = &p.row_idx()[p.col_ptr()[c]..p.col_ptr()[c + 1]];
                if let Ok(k) = col.binary_search(&r) {
                    expected.push((lj, li, p.col_ptr()[c] + k));
                }
            }
        }
        let mut got = Vec::new();
        for c in 0..n {
            let rows = &row_idx[col_ptr[c]..col_ptr[c + 1]];
            assert!(rows.windows(2).all(|w| w[0] < w[1]), "column {c} sorted");
            for e in col_ptr[c]..col_ptr[c + 1] {
                got.push((c, row_idx[e], gather[e]));
            }
        }
        expected.sort_unstable();
        assert_eq!(got, expected);
    }

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
            let range = p.col_ptr()[j]..p.col_ptr()[j + 1];
            for (ve, &i) in v[range.clone()].iter_mut().zip(&p.row_idx()[range]) {
                if i != j {
                    *ve = rng.gen_range(-1.0..1.0);
                    row_sum[i] += f64::abs(*ve);
                    row_sum[j] += f64::abs(*ve);
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

    /// The split of `p` from faer's AMD analysis made supernodal whatever
    /// its size (below 100 unknowns, fundamental supernodes: relaxation would
    /// merge a tiny matrix into one supernode, which cannot be split).
    pub(crate) fn analyse<T: Real>(p: &Pattern) -> Option<SplitFactor<T>> {
        let n = p.n();
        let a = SymbolicSparseColMatRef::new_checked(n, n, p.col_ptr(), None, p.row_idx());
        let mut params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        if n < 100 {
            params.supernodal_params.relax = None;
        }
        let symbolic =
            factorize_symbolic_cholesky(a, faer::Side::Upper, SymmetricOrdering::Amd, params)
                .unwrap();
        SplitFactor::analyse(p, &symbolic, true).unwrap()
    }

    /// No entry of A couples the two halves' P parts.
    fn halves_are_uncoupled<T: Real>(p: &Pattern, split: &SplitFactor<T>) {
        let mut side = vec![2usize; p.n()];
        for (i, h) in split.halves.iter().enumerate() {
            h.unknowns[..h.n_p].iter().for_each(|&u| side[u] = i);
        }
        for j in 0..p.n() {
            for &i in &p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]] {
                assert!(
                    side[i] == 2 || side[j] == 2 || side[i] == side[j],
                    "A[{i},{j}]"
                );
            }
        }
        assert!(split.halves.iter().all(|h| h.n_p > 0));
    }

    /// Split solve vs the plain (double) factorisation on random SPD
    /// values: to rounding in double, to single precision's (these
    /// matrices are well conditioned) with f32 halves.
    fn agrees_with_plain<T: Real>(p: &Pattern, expect_separator: bool) {
        let tol = if T::SINGLE { 1e-5 } else { 1e-12 };
        let mut split = analyse::<T>(p).unwrap_or_else(|| panic!("not splittable: n = {}", p.n()));
        halves_are_uncoupled(p, &split);
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
            assert!(res <= tol, "relative residual {res:e}");
            let scale = xp.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            let diff = xs
                .iter()
                .zip(&xp)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(diff <= tol * scale, "split vs plain: {diff:e}");
            if T::SINGLE {
                assert!(res >= 1e-10, "single precision shows: {res:e}");
            }
        }
    }

    #[test]
    fn split_solves_agree_with_the_plain_factorisation() {
        agrees_with_plain::<f64>(&grid(30, 20, 2), true);
        agrees_with_plain::<f64>(&grid(12, 9, 3), true);
        agrees_with_plain::<f64>(&grid(3, 2, 1), true);
    }

    #[test]
    fn single_precision_halves_agree_to_single_precision() {
        agrees_with_plain::<f32>(&grid(30, 20, 2), true);
        agrees_with_plain::<f32>(&grid(12, 9, 3), true);
        agrees_with_plain::<f32>(&two_grids(7, 6, 2).0, false);
    }

    #[test]
    fn an_empty_separator_splits_disconnected_halves() {
        agrees_with_plain::<f64>(&two_grids(7, 6, 2).0, false);
    }

    #[test]
    fn an_unsplittable_graph_is_reported_not_forced() {
        assert!(analyse::<f64>(&triangle().0).is_none());
    }

    /// The fallback of a mixed factor: `with_scalar` keeps the structure, so
    /// the converted split factorises and solves to the same bits as a split
    /// analysed in double.
    #[test]
    fn a_single_split_turned_double_is_the_double_split() {
        let p = grid(30, 20, 2);
        let v = random_spd(&p, 5);
        let b: Vec<f64> = (0..p.n()).map(|i| (0.3 * i as f64).sin()).collect();
        let solve = |s: &mut SplitFactor<f64>| {
            s.factorize(&v).ok().unwrap();
            let mut x = b.clone();
            s.solve_in_place(&mut x);
            x.iter().map(|a| a.to_bits()).collect::<Vec<_>>()
        };
        let mut single = analyse::<f32>(&p).unwrap();
        single.factorize(&v).ok().unwrap();
        let mut converted = single.with_scalar::<f64>().unwrap();
        assert_eq!(solve(&mut converted), solve(&mut analyse(&p).unwrap()));
        let halves: usize = single.halves.iter().map(|h| h.len_val()).sum();
        assert_eq!(converted.bytes(), single.bytes() + 4 * halves);
    }

    /// The analysis allocates no factor values; the first factorisation
    /// does, all of them, and later ones reuse them.
    #[test]
    fn the_first_factorisation_allocates_the_factor_values() {
        let p = grid(30, 20, 2);
        let mut split = analyse::<f32>(&p).unwrap();
        let stored = |s: &SplitFactor<f32>| s.halves.each_ref().map(|h| h.stored());
        assert_eq!(stored(&split), [0, 0]);
        let want = split.halves.each_ref().map(|h| h.len_val());
        assert!(want.iter().all(|&l| l > 0));
        split.factorize(&random_spd(&p, 1)).ok().unwrap();
        assert_eq!(stored(&split), want);
        let before = split.halves.each_ref().map(|h| h.stored_at());
        split.factorize(&random_spd(&p, 2)).ok().unwrap();
        assert_eq!(split.halves.each_ref().map(|h| h.stored_at()), before);
    }

    #[test]
    fn an_indefinite_matrix_is_reported_in_either_half_or_the_separator() {
        an_indefinite_matrix_is_reported::<f64>();
        an_indefinite_matrix_is_reported::<f32>();
    }

    fn an_indefinite_matrix_is_reported<T: Real>() {
        let p = grid(20, 10, 2);
        let mut split = analyse::<T>(&p).unwrap();
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
        same_bits_run_to_run::<f64>();
        same_bits_run_to_run::<f32>();
    }

    fn same_bits_run_to_run<T: Real>() {
        let p = grid(40, 30, 2);
        let v = random_spd(&p, 3);
        let b: Vec<f64> = (0..p.n()).map(|i| (0.1 * i as f64).cos()).collect();
        let run = || {
            let mut s = analyse::<T>(&p).unwrap();
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
