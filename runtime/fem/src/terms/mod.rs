//! Ready-made terms besides the elastic one.

pub mod anchor;

pub use anchor::SoftAnchors;
