//! Running scenes: building the objective, the frame loop, parameterisation,
//! progress reporting.

pub mod build;
pub mod engine;
pub mod observer;
mod param;
mod run;

pub use engine::Engine;
pub use observer::{FrameLines, Observer, Silent};
pub use run::{FinalState, RunOptions, RunReport, output_folder, run_scene};
