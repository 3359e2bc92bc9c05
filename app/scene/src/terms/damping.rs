//! Stiffness-proportional Rayleigh damping as an incremental potential.
//!
//! The damping force is −C v_{n+1} with C = α M + β K, K the projected
//! elastic Hessian Σ_q PSD(∇²ψ_q) taken **at the start of the step** (a
//! snapshot, so C is constant during the step's Newton solve). The
//! integrators write the new velocity as v_{n+1} = a (x − y) (implicit
//! Euler: a = 1/h, y = x_n; BDF2: a = 3/(2h), y = (4x_n − x_{n−1})/3), so the
//! force is the negative gradient of the quadratic
//!
//!   D(x) = ½ a (x − y)ᵀ C (x − y).
//!
//! The α M part is a [`super::mass::MassQuadratic`] with weight α·a; this
//! term is the β K part: E = ½ w Σ_q (x_q − y_q)ᵀ K_q (x_q − y_q), w = β·a,
//! with the per-element 12×12 (6×6 in 2D) PSD blocks K_q stored.

use std::sync::Arc;

use ecc_fem::{Filter, MAX_STENCIL_DOFS, Term};
use rayon::prelude::*;

use crate::counters::{Counter, Counters};

/// β K damping with element stiffness snapshots.
pub struct StiffnessDamping<const D: usize> {
    /// The elastic term whose projected Hessian is captured.
    elastic: Box<dyn Term<D>>,
    /// Row-major local blocks, `k²` per element, k = arity·D.
    blocks: Vec<f64>,
    /// Per-vertex anchor y.
    pub target: Vec<[f64; D]>,
    /// Weight w = β·a.
    pub weight: f64,
    /// β.
    pub coefficient: f64,
    counters: Arc<Counters>,
}

impl<const D: usize> StiffnessDamping<D> {
    /// Damping over the elements of `elastic` (snapshot K = 0 until
    /// [`StiffnessDamping::snapshot`]).
    pub fn new(elastic: Box<dyn Term<D>>, n_vertices: usize, counters: Arc<Counters>) -> Self {
        let k = elastic.arity() * D;
        let blocks = vec![0.0; elastic.n_stencils() * k * k];
        StiffnessDamping {
            elastic,
            blocks,
            target: vec![[0.0; D]; n_vertices],
            weight: 0.0,
            coefficient: 0.0,
            counters,
        }
    }

    /// Capture K_q = PSD(∇²ψ_q(x)) for every element (counted).
    pub fn snapshot(&mut self, x: &[[f64; D]], filter: Filter) {
        self.counters.bump(Counter::StiffnessSnapshot);
        let k = self.elastic.arity() * D;
        let elastic = &self.elastic;
        self.blocks
            .par_chunks_mut(k * k)
            .enumerate()
            .for_each(|(s, block)| {
                let mut g = [0.0; MAX_STENCIL_DOFS];
                elastic.evaluate(s, x, filter, &mut g[..k], Some(block));
                if block.iter().any(|v| !v.is_finite()) {
                    block.fill(0.0);
                }
            });
    }

    /// d = x_s − y_s, node-major.
    #[inline]
    fn diff(&self, s: usize, x: &[[f64; D]]) -> [f64; MAX_STENCIL_DOFS] {
        let n = self.elastic.arity();
        let st = &self.elastic.stencils()[s * n..(s + 1) * n];
        let mut d = [0.0; MAX_STENCIL_DOFS];
        for (a, &v) in st.iter().enumerate() {
            for c in 0..D {
                d[a * D + c] = x[v][c] - self.target[v][c];
            }
        }
        d
    }
}

impl<const D: usize> Term<D> for StiffnessDamping<D> {
    fn name(&self) -> &str {
        "damping_stiffness"
    }

    fn arity(&self) -> usize {
        self.elastic.arity()
    }

    fn stencils(&self) -> &[usize] {
        self.elastic.stencils()
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.counters.pass(Counter::DampingPass, s);
        let k = self.arity() * D;
        let d = self.diff(s, x);
        let kb = &self.blocks[s * k * k..(s + 1) * k * k];
        let mut e = 0.0;
        for i in 0..k {
            let row: f64 = (0..k).map(|j| kb[i * k + j] * d[j]).sum();
            e += d[i] * row;
        }
        0.5 * self.weight * e
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        _filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let k = self.arity() * D;
        let d = self.diff(s, x);
        let kb = &self.blocks[s * k * k..(s + 1) * k * k];
        for i in 0..k {
            grad[i] = self.weight * (0..k).map(|j| kb[i * k + j] * d[j]).sum::<f64>();
        }
        if let Some(h) = hess {
            for (h, v) in h[..k * k].iter_mut().zip(kb) {
                *h = self.weight * v;
            }
        }
        self.value(s, x)
    }
}
