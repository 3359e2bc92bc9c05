//! The hand-rolled computer algebra system: a hash-consed expression DAG over
//! exact rationals with canonicalising constructors, a canonical printer,
//! differentiation, substitution and f64 evaluation.

mod build;
mod diff;
mod eval;
mod graph;
mod node;
mod print;
pub mod rat;

pub use build::MAX_CONTENT_BITS;
pub use eval::{Env, Tape, eval, eval_many, sign_i4};
pub(crate) use graph::count_work;
pub use graph::{Graph, largest_number_bits, reset_largest_number_bits, work_count};
pub use node::{Id, Node, Sym};
