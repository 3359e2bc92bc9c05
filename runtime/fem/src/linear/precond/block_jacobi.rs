//! Block-Jacobi preconditioner: M = blockdiag(H_vv), the d×d diagonal
//! blocks of the vertices, each inverted through its dense Cholesky factor.
//!
//! **Blocks from the pattern.** Unknowns are numbered vertex by vertex and
//! the unknowns of one vertex have the same neighbours, so in the upper CSC
//! pattern (`crate::pattern`) column j+1 of the same vertex is column j plus
//! the diagonal entry: rows(j+1) = rows(j) ∪ {j+1}. A block is a maximal run
//! of such columns, at most [`MAX_BLOCK`] long; its entries (i, j), i ≤ j,
//! are then the last j − s + 1 entries of column j (s = the block's first
//! unknown). Any partition into contiguous blocks gives a principal
//! submatrix of H, so even an unlucky run that joins two vertices keeps M
//! symmetric positive definite when H is.
//!
//! **Breakdown.** A block that is not positive definite (a non-positive
//! pivot; only when H itself is not, e.g. an unfiltered Hessian) is
//! replaced by its diagonal with non-positive entries set to 1, as Jacobi.

use super::positive_inverse;
use crate::pattern::Pattern;

/// Largest block (vertices have 2 or 3 unknowns).
pub const MAX_BLOCK: usize = 3;

/// Factored diagonal blocks.
pub struct BlockJacobi {
    /// First unknown of each block, plus n.
    starts: Vec<usize>,
    /// Diagonal slot of each unknown (entries of a block are found from it).
    diag: Vec<usize>,
    /// Per block: row-major k×k lower Cholesky factor L (H_bb = L Lᵀ), or
    /// the inverse diagonal in L[i][i] when `jacobi[b]`.
    factors: Vec<[f64; MAX_BLOCK * MAX_BLOCK]>,
    jacobi: Vec<bool>,
}

impl BlockJacobi {
    /// Find the blocks of `pattern` (see the module docs).
    pub fn new(pattern: &Pattern) -> Self {
        let n = pattern.n();
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        let mut starts = vec![0];
        let mut s = 0;
        for j in 1..n {
            let same_vertex = j - s < MAX_BLOCK
                && cp[j + 1] - cp[j] == cp[j] - cp[j - 1] + 1
                && ri[cp[j]..cp[j + 1] - 1] == ri[cp[j - 1]..cp[j]];
            if !same_vertex {
                starts.push(j);
                s = j;
            }
        }
        if n > 0 {
            starts.push(n);
        } else {
            starts.clear();
            starts.push(0);
        }
        let nb = starts.len() - 1;
        BlockJacobi {
            starts,
            diag: (0..n).map(|j| pattern.diag_slot(j)).collect(),
            factors: vec![[0.0; MAX_BLOCK * MAX_BLOCK]; nb],
            jacobi: vec![false; nb],
        }
    }

    /// Number of blocks.
    pub fn blocks(&self) -> usize {
        self.starts.len() - 1
    }

    /// Factor every diagonal block of `values`.
    pub fn setup(&mut self, values: &[f64]) {
        for b in 0..self.blocks() {
            let (s, e) = (self.starts[b], self.starts[b + 1]);
            let k = e - s;
            // block entry (i, j), i ≤ j: the (j − i)-th entry before column j's diagonal
            let h = |i: usize, j: usize| values[self.diag[s + j] - (j - i)];
            let l = &mut self.factors[b];
            let ok = dense_cholesky(k, h, l);
            self.jacobi[b] = !ok;
            if !ok {
                for i in 0..k {
                    l[i * MAX_BLOCK + i] = positive_inverse(h(i, i));
                }
            }
        }
    }

    /// z = M⁻¹ r: per block, forward and backward substitution with L.
    pub fn apply(&self, r: &[f64], z: &mut [f64]) {
        for b in 0..self.blocks() {
            let (s, e) = (self.starts[b], self.starts[b + 1]);
            let l = &self.factors[b];
            let (r, z) = (&r[s..e], &mut z[s..e]);
            if self.jacobi[b] {
                for i in 0..e - s {
                    z[i] = r[i] * l[i * MAX_BLOCK + i];
                }
            } else {
                solve_llt(e - s, l, r, z);
            }
        }
    }
}

/// Dense Cholesky H = L Lᵀ of a k×k block given by its upper entries
/// `h(i, j)`, i ≤ j; false on a non-positive or non-finite pivot.
fn dense_cholesky(
    k: usize,
    h: impl Fn(usize, usize) -> f64,
    l: &mut [f64; MAX_BLOCK * MAX_BLOCK],
) -> bool {
    for j in 0..k {
        let mut d = h(j, j);
        for p in 0..j {
            d -= l[j * MAX_BLOCK + p] * l[j * MAX_BLOCK + p];
        }
        if !(d > 0.0 && d.is_finite()) {
            return false;
        }
        let d = d.sqrt();
        l[j * MAX_BLOCK + j] = d;
        for i in j + 1..k {
            let mut v = h(j, i);
            for p in 0..j {
                v -= l[i * MAX_BLOCK + p] * l[j * MAX_BLOCK + p];
            }
            l[i * MAX_BLOCK + j] = v / d;
        }
    }
    true
}

/// Solve L Lᵀ z = r for a k×k lower factor.
fn solve_llt(k: usize, l: &[f64; MAX_BLOCK * MAX_BLOCK], r: &[f64], z: &mut [f64]) {
    for i in 0..k {
        let mut v = r[i];
        for p in 0..i {
            v -= l[i * MAX_BLOCK + p] * z[p];
        }
        z[i] = v / l[i * MAX_BLOCK + i];
    }
    for i in (0..k).rev() {
        let mut v = z[i];
        for p in i + 1..k {
            v -= l[p * MAX_BLOCK + i] * z[p];
        }
        z[i] = v / l[i * MAX_BLOCK + i];
    }
}
