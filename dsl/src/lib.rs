//! ecc-dsl: the energy language front end and the hand-rolled CAS.

pub mod cas;
pub mod diag;
pub mod ir;
pub mod span;

pub use cas::{Graph, Id, Node, Sym};
pub use diag::{Diagnostics, Error};
pub use ir::{DimIr, InvariantDerivs, Module, PairIr, ParamDecl, Path, ScaleIr, SpectralIr};
pub use span::Span;
