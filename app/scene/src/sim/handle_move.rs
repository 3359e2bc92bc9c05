//! One quasi-static frame as a move of the library's handle deformation
//! ([`ecc_fem::deform::move_handles`]): the keyframed handles and the
//! interpolation parameter t go from frame f − 1 to frame f; every solve is
//! recorded in the run's [`Journal`] and reported to the observer, and a
//! solve that stops the run ends the move.

use std::ops::ControlFlow;

use ecc_fem::deform::HandleMove;
use ecc_fem::{IterationRecord, NewtonResult, NewtonSolver};

use super::journal::{Journal, Recording};
use super::observer::Observer;
use crate::handles::Handle;
use crate::terms::Blend;

/// Write every handle's positions at (fractional) `frame` into `x`.
pub(super) fn place_handles<const D: usize>(handles: &[Handle<D>], frame: f64, x: &mut [[f64; D]]) {
    for h in handles {
        for (&v, p) in h.vertices.iter().zip(h.positions_at(frame)) {
            x[v] = p;
        }
    }
}

/// The interpolation parameter t at (fractional) `frame`, if interpolating
/// over `steps` frames.
pub(super) fn t_of(steps: Option<usize>, frame: f64) -> Option<f64> {
    steps.map(|n| (frame / n as f64).clamp(0.0, 1.0))
}

/// Set t of the interpolation blend at term `slot` (no-op without one).
pub(super) fn set_t<const D: usize>(solver: &mut NewtonSolver<D>, blend: Option<usize>, t: f64) {
    if let Some(slot) = blend
        && let Some(b) = solver.term_mut::<Blend<D>>(slot)
    {
        b.t = t;
    }
}

/// Frame `frame`'s move (see the module docs).
pub(super) struct FrameMove<'a, const D: usize> {
    /// The frame being reached (1-based).
    pub frame: usize,
    /// The handles.
    pub handles: &'a [Handle<D>],
    /// The term slot of the interpolation blend, if any.
    pub blend: Option<usize>,
    /// Interpolation steps, if interpolating.
    pub interp_steps: Option<usize>,
    /// Where solves are recorded.
    pub journal: &'a mut Journal,
    /// Progress reports (and stop requests).
    pub obs: &'a mut dyn Observer,
    /// The solve in progress.
    pub recording: Option<Recording>,
}

impl<const D: usize> HandleMove<D> for FrameMove<'_, D> {
    fn place(&mut self, f: f64, solver: &mut NewtonSolver<D>, x: &mut [[f64; D]]) {
        let at = (self.frame - 1) as f64 + f;
        place_handles(self.handles, at, x);
        if let Some(t) = t_of(self.interp_steps, at) {
            set_t(solver, self.blend, t);
        }
    }

    fn before_solve(&mut self) {
        self.recording = Some(Recording::start(self.journal.solve_seconds));
    }

    fn iteration(&mut self, rec: &IterationRecord, _x: &[[f64; D]]) -> ControlFlow<()> {
        if let Some(r) = self.recording.as_mut() {
            r.iteration(rec);
        }
        self.obs.iteration(self.frame, rec)
    }

    fn solved(&mut self, result: &NewtonResult) -> ControlFlow<()> {
        if let Some(rec) = self.recording.take() {
            self.journal.finish(self.frame, rec, Ok(result));
        }
        if self.journal.stopped.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}
