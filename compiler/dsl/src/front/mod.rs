//! The front end: parsing, name resolution and lowering into the CAS.

pub mod ast;
pub mod domain;
pub mod fibre;
pub mod lower;
pub mod parse;
pub mod resolved;
pub mod sema;
pub mod split;
mod suggest;
