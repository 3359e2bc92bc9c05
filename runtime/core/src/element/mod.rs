//! Linear triangle and tetrahedron elements: rest data, F, and the chain rule
//! from F-space derivatives to node-major x-space derivatives.

pub(crate) mod congruence;
mod curvature;
mod eval;
pub(crate) mod jacobi;
pub(crate) mod rest;

pub use congruence::{Congruence, element_eval_projected, metric};
pub use curvature::element_curvature;
pub(crate) use eval::det;
pub use eval::{ElementEval, element_eval, element_f, element_psi};
pub use rest::{DEGENERATE_REL_TOL, Rest, RestError};
