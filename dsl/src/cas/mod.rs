//! The hand-rolled computer algebra system: a hash-consed expression DAG over
//! exact rationals with canonicalising constructors, printing, differentiation,
//! substitution and f64 evaluation.

mod graph;
mod node;

pub use graph::Graph;
pub use node::{Id, Node, Sym};
