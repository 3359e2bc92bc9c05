//! [`AutodiffTerm`]: the autodiff baseline as a Newton term. Energy, gradient
//! and Hessian of every element come from [`super::element_projected`]
//! (forward-mode dual numbers, then the numeric per-element projection); the
//! line search's values from [`super::element_value`] in plain f64. Stencils
//! and the barrier's step bound (det F > 0 along the step) are the wrapped
//! element term's, so the solve differs from the analytic one only in how
//! each element's derivatives are computed.

use ecc_fem::{Filter, Term};
use ecc_runtime::Rest;

use super::{AdEnergy, element_gradient, element_projected, element_value};

/// The autodiff + numeric-projection element term around an `Elastic` term.
pub struct AutodiffTerm<const D: usize> {
    inner: Box<dyn Term<D>>,
    energy: AdEnergy,
    rest: Vec<Rest<D>>,
    name: String,
}

impl<const D: usize> AutodiffTerm<D> {
    /// Wrap `inner` (arity d + 1, one `rest` per stencil) with the baseline
    /// form of its energy.
    pub fn new(inner: Box<dyn Term<D>>, energy: AdEnergy, rest: Vec<Rest<D>>) -> Self {
        let name = format!("{}+autodiff", inner.name());
        AutodiffTerm {
            inner,
            energy,
            rest,
            name,
        }
    }

    /// The stencil's node-major coordinates.
    fn gather(&self, s: usize, x: &[[f64; D]]) -> Vec<f64> {
        let k = D + 1;
        self.inner.stencils()[s * k..s * k + k]
            .iter()
            .flat_map(|&v| x[v])
            .collect()
    }
}

type Second<const N: usize> = (f64, nalgebra::SVector<f64, N>, nalgebra::SMatrix<f64, N, N>);

/// A first-order result with an (unused) zero Hessian.
fn first<const N: usize>(r: Option<(f64, nalgebra::SVector<f64, N>)>) -> Option<Second<N>> {
    r.map(|(v, g)| (v, g, nalgebra::SMatrix::zeros()))
}

/// Copy an autodiff result into the solver's buffers (+∞ and zeros outside).
fn write<const N: usize>(r: Option<Second<N>>, grad: &mut [f64], hess: Option<&mut [f64]>) -> f64 {
    let Some((v, g, h)) = r else {
        grad.fill(0.0);
        if let Some(out) = hess {
            out.fill(0.0);
        }
        return f64::INFINITY;
    };
    grad[..N].copy_from_slice(g.as_slice());
    if let Some(out) = hess {
        // symmetric: column-major storage is the row-major matrix
        out[..N * N].copy_from_slice(h.as_slice());
    }
    v
}

impl<const D: usize> Term<D> for AutodiffTerm<D> {
    fn name(&self) -> &str {
        &self.name
    }
    fn arity(&self) -> usize {
        D + 1
    }
    fn stencils(&self) -> &[usize] {
        self.inner.stencils()
    }
    fn is_barrier(&self) -> bool {
        self.inner.is_barrier()
    }
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        element_value(self.energy, &self.rest[s], &self.gather(s, x))
    }
    fn max_step(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        self.inner.max_step(s, x, dx)
    }
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let p = self.gather(s, x);
        let (e, rest) = (self.energy, &self.rest[s]);
        match (D, hess.is_some()) {
            (2, true) => write::<6>(element_projected::<D, 6>(e, rest, &p, filter), grad, hess),
            (3, true) => write::<12>(element_projected::<D, 12>(e, rest, &p, filter), grad, hess),
            (2, false) => write::<6>(first(element_gradient::<D, 6>(e, rest, &p)), grad, None),
            (3, false) => write::<12>(first(element_gradient::<D, 12>(e, rest, &p)), grad, None),
            _ => unreachable!("elements are triangles or tets"),
        }
    }
}
