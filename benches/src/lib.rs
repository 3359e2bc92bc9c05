//! # ecc-benches: what accuracy costs in time
//!
//! Criterion benchmarks (`benches/`) and the **report** (`src/bin/report.rs`):
//!
//! ```text
//! cargo run --release -p ecc-benches --bin report -- [--quick] [--out DIR]
//! ```
//!
//! writes `BENCHMARKS.md` and PNG plots into `DIR` (default
//! `docs/benchmarks/`). See [`report`] for what is measured and how.
//!
//! Modules: [`real`] / [`dd`] (number types, from `ecc-tests`), [`graph_eval`] (the CAS graph in
//! any precision), [`linalg`] (Jacobi eigen / signed SVD in any precision),
//! [`generic_kernel`] (the f32/f64 element kernel), [`reference`](mod@reference) (the
//! double-double reference), [`cases`] (hard F), [`energies`] (the energy set),
//! [`element`] (per-element timing and accuracy), [`solve`] (convergence
//! runs), [`scaling`] (time per Newton iteration vs size), [`report`]
//! (machine info, Markdown, PNG figures drawn with `ecc_scene::pictures::Chart`).

// Index loops mirror the maths.
#![allow(clippy::needless_range_loop)]

pub mod autodiff;
pub mod cases;
/// Double-double and the real-number trait, shared with the tests' references.
pub use ecc_tests::{dd, real};
pub mod element;
pub mod energies;
pub mod generic_kernel;
pub mod graph_eval;
pub mod linalg;
pub mod mtx;
pub mod reference;
pub mod report;
pub mod scaling;
pub mod solve;
