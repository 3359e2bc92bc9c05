//! Running scenes: the orchestration (`run`), the shared context and
//! report (`context`), the frame loop, parameterisation, frame writers,
//! progress reporting.

pub mod build;
mod context;
pub mod engine;
mod frames;
mod handle_move;
mod journal;
pub mod observer;
mod param;
mod run;
mod target;
mod view;
mod writers;

pub use context::{FinalState, RunOptions, RunReport, output_folder};
pub use engine::Engine;
pub use observer::{FrameLines, Observer, Silent};
pub use run::run_scene;
