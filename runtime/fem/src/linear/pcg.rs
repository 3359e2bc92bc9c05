//! Preconditioned conjugate gradients on the assembled Hessian.
//!
//! For systems whose Cholesky factor would not fit (large tet meshes, as
//! Smith et al. 2019 did in 3D) or costs more than CG. Uses the same
//! upper-CSC values as the direct path; a symmetric row index (built once)
//! turns y = H x into a parallel gather over rows. The preconditioner M is
//! one of [`Preconditioner`] (default IC(0), [`super::precond`]). Starting from x = 0 every CG
//! iterate is a descent direction for a positive definite H, so an inexact
//! solve (stopped at a relative residual η) is still a valid Newton-type step.
//! All vectors are preallocated.

use rayon::prelude::*;

use super::precond::{Preconditioner, State};
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
    kind: Preconditioner,
    /// Built on the first [`Pcg::solve`] (a stale-factor CG never needs it).
    precond: Option<State>,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    partials: Vec<f64>,
}

impl Pcg {
    /// [`Pcg::with_preconditioner`] with the default preconditioner.
    pub fn new(pattern: &Pattern) -> Self {
        Self::with_preconditioner(pattern, Preconditioner::default())
    }

    /// Build the symmetric row index of `pattern` and allocate the vectors;
    /// [`Pcg::solve`] preconditions with `kind`.
    pub fn with_preconditioner(pattern: &Pattern, kind: Preconditioner) -> Self {
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
            kind,
            precond: None,
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

    /// The preconditioner of [`Pcg::solve`].
    pub fn preconditioner(&self) -> Preconditioner {
        self.kind
    }

    /// Solve H x = b to ‖r‖ ≤ `rel_tol`·‖b‖ (or `max_iters`), x overwritten,
    /// starting from 0, preconditioned by M built from `values` (see
    /// [`super::precond`]: always positive definite, also for a
    /// non-positive diagonal entry).
    pub fn solve(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
    ) -> PcgInfo {
        self.solve_budgeted(pattern, values, b, x, rel_tol, max_iters, false)
    }

    /// [`Pcg::solve`] within a budget of `max_iters` iterations that, with
    /// `give_up`, stops as soon as the budget looks out of reach: from
    /// iteration k₀ = max(5, ⌈max_iters/4⌉) on, when the residual ratio
    /// ρ_k = ‖r_k‖/‖b‖ extrapolated linearly in log scale,
    ///
    ///   k·ln(rel_tol)/ln(ρ_k) > max_iters,                                (1)
    ///
    /// (or ρ_k ≥ 1). A stop by (1) returns ρ_k > `rel_tol`: the caller
    /// treats it as a failed attempt, having spent ≈ k₀ instead of
    /// `max_iters` iterations. Counted, not timed: deterministic.
    #[allow(clippy::too_many_arguments)]
    pub fn solve_budgeted(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
        give_up: bool,
    ) -> PcgInfo {
        let kind = self.kind;
        let mut m = self
            .precond
            .take()
            .unwrap_or_else(|| State::new(kind, pattern));
        m.setup(pattern, values);
        let k0 = 5.max(max_iters.div_ceil(4));
        let hopeless = |k: usize, rho: f64| {
            give_up
                && k >= k0
                && (rho >= 1.0 || k as f64 * rel_tol.ln() / rho.ln() > max_iters as f64)
        };
        let info = self.cg(
            values,
            b,
            x,
            rel_tol,
            max_iters,
            |r, z| m.apply(r, z),
            hopeless,
        );
        self.precond = Some(m);
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
        precond: impl FnMut(&[f64], &mut [f64]),
    ) -> PcgInfo {
        self.cg(values, b, x, rel_tol, max_iters, precond, |_, _| false)
    }

    /// The CG loop; `hopeless(k, ‖r_k‖/‖b‖)` stops it early.
    #[allow(clippy::too_many_arguments)]
    fn cg(
        &mut self,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        rel_tol: f64,
        max_iters: usize,
        mut precond: impl FnMut(&[f64], &mut [f64]),
        hopeless: impl Fn(usize, f64) -> bool,
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
            // converged (no preconditioner solve for a direction never taken) or hopeless
            if rnorm <= rel_tol * bnorm || hopeless(it, rnorm / bnorm) {
                break;
            }
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
