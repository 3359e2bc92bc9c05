//! ecc-dsl: the energy language front end and the hand-rolled CAS.

pub mod cas;
pub mod compile;
pub mod diag;
pub mod front;
pub mod ir;
pub mod poly;
pub mod span;
pub mod testing;

pub use cas::{Env, Graph, Id, Node, Sym, Tape, eval, eval_many};
pub use compile::{compile, compile_dim, slot_pairs};
pub use diag::{Diagnostics, Error};
pub use ir::{DimIr, InvariantDerivs, Module, PairIr, ParamDecl, Path, ScaleIr, SpectralIr};
pub use poly::Proof;
pub use span::Span;
