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
//!   is halved until it is feasible (down to 1/1024 of a substep): the
//!   library's handle deformation, [`ecc_fem::deform::move_handles`], driven
//!   by `super::handle_move::FrameMove`;
//! * **dynamic**: `steps_per_frame` time steps (see [`crate::dynamics`]),
//!   each started from the inertial prediction x̃ (or from x_n when x̃ is
//!   infeasible), with the Rayleigh stiffness snapshot taken at x_n.

use std::any::Any;
use std::sync::Arc;
use std::time::Instant;

use ecc_fem::deform::{MoveEnd, Substeps, feasible, move_handles};
use ecc_fem::{Filter, NewtonSolver, Term};
use rayon::prelude::*;

use super::handle_move::{FrameMove, place_handles, set_t, t_of};
use super::journal::{Journal, Recording};
use super::observer::Observer;
use crate::body::Body;
use crate::counters::Counters;
use crate::dynamics::Dynamics;
use crate::handles::Handle;
use crate::summary::FrameStats;
use crate::terms::{Gravity, Ground, MassMatrix, MassQuadratic, StiffnessDamping};

/// Where each effect term sits in the solver's term list.
#[derive(Clone, Copy, Debug, Default)]
pub struct Slots {
    /// The elastic term, or the interpolation blend.
    pub elastic: usize,
    /// Whether `elastic` is a `Blend`.
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
    /// Every Newton solve so far, and why the run stopped (if it did).
    pub journal: Journal,
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
            journal: Journal::default(),
        }
    }

    fn term(&self, slot: usize) -> &dyn Term<D> {
        self.solver.terms()[slot].as_ref()
    }

    /// The term slot of the interpolation blend, if any.
    fn blend(&self) -> Option<usize> {
        self.slots.blend.then_some(self.slots.elastic)
    }

    /// Σ over a term's stencils of its value at `x` (parallel).
    fn term_value(&self, slot: usize, x: &[[f64; D]]) -> f64 {
        let t = self.term(slot);
        (0..t.n_stencils())
            .into_par_iter()
            .map(|s| t.value(s, x))
            .sum()
    }

    /// One Newton solve from `self.x`, recorded and observed.
    fn solve(&mut self, frame: usize, obs: &mut dyn Observer) {
        let mut rec = Recording::start(self.journal.solve_seconds);
        let result = self.solver.solve_with(&mut self.x, |r, _| {
            rec.iteration(r);
            obs.iteration(frame, r)
        });
        self.journal.finish(frame, rec, result.as_ref());
    }

    /// Advance to `frame` (1-based) and report it.
    pub fn step_frame(&mut self, frame: usize, obs: &mut dyn Observer) -> FrameStats {
        let t0 = Instant::now();
        let first_log = self.journal.log.len();
        if self.dynamics.is_some() {
            self.dynamic_frame(frame, obs);
        } else {
            self.quasi_static_frame(frame, obs);
        }
        let solves = &self.journal.log[first_log..];
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

    /// The handles (and t) from frame − 1 to frame through the library's
    /// handle deformation (see the module docs).
    fn quasi_static_frame(&mut self, frame: usize, obs: &mut dyn Observer) {
        let substeps = Substeps::new(self.substeps);
        let blend = self.blend();
        let mut mv = FrameMove {
            frame,
            handles: &self.handles,
            blend,
            interp_steps: self.interp_steps,
            journal: &mut self.journal,
            obs,
            recording: None,
        };
        match move_handles(&mut self.solver, &mut self.x, substeps, &mut mv) {
            Err(e) => {
                // only a solve can fail (a rejected placement is infeasible)
                let rec = mv.recording.take().unwrap_or_else(|| Recording::start(0.0));
                mv.journal.finish(frame, rec, Err(&e));
            }
            Ok(m) if matches!(m.end, MoveEnd::Infeasible { .. }) => {
                self.journal.stopped = Some(format!(
                    "frame {frame}: moving the handles inverts elements even in 1/{} of a frame",
                    1u64 << substeps.max_halvings
                ));
            }
            Ok(_) => {}
        }
    }

    fn dynamic_frame(&mut self, frame: usize, obs: &mut dyn Observer) {
        let spf = self.steps_per_frame;
        for s in 0..spf {
            if self.journal.stopped.is_some() {
                return;
            }
            let tau = (frame - 1) as f64 + (s + 1) as f64 / spf as f64;
            if let Some(t) = t_of(self.interp_steps, tau) {
                let blend = self.blend();
                set_t(&mut self.solver, blend, t);
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
            place_handles(&self.handles, tau, &mut self.x);
            if !feasible(&mut self.solver, &self.x) {
                self.x.clone_from(&xn);
                place_handles(&self.handles, tau, &mut self.x);
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
            t: t_of(self.interp_steps, frame as f64),
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
