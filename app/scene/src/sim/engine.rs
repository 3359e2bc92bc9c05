//! The frame loop of deformation, dynamics and interpolation scenes.
//!
//! The objective is exactly the sum of the terms the scene names (see
//! [`super::build`]); handles are Dirichlet vertices whose positions are
//! written before each solve. Per frame:
//!
//! * **quasi-static**: the handles (and the interpolation parameter t) move
//!   from the previous frame to this one in `substeps` solves, each
//!   warm-started from the previous; a move that would make the objective
//!   infinite (an element of a barrier energy inverted by the handle jump)
//!   is halved until it is feasible (down to 1/1024 of a frame);
//! * **dynamic**: `steps_per_frame` time steps (see [`crate::dynamics`]),
//!   each started from the inertial prediction x̃ (or from x_n when x̃ is
//!   infeasible), with the Rayleigh stiffness snapshot taken at x_n.

use std::any::Any;
use std::sync::Arc;
use std::time::Instant;

use ecc_fem::{
    Filter, IterationRecord, NewtonResult, NewtonSolver, NewtonStatus, Term, TermTiming,
};
use rayon::prelude::*;

use super::observer::Observer;
use crate::body::Body;
use crate::counters::Counters;
use crate::dynamics::Dynamics;
use crate::handles::Handle;
use crate::summary::{FrameStats, SolveLog, SolvePoint};
use crate::terms::{Blend, Gravity, Ground, MassMatrix, MassQuadratic, StiffnessDamping};

/// Where each effect term sits in the solver's term list.
#[derive(Clone, Copy, Debug, Default)]
pub struct Slots {
    /// The elastic term, or the interpolation blend.
    pub elastic: usize,
    /// Whether `elastic` is a [`Blend`].
    pub blend: bool,
    /// Gravity.
    pub gravity: Option<usize>,
    /// Inertia.
    pub inertia: Option<usize>,
    /// α M damping.
    pub damping_mass: Option<usize>,
    /// β K damping.
    pub damping_stiffness: Option<usize>,
    /// Ground contact.
    pub ground: Option<usize>,
}

/// A built scene, ready to step through frames.
pub struct Engine<const D: usize> {
    /// The body (rest shape, elements, energy).
    pub body: Body<D>,
    /// The solver over exactly the scene's terms.
    pub solver: NewtonSolver<D>,
    /// Term positions.
    pub slots: Slots,
    /// Handles (Dirichlet vertex sets).
    pub handles: Vec<Handle<D>>,
    /// The mass matrix (only with inertia).
    pub mass: Option<Arc<MassMatrix<D>>>,
    /// Integrator state (only with inertia).
    pub dynamics: Option<Dynamics<D>>,
    /// Time steps per frame (dynamics).
    pub steps_per_frame: usize,
    /// Interpolation steps (t = frame / steps), if interpolating.
    pub interp_steps: Option<usize>,
    /// Quasi-static solves per frame.
    pub substeps: usize,
    /// Filter for the Rayleigh stiffness snapshot.
    pub filter: Filter,
    /// Current positions.
    pub x: Vec<[f64; D]>,
    /// Counters shared by the terms.
    pub counters: Arc<Counters>,
    /// Every Newton solve so far.
    pub log: Vec<SolveLog>,
    /// Per-term cost summed over all solves.
    pub timings: Vec<TermTiming>,
    /// Set when a solve failed in a way that makes further frames meaningless.
    pub stopped: Option<String>,
    /// Seconds spent inside Newton solves so far (the time axis of the
    /// convergence plot: output writing between frames is not counted).
    solve_seconds: f64,
}

fn downcast<const D: usize, T: Term<D>>(t: &dyn Term<D>) -> Option<&T> {
    (t as &dyn Any).downcast_ref::<T>()
}

impl<const D: usize> Engine<D> {
    /// Assemble an engine from its parts (see [`super::build`]).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        body: Body<D>,
        solver: NewtonSolver<D>,
        slots: Slots,
        handles: Vec<Handle<D>>,
        mass: Option<Arc<MassMatrix<D>>>,
        dynamics: Option<Dynamics<D>>,
        steps_per_frame: usize,
        interp_steps: Option<usize>,
        substeps: usize,
        counters: Arc<Counters>,
    ) -> Self {
        let x = body.rest.clone();
        let filter = solver.params.filter;
        Engine {
            body,
            solver,
            slots,
            handles,
            mass,
            dynamics,
            steps_per_frame,
            interp_steps,
            substeps,
            filter,
            x,
            counters,
            log: Vec::new(),
            timings: Vec::new(),
            stopped: None,
            solve_seconds: 0.0,
        }
    }

    /// Seconds spent inside Newton solves so far.
    pub fn solve_seconds(&self) -> f64 {
        self.solve_seconds
    }

    fn term(&self, slot: usize) -> &dyn Term<D> {
        self.solver.terms()[slot].as_ref()
    }

    /// Write every handle's positions at (fractional) `frame` into `x`.
    fn place_handles(&mut self, frame: f64) {
        for h in &self.handles {
            for (&v, p) in h.vertices.iter().zip(h.positions_at(frame)) {
                self.x[v] = p;
            }
        }
    }

    fn set_t(&mut self, t: f64) {
        if self.slots.blend
            && let Some(b) = self.solver.term_mut::<Blend<D>>(self.slots.elastic)
        {
            b.t = t;
        }
    }

    fn t_of(&self, frame: f64) -> Option<f64> {
        self.interp_steps
            .map(|n| (frame / n as f64).clamp(0.0, 1.0))
    }

    /// Σ over a term's stencils of its value at `x` (parallel).
    fn term_value(&self, slot: usize, x: &[[f64; D]]) -> f64 {
        let t = self.term(slot);
        (0..t.n_stencils())
            .into_par_iter()
            .map(|s| t.value(s, x))
            .sum()
    }

    /// One Newton solve from `self.x`, logged and observed.
    fn solve(&mut self, frame: usize, obs: &mut dyn Observer) -> NewtonResult {
        let clock = Instant::now();
        let offset = self.solve_seconds;
        let mut points = Vec::new();
        let mut x = std::mem::take(&mut self.x);
        // a record describes the iterate at the *start* of its step: it is
        // plotted at the time that step began (the end of the previous one)
        let mut began = offset;
        let result = self.solver.solve_with(&mut x, |rec: &IterationRecord, _| {
            points.push(SolvePoint {
                grad_inf: rec.grad_inf,
                energy: rec.energy,
                seconds: began,
            });
            began = offset + clock.elapsed().as_secs_f64();
            obs.iteration(frame, rec)
        });
        self.x = x;
        self.solve_seconds += clock.elapsed().as_secs_f64();
        let result = match result {
            Ok(r) => r,
            Err(e) => {
                // positions were checked when the engine was built: a bug
                self.stopped = Some(format!("solver rejected the positions: {e}"));
                return failed_result();
            }
        };
        if result.status == NewtonStatus::Interrupted {
            self.stopped = Some(super::observer::INTERRUPTED.into());
        }
        points.push(SolvePoint {
            grad_inf: result.grad_inf,
            energy: result.energy,
            seconds: began,
        });
        for t in &result.terms {
            match self.timings.iter_mut().find(|a| a.name == t.name) {
                Some(a) => {
                    a.value_passes += t.value_passes;
                    a.value_seconds += t.value_seconds;
                    a.assembly_passes += t.assembly_passes;
                    a.assembly_seconds += t.assembly_seconds;
                }
                None => self.timings.push(t.clone()),
            }
        }
        self.log.push(SolveLog {
            frame,
            status: status_name(&result.status),
            iterations: result.iterations,
            points,
            times: result.times,
        });
        match &result.status {
            NewtonStatus::NonFinite(bad) => {
                self.stopped = Some(format!(
                    "non-finite {} in term `{}` (stencil {}) at frame {frame}",
                    bad.quantity, bad.term, bad.stencil
                ));
            }
            NewtonStatus::BadDirection { slope } => {
                self.stopped = Some(format!(
                    "non-descent Newton direction (slope {slope:e}) at frame {frame}"
                ));
            }
            NewtonStatus::FactorizationFailed { shift } => {
                self.stopped = Some(format!(
                    "Cholesky failed (shift {shift:e}) at frame {frame}"
                ));
            }
            _ => {}
        }
        result
    }

    /// Advance to `frame` (1-based) and report it.
    pub fn step_frame(&mut self, frame: usize, obs: &mut dyn Observer) -> FrameStats {
        let t0 = Instant::now();
        let first_log = self.log.len();
        if self.dynamics.is_some() {
            self.dynamic_frame(frame, obs);
        } else {
            self.quasi_static_frame(frame, obs);
        }
        let solves = &self.log[first_log..];
        let mut stats = self.frame_stats(frame);
        stats.solves = solves.len();
        stats.iterations = solves.iter().map(|s| s.iterations).sum();
        stats.statuses = solves.iter().map(|s| s.status.clone()).collect();
        stats.statuses.dedup();
        stats.converged = solves.iter().all(|s| s.status == "Converged");
        stats.grad_inf = solves
            .last()
            .and_then(|s| s.points.last())
            .map_or(f64::NAN, |p| p.grad_inf);
        stats.seconds = t0.elapsed().as_secs_f64();
        stats
    }

    fn quasi_static_frame(&mut self, frame: usize, obs: &mut dyn Observer) {
        let start = (frame - 1) as f64;
        let base = 1.0 / self.substeps as f64;
        let mut done = 0.0f64;
        let mut step = base;
        let saved = self.x.clone();
        while done < 1.0 - 1e-12 && self.stopped.is_none() {
            let f = (done + step).min(1.0);
            self.place_handles(start + f);
            if let Some(t) = self.t_of(start + f) {
                self.set_t(t);
            }
            let feasible = self.solver.energy(&self.x).is_ok_and(|e| e.is_finite());
            if !feasible {
                step *= 0.5;
                if step < base / 1024.0 {
                    self.x = saved;
                    self.stopped = Some(format!(
                        "frame {frame}: moving the handles inverts elements even in 1/1024 of a frame"
                    ));
                    return;
                }
                // retry from the last feasible positions
                continue;
            }
            self.solve(frame, obs);
            done = f;
            step = (step * 2.0).min(base);
        }
    }

    fn dynamic_frame(&mut self, frame: usize, obs: &mut dyn Observer) {
        let spf = self.steps_per_frame;
        for s in 0..spf {
            if self.stopped.is_some() {
                return;
            }
            let tau = (frame - 1) as f64 + (s + 1) as f64 / spf as f64;
            if let Some(t) = self.t_of(tau) {
                self.set_t(t);
            }
            let dynamics = self.dynamics.as_ref().expect("dynamic frame");
            let plan = dynamics.plan();
            let xn = dynamics.x.clone();
            let slots = self.slots;
            if let Some(i) = slots.inertia
                && let Some(q) = self.solver.term_mut::<MassQuadratic<D>>(i)
            {
                q.target.clone_from(&plan.predicted);
                q.weight = plan.inertia_weight;
            }
            if let Some(i) = slots.damping_mass
                && let Some(q) = self.solver.term_mut::<MassQuadratic<D>>(i)
            {
                q.target.clone_from(&plan.anchor);
                q.weight = q.coefficient * plan.a;
            }
            let filter = self.filter;
            if let Some(i) = slots.damping_stiffness
                && let Some(k) = self.solver.term_mut::<StiffnessDamping<D>>(i)
            {
                k.snapshot(&xn, filter);
                k.target.clone_from(&plan.anchor);
                k.weight = k.coefficient * plan.a;
            }
            // start from the prediction, or from x_n if that is infeasible
            self.x.clone_from(&plan.predicted);
            self.place_handles(tau);
            if !self.solver.energy(&self.x).is_ok_and(|e| e.is_finite()) {
                self.x.clone_from(&xn);
                self.place_handles(tau);
            }
            self.solve(frame, obs);
            let x = self.x.clone();
            if let Some(d) = self.dynamics.as_mut() {
                d.advance(&plan, &x);
            }
        }
    }

    /// Physical quantities at the current positions.
    pub fn frame_stats(&self, frame: usize) -> FrameStats {
        let x = &self.x;
        let measures = self.body.measures(x);
        let min_measure = measures.iter().copied().fold(f64::INFINITY, f64::min);
        let inverted = measures.iter().filter(|m| !(**m > 0.0)).count();
        let elastic = self.term_value(self.slots.elastic, x);
        let gravity = self
            .slots
            .gravity
            .and_then(|i| downcast::<D, Gravity<D>>(self.term(i)).map(|g| g.potential(x)));
        let (contact, min_ground) = match self
            .slots
            .ground
            .and_then(|i| downcast::<D, Ground<D>>(self.term(i)))
        {
            Some(g) => (Some(g.energy(x)), Some(g.min_distance(x))),
            None => (None, None),
        };
        let kinetic = match (&self.mass, &self.dynamics) {
            (Some(m), Some(d)) => Some(m.kinetic(&d.v)),
            _ => None,
        };
        let handle_error = (!self.handles.is_empty()).then(|| {
            let f = frame as f64;
            self.handles
                .iter()
                .flat_map(|h| {
                    h.vertices
                        .iter()
                        .zip(h.positions_at(f))
                        .map(|(&v, p)| dist(&x[v], &p))
                        .collect::<Vec<_>>()
                })
                .fold(0.0, f64::max)
        });
        let total =
            elastic + gravity.unwrap_or(0.0) + contact.unwrap_or(0.0) + kinetic.unwrap_or(0.0);
        FrameStats {
            frame,
            time: self.dynamics.as_ref().map(|d| d.steps as f64 * d.h),
            t: self.t_of(frame as f64),
            solves: 0,
            iterations: 0,
            statuses: Vec::new(),
            converged: true,
            grad_inf: f64::NAN,
            elastic_energy: elastic,
            gravity_potential: gravity,
            contact_energy: contact,
            kinetic_energy: kinetic,
            total_energy: total,
            min_measure,
            inverted,
            min_ground_distance: min_ground,
            handle_error,
            seconds: 0.0,
        }
    }
}

fn dist<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (0..D)
        .map(|c| (a[c] - b[c]) * (a[c] - b[c]))
        .sum::<f64>()
        .sqrt()
}

/// The status name used in summaries ("Converged", "MaxIterations", …).
pub fn status_name(s: &NewtonStatus) -> String {
    match s {
        NewtonStatus::Converged => "Converged",
        NewtonStatus::MaxIterations => "MaxIterations",
        NewtonStatus::LineSearchFailed { .. } => "LineSearchFailed",
        NewtonStatus::NonFinite(_) => "NonFinite",
        NewtonStatus::BadDirection { .. } => "BadDirection",
        NewtonStatus::FactorizationFailed { .. } => "FactorizationFailed",
        NewtonStatus::Interrupted => "Interrupted",
    }
    .to_string()
}

fn failed_result() -> NewtonResult {
    NewtonResult {
        status: NewtonStatus::Interrupted,
        iterations: 0,
        initial_energy: f64::NAN,
        energy: f64::NAN,
        initial_grad_inf: f64::NAN,
        grad_inf: f64::NAN,
        unknowns: 0,
        linear_solver: ecc_fem::LinearSolver::Auto,
        symbolic_analyses: 0,
        numeric_factorizations: 0,
        times: Default::default(),
        terms: Vec::new(),
        records: Vec::new(),
    }
}
