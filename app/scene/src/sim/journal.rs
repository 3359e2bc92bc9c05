//! The record of a run's Newton solves: one [`SolveLog`] per solve (its
//! convergence points on the solve-time axis), the per-term cost summed over
//! all solves, the seconds spent solving, and why the run stopped, if it did.

use std::time::Instant;

use ecc_fem::{FemError, IterationRecord, NewtonResult, NewtonStatus, TermTiming};

use crate::summary::{LinearWork, SolveLog, SolvePoint};

/// Every solve of a run so far.
#[derive(Debug, Default)]
pub struct Journal {
    /// Every Newton solve so far.
    pub log: Vec<SolveLog>,
    /// Per-term cost summed over all solves.
    pub timings: Vec<TermTiming>,
    /// Set when a solve failed in a way that makes further frames meaningless.
    pub stopped: Option<String>,
    /// Seconds spent inside Newton solves so far (the time axis of the
    /// convergence plot: output writing between frames is not counted).
    pub solve_seconds: f64,
}

/// One solve being recorded: its convergence points and their times.
pub struct Recording {
    clock: Instant,
    offset: f64,
    /// When the step of the next record began (the end of the previous one).
    began: f64,
    points: Vec<SolvePoint>,
}

impl Recording {
    /// A solve that starts now, `offset` solve-seconds into the run.
    pub fn start(offset: f64) -> Self {
        Recording {
            clock: Instant::now(),
            offset,
            began: offset,
            points: Vec::new(),
        }
    }

    /// A Newton step: its record describes the iterate at the *start* of
    /// the step, plotted at the time that step began.
    pub fn iteration(&mut self, rec: &IterationRecord) {
        self.points.push(SolvePoint {
            grad_inf: rec.grad_inf,
            energy: rec.energy,
            seconds: self.began,
        });
        self.began = self.offset + self.clock.elapsed().as_secs_f64();
    }
}

impl Journal {
    /// Close the recording of a solve of `frame` that ended with `result`.
    pub fn finish(
        &mut self,
        frame: usize,
        mut rec: Recording,
        result: Result<&NewtonResult, &FemError>,
    ) {
        self.solve_seconds += rec.clock.elapsed().as_secs_f64();
        let result = match result {
            Ok(r) => r,
            Err(e) => {
                // positions were checked when the engine was built: a bug
                self.stopped = Some(format!("solver rejected the positions: {e}"));
                return;
            }
        };
        rec.points.push(SolvePoint {
            grad_inf: result.grad_inf,
            energy: result.energy,
            seconds: rec.began,
        });
        self.add_timings(&result.terms);
        self.log.push(SolveLog {
            frame,
            status: status_name(&result.status),
            iterations: result.iterations,
            points: rec.points,
            times: result.times,
            linear: LinearWork::of_solve(result),
        });
        if let Some(why) = stop_reason(&result.status, frame) {
            self.stopped = Some(why);
        }
    }

    fn add_timings(&mut self, terms: &[TermTiming]) {
        for t in terms {
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
    }
}

/// Why a solve that ended with `status` stops the run (None: it goes on).
fn stop_reason(status: &NewtonStatus, frame: usize) -> Option<String> {
    match status {
        NewtonStatus::Interrupted => Some(super::observer::INTERRUPTED.into()),
        NewtonStatus::NonFinite(bad) => Some(format!(
            "non-finite {} in term `{}` (stencil {}) at frame {frame}",
            bad.quantity, bad.term, bad.stencil
        )),
        NewtonStatus::BadDirection { slope } => Some(format!(
            "non-descent Newton direction (slope {slope:e}) at frame {frame}"
        )),
        NewtonStatus::FactorizationFailed { shift } => Some(format!(
            "Cholesky failed (shift {shift:e}) at frame {frame}"
        )),
        NewtonStatus::Converged
        | NewtonStatus::MaxIterations
        | NewtonStatus::LineSearchFailed { .. } => None,
    }
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
