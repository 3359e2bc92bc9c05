//! One projected Newton iteration, phase by phase (steps 1–4 of the
//! [module docs](super), plus the trust-region ratio of the adaptive
//! policies and the accepted step's record). Each phase either returns its
//! result or the [`NewtonStatus`] the solve stops with.

use std::ops::ControlFlow;
use std::time::Instant;

use ecc_runtime::filter::Filter;
use rayon::prelude::*;

use super::line_search::{Accepted, Armijo, backtrack, extrapolation, initial_step};
use super::params::{FilterPolicy, NewtonParams};
use super::record::{IterationRecord, NewtonStatus, TimeSplit};
use super::solver::NewtonSolver;
use crate::linear::{PrepareInfo, SolveInfo};
use crate::parallel::{dot, norm_inf};

/// What one call of `solve_with` carries from iteration to iteration.
pub(super) struct SolveState {
    pub(super) p: NewtonParams,
    armijo: Armijo,
    /// Diagonal shift for the translation null space (nothing fixed).
    null_shift: f64,
    pub(super) times: TimeSplit,
    pub(super) records: Vec<IterationRecord>,
    /// Filter of the next assembly (changed by the adaptive policies).
    filter: Filter,
    /// Last relative shift that made a raw (unfiltered) Hessian factorable.
    raw_shift: f64,
    /// (energy, ‖∇E‖∞) at the start.
    pub(super) initial: Option<(f64, f64)>,
    /// (energy, ‖∇E‖∞) of the current positions, set by every exit path.
    pub(super) last: (f64, f64),
    /// Accepted steps so far.
    pub(super) iter: usize,
}

impl SolveState {
    pub(super) fn new(p: NewtonParams, n_fixed: usize) -> Self {
        let null_shift = if n_fixed == 0 {
            p.null_space_shift
        } else {
            0.0
        };
        SolveState {
            armijo: Armijo {
                c1: p.armijo_c1,
                beta: p.backtrack,
                min_step: p.min_step,
            },
            null_shift,
            times: TimeSplit::default(),
            records: Vec::new(),
            filter: p.filter_policy.first(p.filter),
            raw_shift: 0.0,
            initial: None,
            last: (f64::INFINITY, f64::INFINITY),
            iter: 0,
            p,
        }
    }
}

/// Step 1's result: E(x), with ∇E in `g` and H in `values`.
struct Assembled {
    energy: f64,
    grad_inf: f64,
    /// ‖∇E₀‖∞, the reference of the relative tolerances.
    g0: f64,
    used_filter: Filter,
    t_assembly: f64,
}

/// Step 3's result: the direction d in `d`.
struct Direction {
    prep: PrepareInfo,
    solve: SolveInfo,
    /// Solved with CG preconditioned by a stale factor (no factorisation).
    reused: bool,
    /// ∇Eᵀd < 0.
    slope: f64,
    t_factor: f64,
    t_solve: f64,
}

/// Step 4's result: x + αd in `xt`.
struct Step {
    acc: Accepted,
    alpha_max: f64,
    t_line_search: f64,
}

impl<const D: usize> NewtonSolver<D> {
    /// One iteration from `x`: `Err(status)` when the solve stops.
    pub(super) fn iteration(
        &mut self,
        x: &mut [[f64; D]],
        s: &mut SolveState,
        callback: &mut impl FnMut(&IterationRecord, &[[f64; D]]) -> ControlFlow<()>,
    ) -> Result<(), NewtonStatus> {
        let a = self.assemble_iterate(x, s)?;
        if a.grad_inf <= s.p.tol_abs || a.grad_inf <= s.p.tol_rel * a.g0 {
            return Err(NewtonStatus::Converged);
        }
        if s.iter >= s.p.max_iters {
            return Err(NewtonStatus::MaxIterations);
        }
        let mut dir = self.direction(s, &a)?;
        let step = match self.line_search(x, s, a.energy, dir.slope) {
            Ok(step) => step,
            // a reused factor's direction failed: retry once with a fresh factor
            Err(_) if dir.reused => {
                let pattern = self.assembler.pattern();
                self.linear
                    .unshift(pattern, &mut self.values, dir.prep.shift);
                let cg = dir.solve.iterations;
                dir = self.fresh_direction(s, &a, cg, dir.t_solve)?;
                self.line_search(x, s, a.energy, dir.slope)?
            }
            Err(status) => return Err(status),
        };
        let (rho, t_rho) = self.trust_ratio(x, s, &a, &dir, &step);
        // accept: x ← x + α d (the accepted α was the last one evaluated into xt)
        x.copy_from_slice(&self.xt);
        let record = self.record(s, &a, &dir, &step, rho, t_rho);
        s.iter += 1;
        let flow = callback(&record, x);
        s.records.push(record);
        if flow.is_break() {
            s.last = self.energy_and_gradient(x, s.p.energy_scale);
            return Err(NewtonStatus::Interrupted);
        }
        Ok(())
    }

    /// Step 1: assemble E, ∇E and the filtered Hessian at `x`; with the raw
    /// Hessian (`Filter::None`) singular somewhere, filter this iteration.
    fn assemble_iterate(
        &mut self,
        x: &[[f64; D]],
        s: &mut SolveState,
    ) -> Result<Assembled, NewtonStatus> {
        let t0 = Instant::now();
        let scale = s.p.energy_scale;
        let mut used_filter = s.filter;
        let mut assembled = self.assembler.assemble(
            &self.terms,
            x,
            scale,
            &mut self.g,
            Some((s.filter, &mut self.values)),
        );
        if s.filter == Filter::None && matches!(&assembled, Err(b) if b.quantity == "hessian") {
            used_filter = s.p.filter;
            assembled = self.assembler.assemble(
                &self.terms,
                x,
                scale,
                &mut self.g,
                Some((s.p.filter, &mut self.values)),
            );
        }
        let t_assembly = t0.elapsed().as_secs_f64();
        s.times.assembly += t_assembly;
        let energy = match assembled {
            Ok(e) => e,
            Err(bad) => {
                // report the energy of x (+∞ if a stencil is outside its domain
                // or NaN) and an unknown (+∞) gradient norm, never NaN
                s.last = (self.assembler.energy(&self.terms, x, scale), f64::INFINITY);
                return Err(NewtonStatus::NonFinite(bad));
            }
        };
        let grad_inf = norm_inf(&self.g);
        let g0 = s.initial.get_or_insert((energy, grad_inf)).1;
        s.last = (energy, grad_inf);
        Ok(Assembled {
            energy,
            grad_inf,
            g0,
            used_filter,
            t_assembly,
        })
    }

    /// Step 3: solve (H + δI) d = −∇E, first with the stale factor when the
    /// reuse policy allows it (see [`crate::linear::reuse`]), else with a
    /// fresh factorisation (or PCG).
    fn direction(&mut self, s: &mut SolveState, a: &Assembled) -> Result<Direction, NewtonStatus> {
        let reuse = s.p.factor_reuse;
        let pattern = self.assembler.pattern();
        let budget = self.linear.stale_budget(pattern, &reuse, &s.p.auto_limits);
        if budget == 0 || a.used_filter == Filter::None {
            return self.fresh_direction(s, a, 0, 0.0);
        }
        let t = Instant::now();
        let prep = self
            .linear
            .shift_only(pattern, &mut self.values, s.null_shift);
        self.rhs.iter_mut().zip(&self.g).for_each(|(r, g)| *r = -g);
        let target = reuse.target(forcing(s, a));
        let solve = self.linear.solve_stale(
            pattern,
            &self.values,
            &self.rhs,
            &mut self.d,
            target,
            budget,
        );
        let t_solve = t.elapsed().as_secs_f64();
        s.times.solve += t_solve;
        let Some(solve) = solve else {
            self.linear.unshift(pattern, &mut self.values, prep.shift);
            return self.fresh_direction(s, a, 0, t_solve);
        };
        let slope = dot(&self.g, &self.d, &mut self.partials);
        let converged = !solve.negative_curvature && solve.relative_residual <= target;
        if converged && slope.is_finite() && slope < 0.0 {
            return Ok(Direction {
                prep,
                solve,
                reused: true,
                slope,
                t_factor: 0.0,
                t_solve,
            });
        }
        self.linear.unshift(pattern, &mut self.values, prep.shift);
        self.fresh_direction(s, a, solve.iterations, t_solve)
    }

    /// Step 3 with a new factorisation (or PCG); `cg_before`/`t_before`:
    /// CG iterations and seconds of a stale-factor attempt this step gave up.
    /// A raw Hessian starts from a tenth of the last shift that made a raw
    /// Hessian factorable.
    fn fresh_direction(
        &mut self,
        s: &mut SolveState,
        a: &Assembled,
        cg_before: usize,
        t_before: f64,
    ) -> Result<Direction, NewtonStatus> {
        let raw = a.used_filter == Filter::None;
        let base_shift = if raw {
            s.null_shift.max(0.1 * s.raw_shift)
        } else {
            s.null_shift
        };
        let t1 = Instant::now();
        let prep = self.linear.prepare(
            self.assembler.pattern(),
            &mut self.values,
            base_shift,
            s.p.shift_attempts,
        );
        let t_factor = t1.elapsed().as_secs_f64();
        s.times.factor += t_factor;
        let prep = prep.map_err(|f| NewtonStatus::FactorizationFailed { shift: f.shift })?;
        if raw {
            s.raw_shift = prep.relative_shift;
        }
        let t2 = Instant::now();
        self.rhs.iter_mut().zip(&self.g).for_each(|(r, g)| *r = -g);
        let mut solve = self.linear.solve(
            self.assembler.pattern(),
            &self.values,
            &self.rhs,
            &mut self.d,
            forcing(s, a),
            s.p.pcg_max_iters,
        );
        solve.iterations += cg_before;
        let t_solve = t2.elapsed().as_secs_f64();
        s.times.solve += t_solve;
        let slope = dot(&self.g, &self.d, &mut self.partials);
        if slope.is_nan() || slope >= 0.0 || !slope.is_finite() {
            return Err(NewtonStatus::BadDirection { slope });
        }
        Ok(Direction {
            prep,
            solve,
            reused: false,
            slope,
            t_factor,
            t_solve: t_solve + t_before,
        })
    }

    /// Step 4: inversion-free bound α_max and backtracking Armijo search from
    /// α₀ = min(1, `barrier_safety`·α_max), then (with `extrapolate`) one
    /// longer step when the full one passed unbounded; leaves x + αd in `xt`.
    fn line_search(
        &mut self,
        x: &[[f64; D]],
        s: &mut SolveState,
        energy: f64,
        slope: f64,
    ) -> Result<Step, NewtonStatus> {
        let t3 = Instant::now();
        self.dx
            .par_iter_mut()
            .with_min_len(4096)
            .for_each(|v| *v = [0.0; D]);
        self.assembler
            .dofs()
            .scatter(&self.d, self.dx.as_flattened_mut());
        let alpha_max = self.assembler.max_step(&self.terms, x, &self.dx);
        let alpha0 = initial_step(alpha_max, s.p.barrier_safety);
        let scale = s.p.energy_scale;
        let (terms, assembler, xt, dx) = (&self.terms, &mut self.assembler, &mut self.xt, &self.dx);
        let mut energy_at = |alpha: f64| {
            xt.par_iter_mut()
                .zip(x)
                .zip(dx)
                .with_min_len(4096)
                .for_each(|((t, x), d)| {
                    for c in 0..D {
                        t[c] = x[c] + alpha * d[c];
                    }
                });
            assembler.energy(terms, xt, scale)
        };
        let mut ls = backtrack(energy, slope, alpha0, s.armijo, &mut energy_at);
        if let Ok(acc) = &mut ls
            && s.p.extrapolate
            && acc.alpha == 1.0
            && !acc.noise_limited
            && let Some(alpha) = extrapolation(energy, slope, acc.energy, alpha_max)
        {
            let e = energy_at(alpha);
            acc.evals += 1;
            if e < acc.energy {
                (acc.alpha, acc.energy) = (alpha, e);
            } else {
                // back to x + d (NaN and +∞ land here too)
                energy_at(1.0);
                acc.evals += 1;
            }
        }
        let t_line_search = t3.elapsed().as_secs_f64();
        s.times.line_search += t_line_search;
        let acc = ls.map_err(|last_step| NewtonStatus::LineSearchFailed {
            last_step,
            max_step: alpha_max.is_finite().then_some(alpha_max),
        })?;
        Ok(Step {
            acc,
            alpha_max,
            t_line_search,
        })
    }

    /// Step 5: trust-region ratio ρ of the adaptive policies (raw curvature along
    /// d at the old x), which picks the next filter; `(None, 0)` for `Fixed`.
    fn trust_ratio(
        &mut self,
        x: &[[f64; D]],
        s: &mut SolveState,
        a: &Assembled,
        dir: &Direction,
        step: &Step,
    ) -> (Option<f64>, f64) {
        if s.p.filter_policy == FilterPolicy::Fixed {
            return (None, 0.0);
        }
        let t4 = Instant::now();
        let curv = if a.used_filter == Filter::None {
            // the assembled values are the raw Hessian at x plus the
            // solver's diagonal shift δ: dᵀ H d = dᵀ (H + δI) d − δ‖d‖²
            // from them, without a second pass over the elements (equal to
            // raw_curvature to 1e-8 relative or better on camelhead and
            // armadillo_cut_low)
            let pattern = self.assembler.pattern();
            let shifted = pattern.quadratic_form(&self.values, &self.d, &mut self.partials);
            shifted - dir.prep.shift * dot(&self.d, &self.d, &mut self.partials)
        } else {
            self.assembler
                .raw_curvature(&self.terms, x, &self.dx, s.p.energy_scale)
        };
        let al = step.acc.alpha;
        let predicted = -(al * dir.slope + 0.5 * al * al * curv);
        let r = (a.energy - step.acc.energy) / predicted;
        s.filter =
            s.p.filter_policy
                .next(s.p.filter, r, s.p.adaptive_threshold);
        let t_rho = t4.elapsed().as_secs_f64();
        s.times.assembly += t_rho;
        (Some(r), t_rho)
    }

    /// Step 6: the record of the accepted step.
    fn record(
        &self,
        s: &SolveState,
        a: &Assembled,
        dir: &Direction,
        step: &Step,
        rho: Option<f64>,
        t_rho: f64,
    ) -> IterationRecord {
        IterationRecord {
            iter: s.iter,
            energy: a.energy,
            grad_inf: a.grad_inf,
            step: step.acc.alpha,
            max_step: step.alpha_max.is_finite().then_some(step.alpha_max),
            decrement: -dir.slope,
            dx_inf: step.acc.alpha * norm_inf(&self.d),
            filter: format!("{:?}", a.used_filter),
            rho,
            shift: dir.prep.shift,
            factorizations: dir.prep.factorizations + dir.solve.factorizations,
            cg_iterations: dir.solve.iterations,
            reused_factor: dir.reused,
            line_search_evals: step.acc.evals,
            noise_limited: step.acc.noise_limited,
            t_assembly: a.t_assembly + t_rho,
            t_factor: dir.t_factor,
            t_solve: dir.t_solve,
            t_line_search: step.t_line_search,
        }
    }

    /// Energy and ‖∇E‖∞ of the returned positions (+∞ gradient norm when
    /// it cannot be evaluated).
    fn energy_and_gradient(&mut self, x: &[[f64; D]], scale: f64) -> (f64, f64) {
        let e = self
            .assembler
            .assemble(&self.terms, x, scale, &mut self.g, None);
        match e {
            Ok(e) => (e, norm_inf(&self.g)),
            Err(_) => (self.assembler.energy(&self.terms, x, scale), f64::INFINITY),
        }
    }
}

/// The inexact-Newton forcing term η_k = clamp(√(‖∇E_k‖∞/‖∇E₀‖∞),
/// `pcg_rel_min`, `pcg_rel_max`) (module docs, step 3).
fn forcing(s: &SolveState, a: &Assembled) -> f64 {
    (a.grad_inf / a.g0)
        .sqrt()
        .clamp(s.p.pcg_rel_min, s.p.pcg_rel_max)
}
