//! The ground: the half-space {x : n·x ≥ h}, per vertex with distance
//! d_v = n·x_v − h (n of unit length).
//!
//! * **Barrier** (IPC, Li et al. 2020): b(d) = −κ (d − d̂)² ln(d/d̂) for
//!   0 < d < d̂, 0 for d ≥ d̂, +∞ for d ≤ 0. It is C² at d̂ and convex:
//!   b′(d) = κ[−2(d − d̂) ln(d/d̂) − (d − d̂)²/d],
//!   b″(d) = κ[−2 ln(d/d̂) − 4(d − d̂)/d + (d − d̂)²/d²] > 0.
//!   [`Term::max_step`] returns the step at which a vertex would reach the
//!   plane, so the solver's line search never lets anything through.
//! * **Penalty**: p(d) = ½ κ min(d, 0)²: free above the plane, quadratic
//!   below; penetration is of order (load per vertex)/κ.
//!
//! Gradient and Hessian per vertex: ∂e/∂x = e′(d) n, ∂²e/∂x² = e″(d) n nᵀ (PSD).

use std::sync::Arc;

use ecc_fem::{Filter, Term};

use crate::counters::{Counter, Counters};
use crate::spec::GroundKind;

/// Ground contact for a set of vertices.
pub struct Ground<const D: usize> {
    vertices: Vec<usize>,
    normal: [f64; D],
    height: f64,
    kind: GroundKind,
    dhat: f64,
    kappa: f64,
    counters: Arc<Counters>,
}

impl<const D: usize> Ground<D> {
    /// Contact of `vertices` with {n·x ≥ height}; `normal` is normalised here.
    pub fn new(
        vertices: Vec<usize>,
        normal: [f64; D],
        height: f64,
        kind: GroundKind,
        dhat: f64,
        kappa: f64,
        counters: Arc<Counters>,
    ) -> Self {
        let len = normal.iter().map(|c| c * c).sum::<f64>().sqrt();
        Ground {
            vertices,
            normal: normal.map(|c| c / len),
            height,
            kind,
            dhat,
            kappa,
            counters,
        }
    }

    /// Signed distance of a point to the plane.
    #[inline]
    pub fn distance(&self, p: &[f64; D]) -> f64 {
        (0..D).map(|c| self.normal[c] * p[c]).sum::<f64>() - self.height
    }

    /// Smallest signed distance over the term's vertices.
    pub fn min_distance(&self, x: &[[f64; D]]) -> f64 {
        self.vertices
            .iter()
            .map(|&v| self.distance(&x[v]))
            .fold(f64::INFINITY, f64::min)
    }

    /// The contact energy at `x` (without counting a pass).
    pub fn energy(&self, x: &[[f64; D]]) -> f64 {
        self.vertices
            .iter()
            .map(|&v| self.scalar(self.distance(&x[v])).0)
            .sum()
    }

    /// (e, e′, e″) at distance d.
    fn scalar(&self, d: f64) -> (f64, f64, f64) {
        let k = self.kappa;
        match self.kind {
            GroundKind::Barrier => {
                if d <= 0.0 || d.is_nan() {
                    (f64::INFINITY, 0.0, 0.0)
                } else if d >= self.dhat {
                    (0.0, 0.0, 0.0)
                } else {
                    let r = d - self.dhat;
                    let l = (d / self.dhat).ln();
                    (
                        -k * r * r * l,
                        k * (-2.0 * r * l - r * r / d),
                        k * (-2.0 * l - 4.0 * r / d + r * r / (d * d)),
                    )
                }
            }
            GroundKind::Penalty => {
                if d >= 0.0 {
                    (0.0, 0.0, 0.0)
                } else {
                    (0.5 * k * d * d, k * d, k)
                }
            }
        }
    }
}

impl<const D: usize> Term<D> for Ground<D> {
    fn name(&self) -> &str {
        "ground"
    }

    fn arity(&self) -> usize {
        1
    }

    fn stencils(&self) -> &[usize] {
        &self.vertices
    }

    fn is_barrier(&self) -> bool {
        self.kind == GroundKind::Barrier
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.counters.pass(Counter::ContactPass, s);
        self.scalar(self.distance(&x[self.vertices[s]])).0
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        _filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        self.counters.pass(Counter::ContactPass, s);
        let (e, de, d2e) = self.scalar(self.distance(&x[self.vertices[s]]));
        for c in 0..D {
            grad[c] = de * self.normal[c];
        }
        if let Some(h) = hess {
            for a in 0..D {
                for b in 0..D {
                    h[a * D + b] = d2e * self.normal[a] * self.normal[b];
                }
            }
        }
        e
    }

    fn max_step(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        if self.kind != GroundKind::Barrier {
            return f64::INFINITY;
        }
        let v = self.vertices[s];
        let approach: f64 = (0..D).map(|c| self.normal[c] * dx[v][c]).sum();
        if approach < 0.0 {
            (self.distance(&x[v]) / -approach).max(0.0)
        } else {
            f64::INFINITY
        }
    }
}
