//! Mass matrices of linear simplices, and the quadratic mass term
//! E = ½ w Σ_s (x_s − y_s)ᵀ M_s (x_s − y_s) used by inertia and mass damping.
//!
//! With density ρ and rest measure |q| (area or volume), element mass
//! m_q = ρ|q|:
//!
//! * **lumped**: vertex v gets m_v = Σ_{q ∋ v} m_q/(d+1); stencils are single
//!   vertices with block m_v I_d;
//! * **consistent**: for linear shape functions ∫ N_a N_b = |q|(1 + δ_ab)/((d+1)(d+2)),
//!   so M_q\[a\]\[b\] = m_q (1 + δ_ab)/((d+1)(d+2)) ⊗ I_d; stencils are elements.
//!   Both have the same total mass Σ_q m_q.
//!
//! A mass matrix is only ever built through [`MassMatrix::build`], which
//! bumps [`Counter::MassMatrixBuild`]: runs without inertia never call it.

use std::sync::Arc;

use ecc_fem::{Filter, Term};

use crate::body::Body;
use crate::counters::{Counter, Counters};
use crate::spec::MassKind;

/// Per-vertex weights m_v = Σ_{q ∋ v} ρ|q|/(d+1) (a vector, not a matrix:
/// gravity uses these without building a mass matrix).
pub fn vertex_masses<const D: usize>(body: &Body<D>, density: f64) -> Vec<f64> {
    let mut m = vec![0.0; body.n_vertices()];
    for (q, mq) in body.measures(&body.rest).iter().enumerate() {
        let share = density * mq.abs() / (D + 1) as f64;
        for &v in body.element(q) {
            m[v] += share;
        }
    }
    m
}

/// A lumped or consistent mass matrix.
#[derive(Clone, Debug)]
pub struct MassMatrix<const D: usize> {
    kind: MassKind,
    /// Stencils (vertices for lumped, elements for consistent), flat.
    stencils: Vec<usize>,
    /// m_v (lumped) or m_q (consistent), one per stencil.
    masses: Vec<f64>,
}

impl<const D: usize> MassMatrix<D> {
    /// Assemble the mass matrix of `body` with density ρ (counted).
    pub fn build(body: &Body<D>, density: f64, kind: MassKind, counters: &Counters) -> Self {
        counters.bump(Counter::MassMatrixBuild);
        match kind {
            MassKind::Lumped => MassMatrix {
                kind,
                stencils: (0..body.n_vertices()).collect(),
                masses: vertex_masses(body, density),
            },
            MassKind::Consistent => MassMatrix {
                kind,
                stencils: body.elements.clone(),
                masses: body
                    .measures(&body.rest)
                    .iter()
                    .map(|m| density * m.abs())
                    .collect(),
            },
        }
    }

    /// Lumped or consistent.
    pub fn kind(&self) -> MassKind {
        self.kind
    }

    /// Vertices per stencil.
    pub fn arity(&self) -> usize {
        match self.kind {
            MassKind::Lumped => 1,
            MassKind::Consistent => D + 1,
        }
    }

    /// Flat stencils.
    pub fn stencils(&self) -> &[usize] {
        &self.stencils
    }

    /// Total mass Σ m.
    pub fn total(&self) -> f64 {
        self.masses.iter().sum()
    }

    /// Scalar coupling M_s\[a\]\[b\] of stencil `s` (times I_d).
    #[inline]
    pub fn coupling(&self, s: usize, a: usize, b: usize) -> f64 {
        match self.kind {
            MassKind::Lumped => self.masses[s],
            MassKind::Consistent => {
                let k = (D + 1) as f64;
                self.masses[s] * if a == b { 2.0 } else { 1.0 } / (k * (k + 1.0))
            }
        }
    }

    /// ½ vᵀ M v (kinetic energy for velocities `v`).
    pub fn kinetic(&self, v: &[[f64; D]]) -> f64 {
        let n = self.arity();
        let mut e = 0.0;
        for s in 0..self.masses.len() {
            let st = &self.stencils[s * n..(s + 1) * n];
            for a in 0..n {
                for b in 0..n {
                    let dot: f64 = (0..D).map(|c| v[st[a]][c] * v[st[b]][c]).sum();
                    e += 0.5 * self.coupling(s, a, b) * dot;
                }
            }
        }
        e
    }
}

/// E = ½ w Σ_s (x_s − y_s)ᵀ M_s (x_s − y_s): inertia (w = 1/(c h)², y = x̃)
/// or mass-proportional damping (w = α·a, y = the velocity anchor).
pub struct MassQuadratic<const D: usize> {
    name: String,
    counter: Counter,
    counters: Arc<Counters>,
    mass: Arc<MassMatrix<D>>,
    /// Per-vertex target y.
    pub target: Vec<[f64; D]>,
    /// Weight w ≥ 0.
    pub weight: f64,
    /// A coefficient the caller scales `weight` from (α for mass damping).
    pub coefficient: f64,
}

impl<const D: usize> MassQuadratic<D> {
    /// A term over `mass` with target `y` and weight 0 (set both before solving).
    pub fn new(
        name: &str,
        counter: Counter,
        mass: Arc<MassMatrix<D>>,
        n_vertices: usize,
        counters: Arc<Counters>,
    ) -> Self {
        MassQuadratic {
            name: name.to_string(),
            counter,
            counters,
            mass,
            target: vec![[0.0; D]; n_vertices],
            weight: 0.0,
            coefficient: 1.0,
        }
    }

    #[inline]
    fn diff(&self, s: usize, x: &[[f64; D]], a: usize) -> [f64; D] {
        let v = self.mass.stencils[s * self.mass.arity() + a];
        std::array::from_fn(|c| x[v][c] - self.target[v][c])
    }
}

impl<const D: usize> Term<D> for MassQuadratic<D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        self.mass.arity()
    }

    fn stencils(&self) -> &[usize] {
        self.mass.stencils()
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.counters.pass(self.counter, s);
        let n = self.arity();
        let mut e = 0.0;
        for a in 0..n {
            let da = self.diff(s, x, a);
            for b in 0..n {
                let db = self.diff(s, x, b);
                let dot: f64 = (0..D).map(|c| da[c] * db[c]).sum();
                e += self.mass.coupling(s, a, b) * dot;
            }
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
        let n = self.arity();
        let k = n * D;
        grad[..k].fill(0.0);
        for a in 0..n {
            for b in 0..n {
                let db = self.diff(s, x, b);
                let m = self.weight * self.mass.coupling(s, a, b);
                for c in 0..D {
                    grad[a * D + c] += m * db[c];
                }
            }
        }
        if let Some(h) = hess {
            h[..k * k].fill(0.0);
            for a in 0..n {
                for b in 0..n {
                    let m = self.weight * self.mass.coupling(s, a, b);
                    for c in 0..D {
                        h[(a * D + c) * k + b * D + c] = m;
                    }
                }
            }
        }
        self.value(s, x)
    }
}
