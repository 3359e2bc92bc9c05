//! Preconditioners M ≈ H of the PCG path (`LinearSolver::Pcg` and the PCG
//! steps of `Auto`), all built from the upper-CSC values of the shifted
//! Hessian at every Newton step:
//!
//! * [`Preconditioner::Jacobi`]: M = diag(H);
//! * [`Preconditioner::BlockJacobi`]: M = the d×d diagonal blocks of the
//!   vertices ([`block_jacobi`]);
//! * [`Preconditioner::Ic0`]: M = Uᵀ U, the incomplete Cholesky factor on
//!   the pattern of H with a diagonal-shift retry on breakdown ([`ic0`]).
//!
//! Every M is symmetric positive definite whatever H is (breakdowns are
//! repaired, never passed on), so every CG iterate from 0 stays a descent
//! direction for a positive definite H. The default is the one measured
//! fastest in docs/benchmarks/reuse.md ("PCG preconditioners").

pub mod block_jacobi;
pub mod ic0;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::pattern::Pattern;
use block_jacobi::BlockJacobi;
use ic0::Ic0;

/// Which preconditioner PCG uses (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Preconditioner {
    /// M = diag(H).
    Jacobi,
    /// M = blockdiag of the vertices' d×d blocks.
    BlockJacobi,
    /// Incomplete Cholesky IC(0) on the pattern of H (the default: fewest
    /// CG iterations × cost on the measured meshes).
    #[default]
    Ic0,
}

impl Preconditioner {
    /// Stable name (`jacobi`, `block_jacobi`, `ic0`).
    pub fn name(self) -> &'static str {
        match self {
            Preconditioner::Jacobi => "jacobi",
            Preconditioner::BlockJacobi => "block_jacobi",
            Preconditioner::Ic0 => "ic0",
        }
    }

    /// Application work of M⁻¹ in matvec flops (per CG iteration), for
    /// `n` unknowns and `nnz` stored upper entries: n for Jacobi, ≈ 2·d·n
    /// for d×d blocks, two triangular solves 2·(2·nnz − n) for IC(0).
    pub fn apply_work(self, n: usize, nnz: usize, dim: usize) -> f64 {
        let (n, nnz) = (n as f64, nnz as f64);
        match self {
            Preconditioner::Jacobi => n,
            Preconditioner::BlockJacobi => 2.0 * dim as f64 * n,
            Preconditioner::Ic0 => 2.0 * (2.0 * nnz - n),
        }
    }

    /// Work of building M from H in matvec flops (pattern only): n for
    /// Jacobi, d²·n for the blocks, [`Ic0::setup_work`] for IC(0).
    pub fn setup_work(self, pattern: &Pattern) -> f64 {
        let n = pattern.n() as f64;
        match self {
            Preconditioner::Jacobi => n,
            Preconditioner::BlockJacobi => 9.0 * n,
            Preconditioner::Ic0 => Ic0::setup_work(pattern),
        }
    }
}

/// Built preconditioner state for one pattern (vectors allocated once).
pub(crate) enum State {
    Jacobi(Vec<f64>),
    Block(BlockJacobi),
    Ic0(Ic0),
}

impl State {
    pub(crate) fn new(kind: Preconditioner, pattern: &Pattern) -> Self {
        match kind {
            Preconditioner::Jacobi => State::Jacobi(vec![0.0; pattern.n()]),
            Preconditioner::BlockJacobi => State::Block(BlockJacobi::new(pattern)),
            Preconditioner::Ic0 => State::Ic0(Ic0::new(pattern)),
        }
    }

    /// Build M from the (shifted) values of H.
    pub(crate) fn setup(&mut self, pattern: &Pattern, values: &[f64]) {
        match self {
            State::Jacobi(inv) => {
                for (j, v) in inv.iter_mut().enumerate() {
                    *v = positive_inverse(values[pattern.diag_slot(j)]);
                }
            }
            State::Block(b) => b.setup(values),
            State::Ic0(f) => f.factorize(pattern, values),
        }
    }

    /// z = M⁻¹ r.
    pub(crate) fn apply(&self, r: &[f64], z: &mut [f64]) {
        match self {
            State::Jacobi(inv) => z
                .par_iter_mut()
                .zip(r.par_iter().zip(inv))
                .with_min_len(4096)
                .for_each(|(z, (r, d))| *z = r * d),
            State::Block(b) => b.apply(r, z),
            State::Ic0(f) => f.apply(r, z),
        }
    }
}

/// 1/d for a positive finite d, else 1 (a non-positive diagonal entry is
/// preconditioned by the identity).
pub(crate) fn positive_inverse(d: f64) -> f64 {
    if d > 0.0 && d.is_finite() {
        1.0 / d
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests;
