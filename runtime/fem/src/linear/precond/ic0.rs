//! Incomplete Cholesky IC(0) on the pattern of H, with Manteuffel's
//! diagonal shift on breakdown.
//!
//! With H stored as its upper triangle in CSC (column j = rows i ≤ j), the
//! factor is an upper-triangular U with the *same* pattern such that
//! (Uᵀ U)_ij = H_ij on the pattern (Meijerink & van der Vorst 1977):
//!
//!   U_ij = (H_ij − Σ_{k<i} U_ki U_kj) / U_ii,   i < j, (i, j) ∈ P       (1)
//!   U_jj = √(H_jj − Σ_{k<j} U_kj²)                                     (2)
//!
//! where the sums run over k with (k, i) and (k, j) in the pattern P; fill
//! outside P is dropped. Column j is computed from the finished columns
//! i < j with a dense scatter of column j (left-looking). When P has no
//! fill (e.g. a tridiagonal or block-diagonal matrix) the dropped terms are
//! all zero and U is the exact Cholesky factor.
//!
//! **Breakdown.** For an SPD H that is not an M-matrix, (2) may meet a
//! non-positive radicand. Then the factorisation is restarted on
//! H + α·diag(H) (Manteuffel 1980), α ∈ {α₀, 10α₀, …} from α₀ = 1e-3
//! (or from a tenth of the last α that worked, so a sequence of similar
//! Hessians does not repeat the failures); after [`MAX_SHIFTS`] shifts, and
//! for entries with a non-positive diagonal, M falls back to Jacobi
//! (U = √diag, no off-diagonals), so M = UᵀU is always positive definite.
//!
//! **Application.** z = (UᵀU)⁻¹ r by a forward solve with Uᵀ (column dots)
//! and a backward solve with U (column updates): 2·(2·nnz − n) flops,
//! sequential.

use super::positive_inverse;
use crate::pattern::Pattern;

/// Shifts tried after the unshifted factorisation breaks down.
pub const MAX_SHIFTS: usize = 6;
/// First shift α₀ (relative to diag(H)).
pub const FIRST_SHIFT: f64 = 1e-3;

/// IC(0) factor and its work space.
pub struct Ic0 {
    col_ptr: Vec<usize>,
    row_idx: Vec<u32>,
    /// U on the pattern of H (slot-aligned with H's values).
    u: Vec<f64>,
    /// Dense scatter of the current column.
    w: Vec<f64>,
    /// Shift α of the last factorisation (0: none; ∞: Jacobi fallback).
    shift: f64,
    /// Restarts of the last factorisation.
    restarts: usize,
}

impl Ic0 {
    /// Copy the pattern and allocate.
    pub fn new(pattern: &Pattern) -> Self {
        Ic0 {
            col_ptr: pattern.col_ptr().to_vec(),
            row_idx: pattern.row_idx().iter().map(|&i| i as u32).collect(),
            u: vec![0.0; pattern.nnz()],
            w: vec![0.0; pattern.n()],
            shift: 0.0,
            restarts: 0,
        }
    }

    /// The relative diagonal shift α used by the last factorisation (0 =
    /// none, ∞ = the Jacobi fallback).
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// Restarts (breakdowns) of the last factorisation.
    pub fn restarts(&self) -> usize {
        self.restarts
    }

    /// Factorise `values` (upper CSC of `pattern`), eqs. (1)–(2), shifting
    /// on breakdown (module docs).
    pub fn factorize(&mut self, pattern: &Pattern, values: &[f64]) {
        debug_assert_eq!(pattern.nnz(), self.u.len());
        let start = if self.shift > 0.0 && self.shift.is_finite() {
            (0.1 * self.shift).max(FIRST_SHIFT)
        } else {
            FIRST_SHIFT
        };
        let mut alpha = 0.0;
        self.restarts = 0;
        loop {
            if self.try_factorize(values, alpha) {
                self.shift = alpha;
                return;
            }
            self.restarts += 1;
            if self.restarts > MAX_SHIFTS {
                self.jacobi(values);
                return;
            }
            alpha = if alpha == 0.0 { start } else { 10.0 * alpha };
        }
    }

    /// One attempt on H + α·diag(H); false on breakdown.
    fn try_factorize(&mut self, values: &[f64], alpha: f64) -> bool {
        let n = self.w.len();
        let (cp, ri, u, w) = (&self.col_ptr, &self.row_idx, &mut self.u, &mut self.w);
        for j in 0..n {
            let (lo, diag) = (cp[j], cp[j + 1] - 1);
            for p in lo..diag {
                w[ri[p] as usize] = values[p];
            }
            let mut d = values[diag] * (1.0 + alpha);
            for p in lo..diag {
                let i = ri[p] as usize;
                // eq. (1): Σ_{k<i} U_ki U_kj over column i (w holds U_kj for k < i)
                let mut s = w[i];
                for q in cp[i]..cp[i + 1] - 1 {
                    s -= u[q] * w[ri[q] as usize];
                }
                let uij = s / u[cp[i + 1] - 1];
                u[p] = uij;
                w[i] = uij;
                d -= uij * uij;
            }
            for p in lo..diag {
                w[ri[p] as usize] = 0.0;
            }
            // eq. (2)
            if !(d > 0.0 && d.is_finite()) {
                return false;
            }
            u[diag] = d.sqrt();
        }
        true
    }

    /// The fallback U = √diag(H) (1 where the diagonal is not positive).
    fn jacobi(&mut self, values: &[f64]) {
        self.u.fill(0.0);
        for j in 0..self.w.len() {
            let diag = self.col_ptr[j + 1] - 1;
            self.u[diag] = positive_inverse(values[diag]).recip().sqrt();
        }
        self.shift = f64::INFINITY;
    }

    /// z = (UᵀU)⁻¹ r: Uᵀ y = r forward, then U z = y backward (in z).
    pub fn apply(&self, r: &[f64], z: &mut [f64]) {
        let (cp, ri, u) = (&self.col_ptr, &self.row_idx, &self.u);
        let n = z.len();
        for j in 0..n {
            let diag = cp[j + 1] - 1;
            let mut s = r[j];
            for p in cp[j]..diag {
                s -= u[p] * z[ri[p] as usize];
            }
            z[j] = s / u[diag];
        }
        for j in (0..n).rev() {
            let diag = cp[j + 1] - 1;
            let zj = z[j] / u[diag];
            z[j] = zj;
            for p in cp[j]..diag {
                z[ri[p] as usize] -= u[p] * zj;
            }
        }
    }

    /// Multiply-adds of one factorisation attempt (pattern only): Σ over
    /// entries (i, j) of the length of column i, plus the diagonals.
    pub fn setup_work(pattern: &Pattern) -> f64 {
        let cp = pattern.col_ptr();
        let ri = pattern.row_idx();
        let mut s = 0.0;
        for j in 0..pattern.n() {
            for &i in &ri[cp[j]..cp[j + 1]] {
                s += (cp[i + 1] - cp[i]) as f64;
            }
        }
        2.0 * s
    }
}
