//! Sparse Cholesky (LLᵀ) with faer's low-level API.
//!
//! [`CholeskyFactor::analyze`] runs the symbolic analysis once per pattern
//! (AMD fill-reducing ordering, elimination tree, simplicial or supernodal
//! structure chosen by faer from the flop ratio). Each Newton step then calls
//! [`CholeskyFactor::factorize`], which writes the numeric factor into the
//! preallocated `l_values` using a preallocated scratch buffer, and
//! [`CholeskyFactor::solve_in_place`]. The factor keeps a copy of the
//! analysed pattern: `factorize` with a different pattern re-analyses (never
//! reads the old structure with new indices) and counts it, so the counters
//! let tests assert that the symbolic analysis really is reused.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use crate::error::FemError;
use crate::pattern::Pattern;

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
    /// analysis failed.
    Symbolic(FemError),
}

/// Symbolic structure, factor values and scratch for one pattern.
pub struct CholeskyFactor {
    symbolic: SymbolicCholesky<usize>,
    /// The pattern (column pointers, row indices) `symbolic` was computed for.
    analysed: (Vec<usize>, Vec<usize>),
    l_values: Vec<f64>,
    mem: MemBuffer,
    par: Par,
    factored: bool,
    symbolic_analyses: usize,
    numeric_factorizations: usize,
}

/// One symbolic analysis and the storage it sizes.
struct Analysis {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    mem: MemBuffer,
}

/// Symbolic analysis of the upper-triangular `pattern` (AMD ordering); the
/// factor values and all scratch are allocated here, once per pattern.
fn analysis(pattern: &Pattern, par: Par) -> Result<Analysis, FemError> {
    let n = pattern.n();
    // SAFETY-free: the pattern invariants (sorted, in-bounds rows) are checked here.
    let a = SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
    let symbolic = factorize_symbolic_cholesky(
        a,
        Side::Upper,
        SymmetricOrdering::Amd,
        CholeskySymbolicParams::default(),
    )
    .map_err(|e| FemError::Symbolic(format!("{e:?}")))?;
    let req = StackReq::any_of(&[
        symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        symbolic.solve_in_place_scratch::<f64>(1, par),
    ]);
    let mem = MemBuffer::try_new(req)
        .map_err(|_| FemError::Symbolic("out of memory for scratch".into()))?;
    let len = symbolic.len_val();
    let mut l_values = Vec::new();
    l_values
        .try_reserve_exact(len)
        .map_err(|_| FemError::Symbolic(format!("out of memory for a factor of {len} values")))?;
    l_values.resize(len, 0.0);
    Ok(Analysis {
        symbolic,
        l_values,
        mem,
    })
}

fn structure(pattern: &Pattern) -> (Vec<usize>, Vec<usize>) {
    (pattern.col_ptr().to_vec(), pattern.row_idx().to_vec())
}

impl CholeskyFactor {
    /// Symbolic analysis of the upper-triangular pattern; allocates the factor
    /// storage and all scratch once.
    pub fn analyze(pattern: &Pattern) -> Result<Self, FemError> {
        let par = Par::rayon(0);
        let Analysis {
            symbolic,
            l_values,
            mem,
        } = analysis(pattern, par)?;
        Ok(CholeskyFactor {
            symbolic,
            analysed: structure(pattern),
            l_values,
            mem,
            par,
            factored: false,
            symbolic_analyses: 1,
            numeric_factorizations: 0,
        })
    }

    /// Whether `pattern` is the one the symbolic analysis was done for.
    pub fn is_for(&self, pattern: &Pattern) -> bool {
        self.analysed.0 == pattern.col_ptr() && self.analysed.1 == pattern.row_idx()
    }

    /// Redo the symbolic analysis for a new pattern (counted).
    fn reanalyze(&mut self, pattern: &Pattern) -> Result<(), FemError> {
        let Analysis {
            symbolic,
            l_values,
            mem,
        } = analysis(pattern, self.par)?;
        self.symbolic = symbolic;
        self.l_values = l_values;
        self.mem = mem;
        self.analysed = structure(pattern);
        self.factored = false;
        self.symbolic_analyses += 1;
        Ok(())
    }

    /// Number of stored values of L.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Memory taken by the factor values, in bytes.
    pub fn factor_bytes(&self) -> usize {
        self.factor_nnz() * std::mem::size_of::<f64>()
    }

    /// Estimated floating-point operations of one numeric factorisation,
    /// Σ_j c_j² over the column counts c_j of L (supernodal: column k of a
    /// supernode of width w with r off-diagonal rows has c = w − k + r).
    pub fn factor_flops(&self) -> f64 {
        match self.symbolic.raw() {
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

    /// Whether faer chose the supernodal variant.
    pub fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
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
        let n = pattern.n();
        self.numeric_factorizations += 1;
        self.factored = false;
        // SAFETY: `is_for` above: this exact pattern was validated by
        // `new_checked` in its symbolic analysis.
        let sym = unsafe {
            SymbolicSparseColMatRef::new_unchecked(n, n, pattern.col_ptr(), None, pattern.row_idx())
        };
        let a = SparseColMatRef::new(sym, values);
        let stack = MemStack::new(&mut self.mem);
        match self.symbolic.factorize_numeric_llt::<f64>(
            &mut self.l_values,
            a,
            Side::Upper,
            Default::default(),
            self.par,
            stack,
            Default::default(),
        ) {
            Ok(_) => {
                self.factored = true;
                Ok(())
            }
            Err(LltError::NonPositivePivot { index }) => {
                Err(FactorizeError::NotPositiveDefinite(NotPositiveDefinite {
                    pivot: index,
                }))
            }
        }
    }

    /// Solve A x = rhs in place with the last successful factorisation.
    /// Returns `false` (leaving `rhs` untouched) if there is none.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> bool {
        if !self.factored {
            return false;
        }
        let n = rhs.len();
        let llt = LltRef::<'_, usize, f64>::new(&self.symbolic, &self.l_values);
        let stack = MemStack::new(&mut self.mem);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            self.par,
            stack,
        );
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::pattern::{StencilSet, build};

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
}
