//! Soft positional anchors: E = Σ_v ½ w_v ‖x_v − p_v‖².
//!
//! One stencil per anchored vertex; gradient w_v (x_v − p_v), Hessian w_v I
//! (already PSD, the filter is irrelevant). Useful as soft handles and as
//! the simplest quadratic term for testing; targets and weights can be
//! changed between solves through [`crate::NewtonSolver::term_mut`].

use ecc_runtime::filter::Filter;

use crate::error::FemError;
use crate::term::Term;

/// Soft anchors pulling vertices towards targets.
#[derive(Clone, Debug)]
pub struct SoftAnchors<const D: usize> {
    name: String,
    vertices: Vec<usize>,
    /// Target position per anchored vertex.
    pub targets: Vec<[f64; D]>,
    /// Stiffness per anchored vertex.
    pub weights: Vec<f64>,
}

impl<const D: usize> SoftAnchors<D> {
    /// Anchors `vertices[i]` to `targets[i]` with stiffness `weights[i]`.
    pub fn new(
        vertices: Vec<usize>,
        targets: Vec<[f64; D]>,
        weights: Vec<f64>,
    ) -> Result<Self, FemError> {
        FemError::check_len("anchor targets", vertices.len(), targets.len())?;
        FemError::check_len("anchor weights", vertices.len(), weights.len())?;
        if let Some(i) = targets
            .iter()
            .position(|t| t.iter().any(|c| !c.is_finite()))
        {
            return Err(FemError::NonFinitePosition {
                what: "anchor targets",
                vertex: vertices[i],
            });
        }
        Ok(SoftAnchors {
            name: "anchors".into(),
            vertices,
            targets,
            weights,
        })
    }

    /// Rename (shown in reports).
    pub fn named(mut self, name: &str) -> Self {
        self.name = name.to_string();
        self
    }
}

impl<const D: usize> Term<D> for SoftAnchors<D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        1
    }

    fn stencils(&self) -> &[usize] {
        &self.vertices
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        let (p, t) = (x[self.vertices[s]], self.targets[s]);
        0.5 * self.weights[s] * (0..D).map(|c| (p[c] - t[c]) * (p[c] - t[c])).sum::<f64>()
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        _filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let (p, t, w) = (x[self.vertices[s]], self.targets[s], self.weights[s]);
        for c in 0..D {
            grad[c] = w * (p[c] - t[c]);
        }
        if let Some(h) = hess {
            h.fill(0.0);
            for c in 0..D {
                h[c * D + c] = w;
            }
        }
        self.value(s, x)
    }
}
