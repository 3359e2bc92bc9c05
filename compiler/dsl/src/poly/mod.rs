//! Exact polynomial machinery over ℚ: sparse multivariate polynomials,
//! rational functions with factored denominators, conversion from and to
//! expressions, exact identity tests and exact division.

mod convert;
mod mono;
mod polynomial;
mod ratfun;

pub use convert::{Converter, Proof, is_zero};
pub use polynomial::{
    MAX_TERMS, Mono, Poly, TooBig, WORK_BUDGET, budget_left, div_linear, set_budget,
};
pub use ratfun::RatFun;
