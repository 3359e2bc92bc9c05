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

pub use eval::{Env, Tape, eval, eval_many};
pub use graph::Graph;
pub use node::{Id, Node, Sym};
