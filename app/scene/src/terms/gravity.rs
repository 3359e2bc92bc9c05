//! Gravity: E = −Σ_v m_v g·x_v, a linear term (zero Hessian).
//!
//! m_v = Σ_{q ∋ v} ρ|q|/(d+1) are per-vertex weights (see
//! [`super::mass::vertex_masses`]): no mass matrix is built for gravity.

use std::sync::Arc;

use ecc_fem::{Filter, Term};

use crate::counters::{Counter, Counters};

/// Constant body force per vertex.
pub struct Gravity<const D: usize> {
    vertices: Vec<usize>,
    /// f_v = m_v g.
    force: Vec<[f64; D]>,
    counters: Arc<Counters>,
}

impl<const D: usize> Gravity<D> {
    /// Weights `masses[v]` under acceleration `g` (vertices with zero weight are skipped).
    pub fn new(masses: &[f64], g: [f64; D], counters: Arc<Counters>) -> Self {
        let vertices: Vec<usize> = (0..masses.len()).filter(|&v| masses[v] > 0.0).collect();
        let force = vertices
            .iter()
            .map(|&v| std::array::from_fn(|c| masses[v] * g[c]))
            .collect();
        Gravity {
            vertices,
            force,
            counters,
        }
    }

    /// Gravitational potential −Σ f_v·x_v at `x`.
    pub fn potential(&self, x: &[[f64; D]]) -> f64 {
        (0..self.vertices.len()).map(|s| self.energy(s, x)).sum()
    }

    #[inline]
    fn energy(&self, s: usize, x: &[[f64; D]]) -> f64 {
        let p = x[self.vertices[s]];
        -(0..D).map(|c| self.force[s][c] * p[c]).sum::<f64>()
    }
}

impl<const D: usize> Term<D> for Gravity<D> {
    fn name(&self) -> &str {
        "gravity"
    }

    fn arity(&self) -> usize {
        1
    }

    fn stencils(&self) -> &[usize] {
        &self.vertices
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.counters.pass(Counter::GravityPass, s);
        self.energy(s, x)
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        _filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        self.counters.pass(Counter::GravityPass, s);
        for c in 0..D {
            grad[c] = -self.force[s][c];
        }
        if let Some(h) = hess {
            h[..D * D].fill(0.0);
        }
        self.energy(s, x)
    }
}
