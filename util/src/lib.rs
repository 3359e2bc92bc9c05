//! # ecc-util: the few helpers every layer needs (std only)
//!
//! * [`atomic`]: write a file atomically (temporary file in the same folder,
//!   flushed, synced, renamed over the destination), so a reader never sees a
//!   partial file and a failed write leaves any old file untouched. Used by
//!   the mesh writers, the scene's output folder and the CLI's `-o`.
//! * [`suggest`](mod@suggest): "did you mean …?" — the closest known name by edit
//!   distance, with one documented threshold, for the `.psi` front end, scene
//!   keys and values, and energy names.
//! * [`simd`]: `vzeroupper` after runtime-dispatched AVX code (faer's
//!   dense kernels), so the scalar maths that follows on that thread runs at
//!   full speed.
//!
//! Errors are plain [`std::io::Error`]s; callers wrap them in their own typed
//! errors with the path.

pub mod atomic;
pub mod simd;
pub mod suggest;

pub use atomic::{write_atomic, write_atomic_with};
pub use simd::clear_upper_simd;
pub use suggest::{edit_distance, suggest, suggest_among};
