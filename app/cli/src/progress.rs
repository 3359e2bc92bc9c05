//! The progress bar of `ecc sim` / `ecc demo`: an [`Observer`] of the scene
//! run that draws an indicatif bar on stderr (frames, plus the current Newton
//! iteration and gradient norm). It draws nothing when stderr is not a
//! terminal or when asked to be quiet (`--quiet`).

use std::ops::ControlFlow;

use ecc_fem::IterationRecord;
use ecc_scene::Observer;
use ecc_scene::summary::FrameStats;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// An indicatif progress bar on stderr.
pub struct Progress {
    bar: ProgressBar,
    iterations: usize,
    quiet: bool,
}

impl Progress {
    /// A bar (hidden when `quiet` or when stderr is not a terminal).
    pub fn new(quiet: bool) -> Self {
        // hidden until the frame count is known (see `start`)
        let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::hidden());
        let style = ProgressStyle::with_template(
            "{prefix:.bold} [{bar:30.cyan/blue}] frame {pos}/{len} {msg} ({elapsed})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
        bar.set_style(style);
        Progress {
            bar,
            iterations: 0,
            quiet,
        }
    }
}

impl Observer for Progress {
    fn start(&mut self, name: &str, frames: usize) {
        self.bar.set_prefix(name.to_string());
        self.bar.set_length(frames as u64);
        self.bar.set_position(0);
        if !self.quiet {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }

    fn iteration(&mut self, _frame: usize, rec: &IterationRecord) -> ControlFlow<()> {
        self.iterations += 1;
        self.bar.set_message(format!(
            "| newton {} (total {}) |∇E|∞ {:.2e}",
            rec.iter + 1,
            self.iterations,
            rec.grad_inf
        ));
        ControlFlow::Continue(())
    }

    fn frame_done(&mut self, stats: &FrameStats) {
        self.bar.set_position(stats.frame as u64);
    }

    fn note(&mut self, msg: &str) {
        self.bar.set_message(format!("| {msg}"));
    }

    fn finish(&mut self) {
        self.bar.finish_and_clear();
    }
}
