//! Jacobi-preconditioned conjugate gradients on the assembled Hessian.
//!
//! For systems whose Cholesky factor would not fit (large tet meshes, as
//! Smith et al. 2019 did in 3D). Uses the same upper-CSC values as the direct
//! path; a symmetric row index (built once) turns y = H x into a parallel
//! gather over rows. Preconditioner M = diag(H). Starting from x = 0 every CG
//! iterate is a descent direction for a positive definite H, so an inexact
//! solve (stopped at a relative residual η) is still a valid Newton-type step.
//! All vectors are preallocated.

use rayon::prelude::*;

use crate::parallel::dot;
use crate::pattern::Pattern;

/// Outcome of one PCG solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PcgInfo {
    /// CG iterations performed.
    pub iterations: usize,
    /// Final ‖r‖₂ / ‖b‖₂.
    pub relative_residual: f64,
    /// Stopped early on non-positive curvature pᵀHp ≤ 0.
    pub negative_curvature: bool,
}

/// Preallocated PCG state for one pattern.
pub struct Pcg {
    /// symmetric row structure: row i → (slot, column) pairs
    row_ptr: Vec<usize>,
    row_ent: Vec<(u32, u32)>,
    inv_diag: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    partials: Vec<f64>,
}

impl Pcg {
    /// Build the symmetric row index of `pattern` and allocate the vectors.
    pub fn new(pattern: &Pattern) -> Self {
        let n = pattern.n();
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        let mut row_ptr = vec![0usize; n + 1];
        for j in 0..n {
            for &i in &ri[cp[j]..cp[j + 1]] {
                row_ptr[i + 1] += 1;
                if i != j {
                    row_ptr[j + 1] += 1;
                }
            }
        }
        for i in 0..n {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut fill = row_ptr.clone();
        let mut row_ent = vec![(0u32, 0u32); row_ptr[n]];
        for j in 0..n {
            for (p, &i) in ri[cp[j]..cp[j + 1]].iter().enumerate() {
                let slot = (cp[j] + p) as u32;
                row_ent[fill[i]] = (slot, j as u32);
                fill[i] += 1;
                if i != j {
                    row_ent[fill[j]] = (slot, i as u32);
                    fill[j] += 1;
                }
            }
        }
        Pcg {
            row_ptr,
            row_ent,
            inv_diag: vec![0.0; n],
            r: vec![0.0; n],
            z: vec![0.0; n],
            p: vec![0.0; n],
            q: vec![0.0; n],
            partials: Vec::new(),
        }
    }

    /// y = H x (parallel over rows).
    pub fn matvec(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        sym_matvec(&self.row_ptr, &self.row_ent, values, x, y);
    }

    /// Solve H x = b to ‖r‖ ≤ `rel_tol`·‖b‖ (or `max_iters`), x overwritten,
    /// starting from 0, preconditioned by M = diag(H). `values` must be
    /// positive on the diagonal (a non-positive diagonal entry is
    /// preconditioned by 1).
    pub fn solve(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
    ) -> PcgInfo {
        let n = pattern.n();
        for j in 0..n {
            let d = values[pattern.diag_slot(j)];
            self.inv_diag[j] = if d > 0.0 && d.is_finite() {
                1.0 / d
            } else {
                1.0
            };
        }
        let inv_diag = std::mem::take(&mut self.inv_diag);
        let info = self.solve_preconditioned(values, b, x, rel_tol, max_iters, |r, z| {
            zip_mul(z, &inv_diag, r)
        });
        self.inv_diag = inv_diag;
        info
    }

    /// CG as in [`Pcg::solve`] with any symmetric positive definite
    /// preconditioner: `precond(r, z)` writes z = M⁻¹ r. With M⁻¹ a
    /// Cholesky solve of an earlier Hessian (a *stale* factor) the
    /// preconditioned matrix M⁻¹H is close to I and CG needs few iterations
    /// while H has changed little (see [`super::reuse`]).
    pub fn solve_preconditioned(
        &mut self,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
        mut precond: impl FnMut(&[f64], &mut [f64]),
    ) -> PcgInfo {
        x.fill(0.0);
        self.r.copy_from_slice(b);
        let bnorm = dot(b, b, &mut self.partials).sqrt();
        if bnorm == 0.0 || !bnorm.is_finite() {
            return PcgInfo {
                iterations: 0,
                relative_residual: 0.0,
                negative_curvature: false,
            };
        }
        precond(&self.r, &mut self.z);
        self.p.copy_from_slice(&self.z);
        let mut rz = dot(&self.r, &self.z, &mut self.partials);
        let mut rnorm = bnorm;
        let mut it = 0;
        let mut negative = false;
        while it < max_iters && rnorm > rel_tol * bnorm {
            sym_matvec(&self.row_ptr, &self.row_ent, values, &self.p, &mut self.q);
            let pq = dot(&self.p, &self.q, &mut self.partials);
            if pq <= 0.0 || !pq.is_finite() || !rz.is_finite() || rz <= 0.0 {
                negative = true;
                if it == 0 {
                    // no curvature information at all: preconditioned steepest descent
                    x.copy_from_slice(&self.z);
                }
                break;
            }
            let alpha = rz / pq;
            axpy(x, alpha, &self.p);
            axpy(&mut self.r, -alpha, &self.q);
            rnorm = dot(&self.r, &self.r, &mut self.partials).sqrt();
            it += 1;
            precond(&self.r, &mut self.z);
            let rz_new = dot(&self.r, &self.z, &mut self.partials);
            let beta = rz_new / rz;
            rz = rz_new;
            self.p
                .par_iter_mut()
                .zip(&self.z)
                .with_min_len(4096)
                .for_each(|(p, z)| *p = z + beta * *p);
        }
        PcgInfo {
            iterations: it,
            relative_residual: rnorm / bnorm,
            negative_curvature: negative,
        }
    }
}

fn sym_matvec(rp: &[usize], re: &[(u32, u32)], values: &[f64], x: &[f64], y: &mut [f64]) {
    y.par_iter_mut()
        .enumerate()
        .with_min_len(1024)
        .for_each(|(i, yi)| {
            let mut s = 0.0;
            for &(slot, j) in &re[rp[i]..rp[i + 1]] {
                s += values[slot as usize] * x[j as usize];
            }
            *yi = s;
        });
}

fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    y.par_iter_mut()
        .zip(x)
        .with_min_len(4096)
        .for_each(|(y, x)| *y += a * x);
}

fn zip_mul(out: &mut [f64], a: &[f64], b: &[f64]) {
    out.par_iter_mut()
        .zip(a.par_iter().zip(b))
        .with_min_len(4096)
        .for_each(|(o, (a, b))| *o = a * b);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::pattern::{StencilSet, build};

    #[test]
    fn pcg_matches_matvec_and_converges() {
        // 2D grid graph Laplacian + 0.01 I (SPD, moderately conditioned)
        let m = 12;
        let mut edges = Vec::new();
        for i in 0..m {
            for j in 0..m {
                let v = i * m + j;
                if j + 1 < m {
                    edges.extend_from_slice(&[v, v + 1]);
                }
                if i + 1 < m {
                    edges.extend_from_slice(&[v, v + m]);
                }
            }
        }
        let n = m * m;
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
            v[p.diag_slot(j)] += 0.01;
        }
        for e in edges.chunks(2) {
            v[p.diag_slot(e[0])] += 1.0;
            v[p.diag_slot(e[1])] += 1.0;
            v[p.slot(e[0], e[1]).unwrap()] -= 1.0;
        }
        let xs: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let mut b = vec![0.0; n];
        p.sym_matvec(&v, &xs, &mut b);
        let mut pcg = Pcg::new(&p);
        let mut b2 = vec![0.0; n];
        pcg.matvec(&v, &xs, &mut b2);
        for (a, c) in b.iter().zip(&b2) {
            assert!((a - c).abs() < 1e-12);
        }
        let mut x = vec![0.0; n];
        let info = pcg.solve(&p, &v, &b, &mut x, 1e-10, 1000);
        assert!(info.relative_residual <= 1e-10, "{info:?}");
        assert!(!info.negative_curvature);
        for (a, c) in x.iter().zip(&xs) {
            assert!((a - c).abs() < 1e-6);
        }
        // a loose tolerance stops early but still descends: bᵀx > 0
        let info = pcg.solve(&p, &v, &b, &mut x, 0.5, 1000);
        assert!(info.iterations >= 1 && info.relative_residual <= 0.5);
        assert!(b.iter().zip(&x).map(|(a, c)| a * c).sum::<f64>() > 0.0);
    }
}
