//! The projected Newton loop (Smith et al. 2019, Algorithm 1).

use std::ops::ControlFlow;
use std::time::Instant;

use ecc_runtime::filter::Filter;
use rayon::prelude::*;

use super::line_search::{Armijo, backtrack};
use super::params::{FilterPolicy, NewtonParams};
use super::record::{IterationRecord, NewtonResult, NewtonStatus, TimeSplit};
use crate::assembly::{Assembler, NonFiniteStencil};
use crate::dofs::DofMap;
use crate::error::FemError;
use crate::linear::{LinearSolver, LinearSystem};
use crate::parallel::{dot, norm_inf};
use crate::pattern::Pattern;
use crate::term::Term;

/// Energy, reduced gradient and (optionally) reduced Hessian values at a point.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// Scaled energy.
    pub energy: f64,
    /// Scaled gradient per vertex DOF (index v·D + c), zero on fixed DOFs.
    pub gradient: Vec<f64>,
    /// Upper-CSC values of the scaled, filtered reduced Hessian over the
    /// unknowns (see [`NewtonSolver::pattern`] and [`NewtonSolver::dofs`]).
    pub hessian: Option<Vec<f64>>,
}

/// A projected Newton solver for Σ terms over a fixed mesh and fixed set.
///
/// Built once per (terms' stencils, fixed DOFs): pattern, slot maps,
/// colourings and the symbolic factorisation. `solve` can then be called
/// any number of times (moved handles, changed term data, new start).
pub struct NewtonSolver<const D: usize> {
    terms: Vec<Box<dyn Term<D>>>,
    assembler: Assembler<D>,
    linear: LinearSystem,
    /// Parameters (may be changed between solves; `linear_solver` and
    /// `auto_limits` only take effect through [`NewtonSolver::set_linear_solver`]).
    pub params: NewtonParams,
    g: Vec<f64>,
    values: Vec<f64>,
    rhs: Vec<f64>,
    d: Vec<f64>,
    dx: Vec<[f64; D]>,
    xt: Vec<[f64; D]>,
    partials: Vec<f64>,
}

impl<const D: usize> NewtonSolver<D> {
    /// Solver with whole vertices fixed (`fixed` may be empty).
    pub fn new(
        n_vertices: usize,
        terms: Vec<Box<dyn Term<D>>>,
        fixed: &[usize],
        params: NewtonParams,
    ) -> Result<Self, FemError> {
        let dofs = DofMap::from_fixed_vertices(n_vertices, D, fixed)?;
        Self::with_dofs(terms, dofs, params)
    }

    /// Solver with an explicit DOF map (per-coordinate constraints).
    pub fn with_dofs(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
    ) -> Result<Self, FemError> {
        let nv = dofs.n_vertices();
        let assembler = Assembler::new(&terms, dofs)?;
        let pattern = assembler.pattern();
        let linear = LinearSystem::new(pattern, params.linear_solver, params.auto_limits)?;
        let n = pattern.n();
        let nnz = pattern.nnz();
        Ok(NewtonSolver {
            terms,
            linear,
            params,
            g: vec![0.0; n],
            values: vec![0.0; nnz],
            rhs: vec![0.0; n],
            d: vec![0.0; n],
            dx: vec![[0.0; D]; nv],
            xt: vec![[0.0; D]; nv],
            partials: Vec::new(),
            assembler,
        })
    }

    /// Rebuild the linear backend (e.g. switch Cholesky ↔ PCG).
    pub fn set_linear_solver(&mut self, choice: LinearSolver) -> Result<(), FemError> {
        self.params.linear_solver = choice;
        self.linear = LinearSystem::new(self.assembler.pattern(), choice, self.params.auto_limits)?;
        Ok(())
    }

    /// The linear solver in use (`Cholesky` or `Pcg`).
    pub fn linear_solver(&self) -> LinearSolver {
        self.linear.kind()
    }

    /// The linear system (factor size, counters).
    pub fn linear_system(&self) -> &LinearSystem {
        &self.linear
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        self.assembler.dofs()
    }

    /// The reduced Hessian's pattern.
    pub fn pattern(&self) -> &Pattern {
        self.assembler.pattern()
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.dx.len()
    }

    /// The terms.
    pub fn terms(&self) -> &[Box<dyn Term<D>>] {
        &self.terms
    }

    /// Term `i` as its concrete type, to change its data between solves
    /// (its stencils must not change).
    pub fn term_mut<T: Term<D>>(&mut self, i: usize) -> Option<&mut T> {
        let t: &mut dyn std::any::Any = self.terms.get_mut(i)?.as_mut();
        t.downcast_mut::<T>()
    }

    fn check_positions(&self, x: &[[f64; D]]) -> Result<(), FemError> {
        if x.len() != self.dx.len() {
            return Err(FemError::LengthMismatch {
                what: "positions",
                expected: self.dx.len(),
                got: x.len(),
            });
        }
        if let Some(v) = x.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(FemError::NonFinitePosition {
                what: "positions",
                vertex: v,
            });
        }
        Ok(())
    }

    /// Scaled energy at `x` (`+∞` outside the domain).
    pub fn energy(&mut self, x: &[[f64; D]]) -> Result<f64, FemError> {
        self.check_positions(x)?;
        Ok(self
            .assembler
            .energy(&self.terms, x, self.params.energy_scale))
    }

    /// Scaled energy, gradient and optionally the filtered Hessian at `x`.
    pub fn evaluate(
        &mut self,
        x: &[[f64; D]],
        hessian: Option<Filter>,
    ) -> Result<Result<Evaluation, NonFiniteStencil>, FemError> {
        self.check_positions(x)?;
        let mut reduced = vec![0.0; self.g.len()];
        let mut values = hessian.map(|_| vec![0.0; self.values.len()]);
        let h = hessian.zip(values.as_deref_mut());
        let assembled =
            self.assembler
                .assemble(&self.terms, x, self.params.energy_scale, &mut reduced, h);
        Ok(assembled.map(|energy| {
            let mut gradient = vec![0.0; x.len() * D];
            self.assembler.dofs().scatter(&reduced, &mut gradient);
            Evaluation {
                energy,
                gradient,
                hessian: values,
            }
        }))
    }

    /// Minimise from `x` (fixed vertices keep their values in `x`).
    pub fn solve(&mut self, x: &mut [[f64; D]]) -> Result<NewtonResult, FemError> {
        self.solve_with(x, |_, _| ControlFlow::Continue(()))
    }

    /// [`NewtonSolver::solve`] with a callback after every accepted step
    /// (record, new positions); `ControlFlow::Break` stops with `Interrupted`.
    pub fn solve_with(
        &mut self,
        x: &mut [[f64; D]],
        mut callback: impl FnMut(&IterationRecord, &[[f64; D]]) -> ControlFlow<()>,
    ) -> Result<NewtonResult, FemError> {
        self.check_positions(x)?;
        let t_start = Instant::now();
        self.assembler.reset_timings();
        let p = self.params.clone();
        let scale = p.energy_scale;
        let null_shift = if self.dofs().n_fixed() == 0 {
            p.null_space_shift
        } else {
            0.0
        };
        let armijo = Armijo {
            c1: p.armijo_c1,
            beta: p.backtrack,
            min_step: p.min_step,
        };
        let mut times = TimeSplit::default();
        let mut records = Vec::new();
        let mut filter = p.filter_policy.first(p.filter);
        // last relative shift that made a raw (unfiltered) Hessian factorable
        let mut raw_shift = 0.0f64;
        let mut initial: Option<(f64, f64)> = None;
        // (energy, ‖∇E‖∞) of the current positions, set by every exit path
        let mut last: (f64, f64);
        let mut iter = 0;

        let status = loop {
            // 1. assemble E, ∇E and the filtered Hessian
            let t0 = Instant::now();
            let mut used_filter = filter;
            let mut assembled = self.assembler.assemble(
                &self.terms,
                x,
                scale,
                &mut self.g,
                Some((filter, &mut self.values)),
            );
            if filter == Filter::None && matches!(&assembled, Err(b) if b.quantity == "hessian") {
                // the raw Hessian is genuinely singular somewhere: filter this iteration
                used_filter = p.filter;
                assembled = self.assembler.assemble(
                    &self.terms,
                    x,
                    scale,
                    &mut self.g,
                    Some((p.filter, &mut self.values)),
                );
            }
            let t_assembly = t0.elapsed().as_secs_f64();
            times.assembly += t_assembly;
            let energy = match assembled {
                Ok(e) => e,
                Err(bad) => {
                    // report the energy of x (+∞ if a stencil is outside its domain
                    // or NaN) and an unknown (+∞) gradient norm, never NaN
                    last = (self.assembler.energy(&self.terms, x, scale), f64::INFINITY);
                    break NewtonStatus::NonFinite(bad);
                }
            };
            let grad_inf = norm_inf(&self.g);
            let g0 = initial.get_or_insert((energy, grad_inf)).1;
            last = (energy, grad_inf);

            // 2. convergence
            if grad_inf <= p.tol_abs || grad_inf <= p.tol_rel * g0 {
                break NewtonStatus::Converged;
            }
            if iter >= p.max_iters {
                break NewtonStatus::MaxIterations;
            }

            // 3. (H + δI) d = −∇E
            let raw = used_filter == Filter::None;
            let base_shift = if raw {
                null_shift.max(0.1 * raw_shift)
            } else {
                null_shift
            };
            let t1 = Instant::now();
            let prep = self.linear.prepare(
                self.assembler.pattern(),
                &mut self.values,
                base_shift,
                p.shift_attempts,
            );
            let t_factor = t1.elapsed().as_secs_f64();
            times.factor += t_factor;
            let prep = match prep {
                Ok(i) => i,
                Err(f) => break NewtonStatus::FactorizationFailed { shift: f.shift },
            };
            if raw {
                raw_shift = prep.relative_shift;
            }
            let t2 = Instant::now();
            self.rhs.iter_mut().zip(&self.g).for_each(|(r, g)| *r = -g);
            let eta = (grad_inf / g0).sqrt().clamp(p.pcg_rel_min, p.pcg_rel_max);
            let solve = self.linear.solve(
                self.assembler.pattern(),
                &self.values,
                &self.rhs,
                &mut self.d,
                eta,
                p.pcg_max_iters,
            );
            let t_solve = t2.elapsed().as_secs_f64();
            times.solve += t_solve;
            let slope = dot(&self.g, &self.d, &mut self.partials);
            if slope.is_nan() || slope >= 0.0 || !slope.is_finite() {
                break NewtonStatus::BadDirection { slope };
            }

            // 4. inversion-free bound and backtracking line search
            let t3 = Instant::now();
            self.dx
                .par_iter_mut()
                .with_min_len(4096)
                .for_each(|v| *v = [0.0; D]);
            self.assembler
                .dofs()
                .scatter(&self.d, self.dx.as_flattened_mut());
            let alpha_max = self.assembler.max_step(&self.terms, x, &self.dx);
            let alpha0 = if alpha_max.is_finite() {
                (p.barrier_safety * alpha_max).min(1.0)
            } else {
                1.0
            };
            let (terms, assembler, xt, dx) =
                (&self.terms, &mut self.assembler, &mut self.xt, &self.dx);
            let ls = backtrack(energy, slope, alpha0, armijo, |alpha| {
                xt.par_iter_mut()
                    .zip(&*x)
                    .zip(dx)
                    .with_min_len(4096)
                    .for_each(|((t, x), d)| {
                        for c in 0..D {
                            t[c] = x[c] + alpha * d[c];
                        }
                    });
                assembler.energy(terms, xt, scale)
            });
            let t_line_search = t3.elapsed().as_secs_f64();
            times.line_search += t_line_search;
            let acc = match ls {
                Ok(a) => a,
                Err(last_step) => {
                    break NewtonStatus::LineSearchFailed {
                        last_step,
                        max_step: alpha_max.is_finite().then_some(alpha_max),
                    };
                }
            };

            // 5. trust-region ratio for the adaptive policies (raw curvature along d at the old x)
            let mut rho = None;
            let mut t_rho = 0.0;
            if p.filter_policy != FilterPolicy::Fixed {
                let t4 = Instant::now();
                let curv = self
                    .assembler
                    .raw_curvature(&self.terms, x, &self.dx, scale);
                let a = acc.alpha;
                let predicted = -(a * slope + 0.5 * a * a * curv);
                let r = (energy - acc.energy) / predicted;
                rho = Some(r);
                filter = p.filter_policy.next(p.filter, r, p.adaptive_threshold);
                t_rho = t4.elapsed().as_secs_f64();
                times.assembly += t_rho;
            }

            // 6. accept: x ← x + α d (the accepted α was the last one evaluated into xt)
            x.copy_from_slice(&self.xt);
            let record = IterationRecord {
                iter,
                energy,
                grad_inf,
                step: acc.alpha,
                max_step: alpha_max.is_finite().then_some(alpha_max),
                decrement: -slope,
                dx_inf: acc.alpha * norm_inf(&self.d),
                filter: format!("{used_filter:?}"),
                rho,
                shift: prep.shift,
                factorizations: prep.factorizations,
                cg_iterations: solve.iterations,
                line_search_evals: acc.evals,
                noise_limited: acc.noise_limited,
                t_assembly: t_assembly + t_rho,
                t_factor,
                t_solve,
                t_line_search,
            };
            iter += 1;
            let flow = callback(&record, x);
            records.push(record);
            if flow.is_break() {
                // report the energy and gradient of the returned positions
                let e = self
                    .assembler
                    .assemble(&self.terms, x, scale, &mut self.g, None);
                last = match e {
                    Ok(e) => (e, norm_inf(&self.g)),
                    Err(_) => (self.assembler.energy(&self.terms, x, scale), f64::INFINITY),
                };
                break NewtonStatus::Interrupted;
            }
        };
        times.total = t_start.elapsed().as_secs_f64();
        let (initial_energy, initial_grad_inf) = initial.unwrap_or(last);
        let chol = self.linear.cholesky();
        Ok(NewtonResult {
            status,
            iterations: iter,
            initial_energy,
            energy: last.0,
            initial_grad_inf,
            grad_inf: last.1,
            unknowns: self.g.len(),
            linear_solver: self.linear.kind(),
            symbolic_analyses: chol.map_or(0, |c| c.symbolic_analyses()),
            numeric_factorizations: chol.map_or(0, |c| c.numeric_factorizations()),
            times,
            terms: self.assembler.timings().to_vec(),
            records,
        })
    }
}
