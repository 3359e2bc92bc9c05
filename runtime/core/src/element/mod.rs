//! Linear triangle and tetrahedron elements: rest data, F, and the chain rule
//! from F-space derivatives to node-major x-space derivatives.

mod eval;
mod rest;

pub use eval::{ElementEval, tet_eval, tet_f, tet_psi, tri_eval, tri_f, tri_psi};
pub use rest::{DEGENERATE_REL_TOL, RestError, TetRest, TriRest};
