//! Sparse Cholesky (LLᵀ) with faer's low-level API.
//!
//! [`CholeskyFactor::analyze_with`] runs the symbolic analysis once per
//! pattern (the fill-reducing ordering of [`CholeskyParams::ordering`],
//! elimination tree, simplicial or supernodal structure chosen by faer from
//! the flop ratio) and fixes the thread policy ([`ThreadPolicy`]); a split
//! factor ([`ThreadPolicy::Split`]) is read off the group graph's
//! elimination tree and only its halves are analysed by faer. Each Newton step then calls
//! [`CholeskyFactor::factorize`], which writes the numeric factor into the
//! preallocated `l_values` using a preallocated scratch buffer, and
//! [`CholeskyFactor::solve_in_place`]. The factor keeps a copy of the
//! analysed pattern: `factorize` with a different pattern re-analyses (never
//! reads the old structure with new indices) and counts it, so the counters
//! let tests assert that the symbolic analysis really is reused.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use std::time::Instant;

use faer::perm::PermRef;
use faer::{Conj, MatMut, Par, Side};

use serde::{Deserialize, Serialize};

mod grouped;
mod half;
mod precision;
mod real;
mod split;
mod threads;
mod tree;

pub use precision::{FactorPrecision, MIXED_MIN_FLOPS};
pub use threads::{REPROBE_EVERY, ThreadPolicy};

/// [`ecc_util::clear_upper_simd`] on this thread and, when faer's kernels
/// ran on rayon's workers (`pool`), on every worker of the pool: the threads
/// that assemble the next Hessian.
fn clear_simd(pool: bool) {
    ecc_util::clear_upper_simd();
    if pool && rayon::current_num_threads() > 1 {
        rayon::broadcast(|_| ecc_util::clear_upper_simd());
    }
}

/// [`ThreadPolicy::Split`] splits a factorisation whose estimated flops
/// (Σ c² of the unsplit factor: `tree::Tree::total_flops`) reach this; below,
/// the two-thread overhead (the separator's dense block, joins) does not pay
/// (docs/benchmarks/ordering.md, "Tree-level parallel factorisation").
pub const SPLIT_MIN_FLOPS: f64 = 5e7;

use super::ordering::{Coordinates, FillOrdering, Ordered, ordered};
use crate::error::FemError;
use crate::pattern::Pattern;
use precision::Split;
use threads::ThreadChooser;
use tree::Tree;

/// How [`CholeskyFactor`] orders and threads its factorisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CholeskyParams {
    /// Fill-reducing ordering of the symbolic analysis.
    pub ordering: FillOrdering,
    /// Threads of the numeric factorisation and the solves.
    pub threads: ThreadPolicy,
    /// Scalar of a split factor's halves ([`FactorPrecision`]; factors that
    /// are not split are always double).
    #[serde(default)]
    pub precision: FactorPrecision,
}

/// The numeric factorisation hit a non-positive pivot (matrix not numerically PD).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotPositiveDefinite {
    /// Column (in the permuted order) where it failed.
    pub pivot: usize,
}

/// Why [`CholeskyFactor::factorize`] produced no factor.
#[derive(Clone, Debug, PartialEq)]
pub enum FactorizeError {
    /// A non-positive pivot.
    NotPositiveDefinite(NotPositiveDefinite),
    /// The pattern differed from the analysed one and its new symbolic
    /// analysis failed, or the factor's values could not be allocated.
    Symbolic(FemError),
}

impl FactorizeError {
    /// A non-positive pivot at `pivot` (a column in the permuted order).
    pub(crate) fn not_positive(pivot: usize) -> Self {
        FactorizeError::NotPositiveDefinite(NotPositiveDefinite { pivot })
    }
}

/// Symbolic structure, factor values and scratch for one pattern.
pub struct CholeskyFactor {
    /// The factorisation of the analysed pattern.
    kind: Kind,
    /// The [`Pattern::id`] of the pattern `kind` was analysed for (0: none).
    analysed: u64,
    /// As asked (the ordering may be `Auto`; reanalyses resolve it again).
    params: CholeskyParams,
    /// The concrete ordering of the current analysis.
    ordering: FillOrdering,
    /// Positions of the unknowns for [`FillOrdering::Geometric`] (kept for
    /// reanalyses).
    coords: Option<Coordinates>,
    factored: bool,
    /// A mixed factor met a matrix indefinite in double too (its later
    /// single-precision breakdowns are reported without a double retry).
    indefinite_seen: bool,
    symbolic_analyses: usize,
    numeric_factorizations: usize,
}

/// How the analysed pattern is factorised.
enum Kind {
    /// faer's supernodal factorisation of the whole matrix.
    Plain(Box<Plain>),
    /// The two-way split factor ([`ThreadPolicy::Split`]): every
    /// factorisation and solve goes through it.
    Split(Box<Split>),
    /// A reanalysis failed: nothing to factorise with until the next one.
    Missing,
}

/// faer's symbolic analysis of the whole matrix, the factor values and the
/// scratch it sizes.
struct Plain {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    mem: MemBuffer,
    threads: ThreadChooser,
    /// The parallelism of the last numeric factorisation (used by the solves).
    par: Par,
}

/// The split factor when `params` asks for it, the pool has two threads and
/// the plain factorisation (`symbolic`) is supernodal and large enough.
fn split_for(
    pattern: &Pattern,
    params: CholeskyParams,
    symbolic: &SymbolicCholesky<usize>,
) -> Result<Option<Split>, FemError> {
    let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
        return Ok(None);
    };
    let plain = flops(symbolic);
    if !splits(params) || plain < SPLIT_MIN_FLOPS {
        return Ok(None);
    }
    let perm = symbolic.perm().map(|p| p.arrays().0);
    Split::analyse(
        pattern,
        perm,
        &Tree::of_supernodal(sn),
        params.precision,
        plain,
    )
}

/// Whether `params` and the pool ask for a split factor (if it pays).
fn splits(params: CholeskyParams) -> bool {
    params.threads == ThreadPolicy::Split && rayon::current_num_threads() >= 2
}

/// The split factor read off the elimination tree of the group graph
/// ([`Tree::of_groups`]) when `params` asks for it and it pays: no
/// symbolic factorisation of the whole matrix (on the 1M-triangle disk,
/// faer's took 0.6 s of setup only to find the split).
fn group_split(
    pattern: &Pattern,
    params: CholeskyParams,
    ordered: &Ordered,
) -> Result<Option<Split>, FemError> {
    let Some(groups) = ordered.groups.as_ref().filter(|_| splits(params)) else {
        return Ok(None);
    };
    let tree = Tree::of_groups(&*groups.elimination()?);
    let plain = tree.total_flops();
    if plain < SPLIT_MIN_FLOPS {
        return Ok(None);
    }
    Split::analyse(
        pattern,
        ordered.perm.as_deref(),
        &tree,
        params.precision,
        plain,
    )
}

/// Symbolic analysis of the upper-triangular `pattern` with the ordering of
/// `params`; the factor values and all scratch are allocated here, once per
/// pattern, sized for the thread policy. Where the ordering is by groups
/// ([`Ordered::groups`]) the split is decided on the group graph's tree and
/// faer analyses the whole matrix only when it is not split; otherwise
/// (faer's own AMD) the split is read off faer's supernodal tree.
fn analysis(
    pattern: &Pattern,
    params: CholeskyParams,
    coords: Option<&Coordinates>,
) -> Result<(Kind, FillOrdering), FemError> {
    let n = pattern.n();
    let ordered = ordered(pattern, params.ordering, coords)?;
    if let Some(split) = group_split(pattern, params, &ordered)? {
        return Ok((Kind::Split(Box::new(split)), ordered.used));
    }
    // SAFETY-free: the pattern invariants (sorted, in-bounds rows) are
    // checked here, where faer reads the whole pattern (the split halves
    // read it through their vertex graphs and slots; on the 1M-triangle
    // disk the check took 0.04 s of setup)
    let a = SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
    let inv = ordered
        .perm
        .as_deref()
        .map(ecc_mesh::dissection::inverse_permutation);
    let ordering = match (&ordered.perm, &inv) {
        (Some(p), Some(i)) => SymmetricOrdering::Custom(PermRef::new_checked(p, i, n)),
        _ => SymmetricOrdering::Amd,
    };
    let symbolic = factorize_symbolic_cholesky(a, Side::Upper, ordering, symbolic_params())
        .map_err(|e| FemError::Symbolic(format!("{e:?}")))?;
    if ordered.groups.is_none()
        && let Some(split) = split_for(pattern, params, &symbolic)?
    {
        return Ok((Kind::Split(Box::new(split)), ordered.used));
    }
    let threads = ThreadChooser::new(
        params.threads,
        matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)),
    );
    let req = StackReq::any_of(&[Par::Seq, Par::rayon(0)].map(|par| {
        StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, par),
        ])
    }));
    let mem = MemBuffer::try_new(req)
        .map_err(|_| FemError::Symbolic("out of memory for scratch".into()))?;
    let len = symbolic.len_val();
    let l_values = split::zeros(len, &format!("a factor of {len} values"))?;
    let plain = Plain {
        symbolic,
        l_values,
        mem,
        threads,
        par: Par::Seq,
    };
    Ok((Kind::Plain(Box::new(plain)), ordered.used))
}

/// faer's symbolic parameters: always supernodal. faer picks its simplicial
/// factorisation below ≈ 80 flops per stored value of L (Σ c² / nnz(L)),
/// which on the meshes measured (2026-12-02, one thread, block AMD) is
/// 1.4–2.8× slower than its supernodal one: bar-2523 (tets, n = 2658)
/// 3.7 → 1.4 ms, hand_1_i_f5000 4.2 → 2.0 ms, a 1.9k-triangle disk
/// 5.0 → 1.8 ms, a 600-triangle disk 0.3 → 0.2 ms; where faer already chose
/// supernodal nothing changes. (CHOLMOD on hand_1_i_f5000: 3.5–4.8 ms.)
fn symbolic_params() -> CholeskySymbolicParams<'static> {
    CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    }
}

/// Estimated flops of one numeric factorisation, Σ_j c_j² over the column
/// counts c_j of L (supernodal: column k of a supernode of width w with r
/// off-diagonal rows has c = w − k + r).
fn flops(symbolic: &SymbolicCholesky<usize>) -> f64 {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => s
            .col_ptr()
            .windows(2)
            .map(|w| ((w[1] - w[0]) as f64).powi(2))
            .sum(),
        SymbolicCholeskyRaw::Supernodal(s) => (0..s.n_supernodes())
            .map(|k| {
                let w = s.supernode_end()[k] - s.supernode_begin()[k];
                let r = s.supernode(k).pattern().len();
                (0..w).map(|c| ((w - c + r) as f64).powi(2)).sum::<f64>()
            })
            .sum(),
    }
}

impl CholeskyFactor {
    /// Symbolic analysis of the upper-triangular pattern with the default
    /// [`CholeskyParams`]; allocates the factor storage and all scratch once.
    pub fn analyze(pattern: &Pattern) -> Result<Self, FemError> {
        Self::analyze_with(pattern, CholeskyParams::default())
    }

    /// Symbolic analysis with the ordering and thread policy of `params`.
    pub fn analyze_with(pattern: &Pattern, params: CholeskyParams) -> Result<Self, FemError> {
        Self::analyze_at(pattern, params, None)
    }

    /// [`CholeskyFactor::analyze_with`] with the position of every unknown
    /// (`coords.len() == pattern.n()`), which [`FillOrdering::Geometric`]
    /// needs (the other orderings ignore it).
    pub fn analyze_at(
        pattern: &Pattern,
        params: CholeskyParams,
        coords: Option<Coordinates>,
    ) -> Result<Self, FemError> {
        let (kind, ordering) = analysis(pattern, params, coords.as_ref())?;
        Ok(CholeskyFactor {
            kind,
            analysed: pattern.id(),
            params,
            ordering,
            coords,
            factored: false,
            indefinite_seen: false,
            symbolic_analyses: 1,
            numeric_factorizations: 0,
        })
    }

    /// Whether `pattern` is the one the symbolic analysis was done for (it
    /// or a clone: [`Pattern::id`]; an equal pattern built apart is
    /// analysed again).
    pub fn is_for(&self, pattern: &Pattern) -> bool {
        self.analysed == pattern.id()
    }

    /// Redo the symbolic analysis for a new pattern (counted).
    fn reanalyze(&mut self, pattern: &Pattern) -> Result<(), FemError> {
        // drop the old factor first: the new one may be as large; until an
        // analysis succeeds there is no pattern to factorise with
        self.kind = Kind::Missing;
        self.analysed = 0;
        self.factored = false;
        // a dissection computed for the old pattern's graph need not suit
        // the new one's
        if let Some(c) = &mut self.coords {
            c.dissection = None;
        }
        let (kind, ordering) = analysis(pattern, self.params, self.coords.as_ref())?;
        self.ordering = ordering;
        self.kind = kind;
        self.analysed = pattern.id();
        self.factored = false;
        self.symbolic_analyses += 1;
        Ok(())
    }

    /// Number of stored values of L (of both halves and the dense separator
    /// factor for a split factor).
    pub fn factor_nnz(&self) -> usize {
        match &self.kind {
            Kind::Plain(p) => p.symbolic.len_val(),
            Kind::Split(s) => s.nnz(),
            Kind::Missing => 0,
        }
    }

    /// Memory taken by the factor values, in bytes (a mixed split factor's
    /// halves at 4 bytes a value).
    pub fn factor_bytes(&self) -> usize {
        match &self.kind {
            Kind::Plain(p) => p.symbolic.len_val() * std::mem::size_of::<f64>(),
            Kind::Split(s) => s.bytes(),
            Kind::Missing => 0,
        }
    }

    /// Whether the factor is a mixed-precision split ([`FactorPrecision`]):
    /// its solves are then accurate to about κ·2⁻²⁴ only, and
    /// [`crate::linear::LinearSystem::solve`] refines them by CG.
    pub fn is_mixed(&self) -> bool {
        matches!(&self.kind, Kind::Split(s) if s.is_mixed())
    }

    /// The precision of the factor now: [`FactorPrecision::Mixed`] for a
    /// mixed split ([`CholeskyFactor::is_mixed`]), otherwise double (not
    /// split, asked double, or fallen back to double).
    pub fn precision(&self) -> FactorPrecision {
        if self.is_mixed() {
            FactorPrecision::Mixed
        } else {
            FactorPrecision::Double
        }
    }

    /// Whether a mixed factor has met a matrix indefinite in double too.
    #[cfg(test)]
    pub(crate) fn indefinite_seen(&self) -> bool {
        self.indefinite_seen
    }

    /// Make a mixed-precision factor double for good (same structure, fresh
    /// storage, to be factorised again); nothing for any other factor. On an
    /// allocation failure the factor stays as it was.
    pub fn to_double(&mut self) -> Result<(), FemError> {
        if let Kind::Split(split) = &self.kind
            && let Some(double) = split.double()?
        {
            self.kind = Kind::Split(Box::new(double));
            self.factored = false;
        }
        Ok(())
    }

    /// Estimated floating-point operations of one numeric factorisation,
    /// Σ_j c_j² over the column counts c_j of L (supernodal: column k of a
    /// supernode of width w with r off-diagonal rows has c = w − k + r).
    /// A split factor counts both halves' own columns (their updates of the
    /// separator included) and ≈ k³/3 for the dense L_Σ (k separator
    /// unknowns).
    pub fn factor_flops(&self) -> f64 {
        match &self.kind {
            Kind::Plain(p) => flops(&p.symbolic),
            Kind::Split(s) => s.flops(),
            Kind::Missing => 0.0,
        }
    }

    /// For a split factor ([`ThreadPolicy::Split`]): the separator's number
    /// of unknowns and the estimated flops of the critical path on two
    /// threads (the larger half, then L_Σ); `None` when the factorisation is
    /// not split.
    pub fn split(&self) -> Option<(usize, f64)> {
        match &self.kind {
            Kind::Split(s) => Some((s.separator_len(), s.critical_flops())),
            _ => None,
        }
    }

    /// The ordering and thread policy this factor was analysed with, the
    /// ordering concrete (a requested [`FillOrdering::Auto`] resolved).
    pub fn params(&self) -> CholeskyParams {
        CholeskyParams {
            ordering: self.ordering,
            ..self.params
        }
    }

    /// For a split factor, the seconds of the phases of its last successful
    /// factorisation: half 1 and half 2 (each on one thread), both halves
    /// (their `rayon::join`), and the separator's Schur complement and dense
    /// factor; `None` when the factorisation is not split.
    pub fn split_phases(&self) -> Option<[f64; 4]> {
        match &self.kind {
            Kind::Split(s) => Some(s.phases()),
            _ => None,
        }
    }

    /// Whether the last numeric factorisation (and so the solves) ran on
    /// rayon's threads, as the [`ThreadPolicy`] chose.
    pub fn is_parallel(&self) -> bool {
        match &self.kind {
            Kind::Plain(p) => !matches!(p.par, Par::Seq),
            Kind::Split(_) => true,
            Kind::Missing => false,
        }
    }

    /// Number of supernodes and the widest one (columns) of a plain
    /// factor, or `None` for a simplicial or split one.
    pub fn supernodes(&self) -> Option<(usize, usize)> {
        let Kind::Plain(p) = &self.kind else {
            return None;
        };
        match p.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(_) => None,
            SymbolicCholeskyRaw::Supernodal(s) => {
                let widest = (0..s.n_supernodes())
                    .map(|k| s.supernode_end()[k] - s.supernode_begin()[k])
                    .max()
                    .unwrap_or(0);
                Some((s.n_supernodes(), widest))
            }
        }
    }

    /// Whether the factor is supernodal (a split factor's halves always are).
    pub fn is_supernodal(&self) -> bool {
        match &self.kind {
            Kind::Plain(p) => matches!(p.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)),
            Kind::Split(_) => true,
            Kind::Missing => false,
        }
    }

    /// How many symbolic analyses this factor has done: 1 from
    /// [`CholeskyFactor::analyze`], plus one each time
    /// [`CholeskyFactor::factorize`] met a different pattern.
    pub fn symbolic_analyses(&self) -> usize {
        self.symbolic_analyses
    }

    /// How many numeric factorisations were attempted.
    pub fn numeric_factorizations(&self) -> usize {
        self.numeric_factorizations
    }

    /// Numeric LLᵀ of the matrix with this pattern and upper-triangular
    /// `values`. A pattern other than the analysed one is analysed first
    /// (and counted in [`CholeskyFactor::symbolic_analyses`]).
    pub fn factorize(&mut self, pattern: &Pattern, values: &[f64]) -> Result<(), FactorizeError> {
        if !self.is_for(pattern) {
            self.reanalyze(pattern).map_err(FactorizeError::Symbolic)?;
        }
        self.numeric_factorizations += 1;
        self.factored = false;
        let indefinite_seen = &mut self.indefinite_seen;
        match &mut self.kind {
            Kind::Plain(p) => p.factorize(pattern, values),
            Kind::Split(split) => factorize_split(split, values, indefinite_seen),
            Kind::Missing => Err(FactorizeError::Symbolic(FemError::Symbolic(
                "no symbolic analysis to factorise with (the last one failed)".into(),
            ))),
        }?;
        self.factored = true;
        Ok(())
    }

    /// Solve A x = rhs in place with the last successful factorisation.
    /// Returns `false` (leaving `rhs` untouched) if there is none.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> bool {
        if !self.factored {
            return false;
        }
        match &mut self.kind {
            Kind::Plain(p) => p.solve_in_place(rhs),
            Kind::Split(split) => {
                split.solve_in_place(rhs);
                clear_simd(true);
            }
            Kind::Missing => return false,
        }
        true
    }
}

/// Numeric factorisation of a split factor: a single-precision breakdown
/// is retried in double once per factor (module docs of `precision`).
fn factorize_split(
    split: &mut Split,
    values: &[f64],
    indefinite_seen: &mut bool,
) -> Result<(), FactorizeError> {
    let mut result = split.factorize(values);
    let broke_down = matches!(result, Err(FactorizeError::NotPositiveDefinite(_)));
    if broke_down && split.is_mixed() && !*indefinite_seen {
        // single precision broke down: the same matrix in double tells a
        // breakdown of precision (double succeeds: stay double) from an
        // indefinite matrix (double fails too: stay mixed, and report later
        // breakdowns as they are)
        if let Some(mut double) = split.double().map_err(FactorizeError::Symbolic)? {
            result = double.factorize(values);
            match result {
                Ok(()) => *split = double,
                Err(FactorizeError::NotPositiveDefinite(_)) => *indefinite_seen = true,
                Err(FactorizeError::Symbolic(_)) => {}
            }
        }
    }
    clear_simd(true);
    result
}

impl Plain {
    /// faer's numeric LLᵀ of `values` on the analysed `pattern`.
    fn factorize(&mut self, pattern: &Pattern, values: &[f64]) -> Result<(), FactorizeError> {
        let n = pattern.n();
        // SAFETY: the caller checked `is_for`: this exact pattern was
        // validated by `new_checked` in its symbolic analysis.
        let sym = unsafe {
            SymbolicSparseColMatRef::new_unchecked(n, n, pattern.col_ptr(), None, pattern.row_idx())
        };
        let a = SparseColMatRef::new(sym, values);
        let stack = MemStack::new(&mut self.mem);
        self.par = self.threads.next();
        let start = Instant::now();
        let result = self.symbolic.factorize_numeric_llt::<f64>(
            &mut self.l_values,
            a,
            Side::Upper,
            Default::default(),
            self.par,
            stack,
            Default::default(),
        );
        clear_simd(!matches!(self.par, Par::Seq));
        match result {
            Ok(_) => {
                self.threads.record(self.par, start.elapsed().as_secs_f64());
                Ok(())
            }
            Err(LltError::NonPositivePivot { index }) => Err(FactorizeError::not_positive(index)),
        }
    }

    /// Solve with the last numeric factor.
    fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let n = rhs.len();
        let llt = LltRef::<'_, usize, f64>::new(&self.symbolic, &self.l_values);
        let stack = MemStack::new(&mut self.mem);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            self.par,
            stack,
        );
        clear_simd(!matches!(self.par, Par::Seq));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::pattern::{StencilSet, build};

    /// A rayon pool of `threads` threads.
    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// Path graph 0-1-2-…: 1D Laplacian + I, tridiagonal, SPD.
    fn path(n: usize) -> (Pattern, Vec<f64>) {
        let edges: Vec<usize> = (0..n - 1).flat_map(|i| [i, i + 1]).collect();
        let dofs = DofMap::all_free(n, 1).unwrap();
        let (p, _) = build(
            &[StencilSet {
                name: "e",
                arity: 2,
                stencils: &edges,
            }],
            &dofs,
        )
        .unwrap();
        let mut v = vec![0.0; p.nnz()];
        for j in 0..n {
            v[p.diag_slot(j)] = 3.0;
            if j > 0 {
                v[p.slot(j - 1, j).unwrap()] = -1.0;
            }
        }
        (p, v)
    }

    #[test]
    fn solves_and_reuses_symbolic() {
        let n = 50;
        let (p, v) = path(n);
        let mut f = CholeskyFactor::analyze(&p).unwrap();
        let xs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut b = vec![0.0; n];
        for step in 0..3 {
            let scaled: Vec<f64> = v.iter().map(|a| a * (1.0 + step as f64)).collect();
            p.sym_matvec(&scaled, &xs, &mut b);
            f.factorize(&p, &scaled).unwrap();
            assert!(f.solve_in_place(&mut b));
            for (a, e) in b.iter().zip(&xs) {
                assert!((a - e).abs() < 1e-12);
            }
        }
        assert_eq!(f.symbolic_analyses(), 1);
        assert_eq!(f.numeric_factorizations(), 3);
    }

    /// A clone of the analysed pattern is the same pattern (no analysis); an
    /// equal one built apart is analysed again, counted, and solves.
    #[test]
    fn a_pattern_is_matched_by_its_id() {
        let (p, v) = path(30);
        let mut f = CholeskyFactor::analyze(&p).unwrap();
        assert!(f.is_for(&p.clone()));
        f.factorize(&p.clone(), &v).unwrap();
        assert_eq!(f.symbolic_analyses(), 1);
        let (q, w) = path(30);
        assert_eq!((q.col_ptr(), q.row_idx()), (p.col_ptr(), p.row_idx()));
        assert_ne!(q.id(), p.id());
        assert!(!f.is_for(&q));
        f.factorize(&q, &w).unwrap();
        assert_eq!(f.symbolic_analyses(), 2);
        let mut x = vec![1.0; 30];
        assert!(f.solve_in_place(&mut x));
        let mut ax = vec![0.0; 30];
        q.sym_matvec(&w, &x, &mut ax);
        assert!(ax.iter().all(|a| (a - 1.0).abs() < 1e-12));
    }

    #[test]
    fn a_changed_pattern_is_analysed_again_and_counted() {
        let (p, v) = path(30);
        let mut f = CholeskyFactor::analyze(&p).unwrap();
        f.factorize(&p, &v).unwrap();
        f.factorize(&p, &v).unwrap();
        assert_eq!(f.symbolic_analyses(), 1, "same pattern: no new analysis");
        let (q, w) = path(40);
        assert!(!f.is_for(&q));
        f.factorize(&q, &w).unwrap();
        assert_eq!(f.symbolic_analyses(), 2, "new pattern: one new analysis");
        assert!(f.is_for(&q));
        // the new factor solves the new system
        let xs: Vec<f64> = (0..40).map(|i| (0.3 * i as f64).cos()).collect();
        let mut b = vec![0.0; 40];
        q.sym_matvec(&w, &xs, &mut b);
        assert!(f.solve_in_place(&mut b));
        for (a, e) in b.iter().zip(&xs) {
            assert!((a - e).abs() < 1e-12);
        }
        assert_eq!(f.numeric_factorizations(), 3);
    }

    #[test]
    fn indefinite_is_reported() {
        let (p, mut v) = path(10);
        v[p.diag_slot(4)] = -5.0;
        let mut f = CholeskyFactor::analyze(&p).unwrap();
        assert!(matches!(
            f.factorize(&p, &v),
            Err(FactorizeError::NotPositiveDefinite(_))
        ));
        let mut b = vec![1.0; 10];
        assert!(!f.solve_in_place(&mut b));
        assert_eq!(b, vec![1.0; 10]);
    }

    /// A diagonally dominant SPD matrix on `p`: off-diagonals −1.
    fn dominant(p: &Pattern) -> Vec<f64> {
        let mut v = vec![-1.0; p.nnz()];
        for j in 0..p.n() {
            v[p.diag_slot(j)] = 1.0 + 30.0;
        }
        v
    }

    #[test]
    fn every_ordering_and_policy_solves_the_same_system() {
        let p = crate::linear::ordering::tests::grid(9, 7, 2);
        let coords: Coordinates = crate::linear::ordering::tests::grid_coords(9, 7, 2).into();
        let v = dominant(&p);
        let xs: Vec<f64> = (0..p.n()).map(|i| (0.7 * i as f64).sin()).collect();
        let mut b = vec![0.0; p.n()];
        p.sym_matvec(&v, &xs, &mut b);
        for ordering in FillOrdering::ALL.into_iter().filter(|o| o.is_available()) {
            for threads in ThreadPolicy::ALL {
                let params = CholeskyParams {
                    ordering,
                    threads,
                    ..Default::default()
                };
                let mut f = CholeskyFactor::analyze_at(&p, params, Some(coords.clone())).unwrap();
                assert_eq!(f.params(), params);
                for _ in 0..3 {
                    f.factorize(&p, &v).unwrap();
                    let mut x = b.clone();
                    assert!(f.solve_in_place(&mut x));
                    let err = x
                        .iter()
                        .zip(&xs)
                        .map(|(a, e)| (a - e).abs())
                        .fold(0.0, f64::max);
                    assert!(err < 1e-12, "{params:?}: {err}");
                }
                assert_eq!(f.symbolic_analyses(), 1, "{params:?}");
            }
        }
    }

    #[test]
    fn custom_permutations_follow_faers_convention() {
        // dim 1: no two unknowns share a closed neighbourhood, so block AMD is
        // faer's AMD passed back as a custom permutation; a permutation read
        // the wrong way round would change the fill.
        let p = crate::linear::ordering::tests::grid(12, 9, 1);
        let fill = |ordering| {
            let params = CholeskyParams {
                ordering,
                ..Default::default()
            };
            CholeskyFactor::analyze_with(&p, params)
                .unwrap()
                .factor_nnz()
        };
        assert_eq!(fill(FillOrdering::BlockAmd), fill(FillOrdering::Amd));
        let q = crate::linear::ordering::tests::grid(12, 9, 2);
        let two = |ordering| {
            let params = CholeskyParams {
                ordering,
                ..Default::default()
            };
            CholeskyFactor::analyze_with(&q, params)
                .unwrap()
                .factor_nnz()
        };
        assert!(two(FillOrdering::BlockAmd) <= two(FillOrdering::Amd));
    }

    #[test]
    fn auto_threads_times_one_sequential_and_one_parallel_factorisation() {
        let p = crate::linear::ordering::tests::grid(100, 100, 2);
        let v = dominant(&p);
        let pool = pool(2);
        pool.install(|| {
            let params = CholeskyParams {
                threads: ThreadPolicy::Auto,
                ..Default::default()
            };
            let mut f = CholeskyFactor::analyze_with(&p, params).unwrap();
            assert!(
                f.is_supernodal(),
                "the grid must be supernodal for this test"
            );
            f.factorize(&p, &v).unwrap();
            assert!(!f.is_parallel(), "first probe: sequential");
            f.factorize(&p, &v).unwrap();
            assert!(f.is_parallel(), "second probe: parallel");
            let mut x = vec![1.0; p.n()];
            assert!(f.solve_in_place(&mut x));
            let mut d = CholeskyFactor::analyze(&p).unwrap();
            assert_eq!(d.params().threads, ThreadPolicy::Split, "the default");
            for _ in 0..3 {
                d.factorize(&p, &v).unwrap();
                // the default never uses faer's parallel kernels: it splits
                // (this grid is large enough) or runs on one thread
                assert!(matches!(d.kind, Kind::Split(_)) && d.split().is_some());
            }
        });
    }

    /// faer's AVX-512 kernels leave the vector registers' upper halves in
    /// use; every factorisation and solve must leave them cleared on the
    /// calling thread and on the pool's workers (`clear_simd`), or the
    /// scalar assembly that follows there runs up to 2× slower
    /// (docs/benchmarks/threads.md §0).
    #[test]
    fn factorisations_and_solves_leave_the_vector_unit_clean_on_every_thread() {
        let p = crate::linear::ordering::tests::grid(100, 100, 2);
        let v = dominant(&p);
        let pool = pool(2);
        for threads in [
            ThreadPolicy::Split,
            ThreadPolicy::Sequential,
            ThreadPolicy::Parallel,
        ] {
            pool.install(|| {
                let params = CholeskyParams {
                    threads,
                    ..Default::default()
                };
                let mut f = CholeskyFactor::analyze_with(&p, params).unwrap();
                let dirty = || {
                    let workers: Vec<Option<bool>> =
                        rayon::broadcast(|_| ecc_util::simd::upper_simd_in_use());
                    let mut all = workers;
                    all.push(ecc_util::simd::upper_simd_in_use());
                    all
                };
                f.factorize(&p, &v).unwrap();
                let after_factor = dirty();
                let mut x = vec![1.0; p.n()];
                assert!(f.solve_in_place(&mut x));
                let after_solve = dirty();
                for (what, state) in [("factorisation", after_factor), ("solve", after_solve)] {
                    assert!(
                        state.iter().all(|d| *d != Some(true)),
                        "{threads:?}: upper vector state in use after the {what}: {state:?}"
                    );
                }
            });
        }
    }

    #[test]
    fn the_split_policy_splits_large_factors_on_two_threads_only() {
        let p = crate::linear::ordering::tests::grid(100, 100, 2);
        let v = dominant(&p);
        let xs: Vec<f64> = (0..p.n()).map(|i| (0.01 * i as f64).sin()).collect();
        let mut b = vec![0.0; p.n()];
        p.sym_matvec(&v, &xs, &mut b);
        let params = CholeskyParams {
            threads: ThreadPolicy::Split,
            precision: FactorPrecision::Double,
            ..Default::default()
        };
        let in_pool = |threads: usize| {
            let pool = pool(threads);
            pool.install(|| {
                let mut f = CholeskyFactor::analyze_with(&p, params).unwrap();
                let mut x = Vec::new();
                for _ in 0..3 {
                    f.factorize(&p, &v).unwrap();
                    x = b.clone();
                    assert!(f.solve_in_place(&mut x));
                    let err = x
                        .iter()
                        .zip(&xs)
                        .map(|(a, e)| (a - e).abs())
                        .fold(0.0, f64::max);
                    assert!(err < 1e-12, "{threads} threads: {err}");
                }
                assert_eq!(f.symbolic_analyses(), 1);
                (f.split(), f.is_parallel(), x)
            })
        };
        let (split, parallel, _) = in_pool(2);
        let (k, critical) = split.expect("two threads and large enough: split");
        assert!(parallel && k > 0);
        let plain = CholeskyFactor::analyze(&p).unwrap().factor_flops();
        assert!(
            plain >= SPLIT_MIN_FLOPS,
            "the grid must be above the threshold"
        );
        assert!(
            critical < plain,
            "the critical path is shorter: {critical:e} vs {plain:e}"
        );
        let (one, parallel, _) = in_pool(1);
        assert!(
            one.is_none() && !parallel,
            "one thread: the sequential path"
        );
        let small = crate::linear::ordering::tests::grid(9, 7, 2);
        let f = CholeskyFactor::analyze_with(&small, params).unwrap();
        assert!(f.split().is_none(), "below the threshold: sequential");
    }

    /// The halves factorise only their own columns (split.rs, half.rs): the
    /// split does about the plain factorisation's flops, not the separator's
    /// dense block three times over, and its critical path is well below
    /// the plain flops.
    #[test]
    fn the_split_adds_little_work_over_the_plain_factorisation() {
        let p = crate::linear::ordering::tests::grid(100, 100, 2);
        let params = CholeskyParams {
            threads: ThreadPolicy::Split,
            ..Default::default()
        };
        let pool = pool(2);
        let f = pool.install(|| CholeskyFactor::analyze_with(&p, params).unwrap());
        let (k, critical) = f.split().expect("split");
        let plain = CholeskyFactor::analyze(&p).unwrap().factor_flops();
        let split = f.factor_flops();
        let dense: f64 = (1..=k).map(|c| (c as f64).powi(2)).sum();
        assert!(
            split <= 1.05 * plain,
            "split {split:e} vs plain {plain:e} (k = {k})"
        );
        assert!(
            critical >= dense && critical <= 0.8 * plain,
            "{critical:e} vs {plain:e}"
        );
    }

    /// The tree read off the group graph ([`Tree::of_groups`]) against
    /// faer's symbolic analysis of the whole matrix in the same order with
    /// fundamental supernodes (no relaxation): the same flops, Σ c² over
    /// the scalar columns, and a tree whose nodes tile the columns
    /// bottom-up.
    #[test]
    fn the_group_tree_has_the_scalar_factors_flops() {
        use crate::linear::ordering::tests::{grid, grid_coords};
        for (p, coords, o) in [
            (grid(30, 20, 2), None, FillOrdering::BlockAmd),
            (grid(12, 9, 3), None, FillOrdering::BlockAmd),
            (
                grid(40, 40, 2),
                Some(grid_coords(40, 40, 2)),
                FillOrdering::Geometric,
            ),
        ] {
            let coords = coords.map(Coordinates::from);
            let ordered = ordered(&p, o, coords.as_ref()).unwrap();
            let elimination = ordered.groups.as_ref().unwrap().elimination().unwrap();
            let tree = Tree::of_groups(&elimination);
            let n = p.n();
            let perm = ordered.perm.unwrap();
            let inv = ecc_mesh::dissection::inverse_permutation(&perm);
            let a = SymbolicSparseColMatRef::new_checked(n, n, p.col_ptr(), None, p.row_idx());
            let mut params = symbolic_params();
            params.supernodal_params.relax = None;
            let ordering = SymmetricOrdering::Custom(PermRef::new_checked(&perm, &inv, n));
            let symbolic = factorize_symbolic_cholesky(a, Side::Upper, ordering, params).unwrap();
            let (want, got) = (flops(&symbolic), tree.total_flops());
            assert!(
                (want - got).abs() <= 1e-12 * want,
                "{o:?}: {got:e} vs faer {want:e}"
            );
            assert_eq!(tree.begin[0], 0);
            assert_eq!(*tree.end.last().unwrap(), n);
            for k in 0..tree.parent.len() {
                assert!(tree.begin[k] < tree.end[k]);
                assert!(k == 0 || tree.begin[k] == tree.end[k - 1]);
                assert!(tree.parent[k] == usize::MAX || tree.parent[k] > k);
            }
            assert!(
                tree.parent.len() < elimination.sizes.len(),
                "chains are merged"
            );
        }
    }

    /// Every ordering splits: those by groups from the group graph's tree,
    /// faer's own AMD from its supernodal tree; the solves agree.
    #[test]
    fn every_ordering_splits_and_solves() {
        let p = crate::linear::ordering::tests::grid(100, 100, 2);
        let coords = crate::linear::ordering::tests::grid_coords(100, 100, 2);
        let v = dominant(&p);
        let b: Vec<f64> = (0..p.n()).map(|i| (0.3 * i as f64).cos()).collect();
        let mut reference = CholeskyFactor::analyze_with(
            &p,
            CholeskyParams {
                threads: ThreadPolicy::Sequential,
                ..Default::default()
            },
        )
        .unwrap();
        reference.factorize(&p, &v).unwrap();
        let mut want = b.clone();
        assert!(reference.solve_in_place(&mut want));
        pool(2).install(|| {
            for ordering in [
                FillOrdering::Amd,
                FillOrdering::BlockAmd,
                FillOrdering::Geometric,
            ] {
                let params = CholeskyParams {
                    ordering,
                    threads: ThreadPolicy::Split,
                    precision: FactorPrecision::Double,
                };
                let mut f =
                    CholeskyFactor::analyze_at(&p, params, Some(coords.clone().into())).unwrap();
                assert!(f.split().is_some(), "{ordering:?}");
                assert!(f.is_supernodal() && f.supernodes().is_none());
                f.factorize(&p, &v).unwrap();
                let mut x = b.clone();
                assert!(f.solve_in_place(&mut x));
                let err = x
                    .iter()
                    .zip(&want)
                    .map(|(a, e)| (a - e).abs())
                    .fold(0.0, f64::max);
                assert!(err < 1e-10, "{ordering:?}: {err:e}");
            }
        });
    }

    #[test]
    fn the_linear_system_factors_with_the_chosen_params() {
        use crate::linear::{AutoLimits, LinearSolver, LinearSystem};
        let p = crate::linear::ordering::tests::grid(6, 5, 2);
        let params = CholeskyParams {
            ordering: FillOrdering::BlockAmd,
            threads: ThreadPolicy::Parallel,
            ..Default::default()
        };
        for choice in [LinearSolver::Cholesky, LinearSolver::Auto] {
            let sys =
                LinearSystem::with_cholesky_params(&p, choice, AutoLimits::default(), 2, params)
                    .unwrap();
            assert_eq!(sys.cholesky().unwrap().params(), params, "{choice:?}");
            let default = LinearSystem::new(&p, choice, AutoLimits::default()).unwrap();
            // the default `Auto` ordering is reported as the one it used
            // (block AMD on this small grid)
            assert_eq!(
                default.cholesky().unwrap().params(),
                CholeskyParams {
                    ordering: FillOrdering::BlockAmd,
                    ..CholeskyParams::default()
                }
            );
        }
    }

    #[cfg(not(feature = "metis"))]
    #[test]
    fn an_ordering_not_compiled_in_is_an_error_not_a_silent_pcg() {
        use crate::linear::{AutoLimits, LinearSolver, LinearSystem};
        let p = crate::linear::ordering::tests::grid(3, 3, 2);
        let params = CholeskyParams {
            ordering: FillOrdering::Metis,
            ..Default::default()
        };
        for choice in [LinearSolver::Cholesky, LinearSolver::Auto] {
            let e =
                LinearSystem::with_cholesky_params(&p, choice, AutoLimits::default(), 2, params)
                    .err()
                    .expect("metis without the feature must fail");
            assert!(format!("{e}").contains("`metis` feature"), "{e}");
        }
        let pcg = LinearSystem::with_cholesky_params(
            &p,
            LinearSolver::Pcg,
            AutoLimits::default(),
            2,
            params,
        );
        assert!(pcg.is_ok(), "PCG does not order");
    }
}
