//! Progress reporting: an [`Observer`] sees frames and Newton iterations.
//! The scene only reports; drawing is the caller's business (the `ecc` CLI
//! draws a progress bar). [`Silent`] ignores everything and [`FrameLines`]
//! prints one plain line per frame on stderr.

use std::ops::ControlFlow;

use ecc_fem::IterationRecord;

use crate::summary::FrameStats;

/// Why a run stopped when an observer returned `Break` (summary `stopped`).
pub(crate) const INTERRUPTED: &str = "interrupted (the progress observer asked to stop)";

/// Receives progress events (all methods default to doing nothing).
pub trait Observer {
    /// The run starts with `frames` frames to compute.
    fn start(&mut self, _name: &str, _frames: usize) {}
    /// A Newton iteration of `frame` was accepted. `Break` stops the run:
    /// the solve ends with status `Interrupted`, the run stops early (what was
    /// computed is written, the summary says why).
    fn iteration(&mut self, _frame: usize, _rec: &IterationRecord) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// `frame` is done.
    fn frame_done(&mut self, _stats: &FrameStats) {}
    /// A phase message (writing pictures, …).
    fn note(&mut self, _msg: &str) {}
    /// The run is over.
    fn finish(&mut self) {}
}

/// Ignores everything.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Observer for Silent {}

/// One plain line per finished frame on stderr (`name: frame 3/24, 5 Newton
/// iterations, |∇E|∞ 1.2e-7`), for examples and tools without a terminal UI.
#[derive(Clone, Debug, Default)]
pub struct FrameLines {
    name: String,
    frames: usize,
}

impl Observer for FrameLines {
    fn start(&mut self, name: &str, frames: usize) {
        self.name = name.to_string();
        self.frames = frames;
    }

    fn frame_done(&mut self, stats: &FrameStats) {
        eprintln!(
            "{}: frame {}/{}, {} Newton iterations, |∇E|∞ {:.2e}",
            self.name, stats.frame, self.frames, stats.iterations, stats.grad_inf
        );
    }

    fn note(&mut self, msg: &str) {
        eprintln!("{}: {msg}", self.name);
    }
}
