//! Term wrappers for the solve comparison.
//!
//! * [`NumericProjection`]: the same element term, but its Hessian is the
//!   *raw* element Hessian (`Filter::None`) projected numerically with
//!   nalgebra's `SymmetricEigen` of the 6×6 / 12×12 (eigenvalues mapped by the
//!   requested filter, Q Λ⁺ Qᵀ) — projected Newton as it is usually written
//!   without an analytic eigensystem. With `Filter::None` it passes the raw
//!   Hessian through.
//! * [`LaplacianProxy`]: a first-order baseline. Energy and gradient are the
//!   real ones; the Hessian is the constant H_e = 2|q| BᵀB, i.e. the
//!   F-space Hessian replaced by 2I (the Hessian of ‖F‖², so Σ_e H_e is the
//!   cotangent-like Laplacian of the rest mesh, one copy per coordinate) —
//!   the quadratic proxy of AQP (Kovalsky et al. 2016) and of the ARAP
//!   local-global global step (Liu et al. 2008), with the same line search
//!   as Newton. With `B = ∂vec(F)/∂x`, (BᵀB)_{(n,r),(m,s)} = δ_rs Σ_c w_n\[c\] w_m\[c\]
//!   where w_n is row n−1 of Dm⁻¹ (w_0 = −Σ w_n).

use ecc_fem::{Filter, Term};
use ecc_runtime::Rest;
use ecc_runtime::reference::project_psd_numeric;
use nalgebra::SMatrix;

/// Numeric per-element projection around an element term.
pub struct NumericProjection<const D: usize> {
    inner: Box<dyn Term<D>>,
    name: String,
}

impl<const D: usize> NumericProjection<D> {
    /// Wrap `inner` (an element term of arity 3 in 2D or 4 in 3D).
    pub fn new(inner: Box<dyn Term<D>>) -> Self {
        let name = format!("{}+numeric-projection", inner.name());
        NumericProjection { inner, name }
    }
}

fn project_in_place<const N: usize>(h: &mut [f64], filter: Filter)
where
    nalgebra::Const<N>: nalgebra::DimSub<nalgebra::U1>,
    nalgebra::DefaultAllocator:
        nalgebra::allocator::Allocator<nalgebra::DimDiff<nalgebra::Const<N>, nalgebra::U1>>,
{
    let cols: [[f64; N]; N] = std::array::from_fn(|j| std::array::from_fn(|i| h[j * N + i]));
    let m = SMatrix::<f64, N, N>::from_array_storage(nalgebra::ArrayStorage(cols));
    let p = project_psd_numeric(&m, filter);
    h.copy_from_slice(p.as_slice());
}

impl<const D: usize> Term<D> for NumericProjection<D> {
    fn name(&self) -> &str {
        &self.name
    }
    fn arity(&self) -> usize {
        self.inner.arity()
    }
    fn stencils(&self) -> &[usize] {
        self.inner.stencils()
    }
    fn is_barrier(&self) -> bool {
        self.inner.is_barrier()
    }
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.inner.value(s, x)
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
        let Some(h) = hess else {
            return self.inner.evaluate(s, x, filter, grad, None);
        };
        let psi = self.inner.evaluate(s, x, Filter::None, grad, Some(&mut *h));
        if filter != Filter::None {
            match h.len() {
                36 => project_in_place::<6>(h, filter),
                144 => project_in_place::<12>(h, filter),
                // other arities: leave raw (not used by the report)
                _ => {}
            }
        }
        psi
    }
}

/// The constant Laplacian-like proxy Hessian around an element term.
pub struct LaplacianProxy<const D: usize> {
    inner: Box<dyn Term<D>>,
    /// Per stencil, row-major k×k.
    hess: Vec<f64>,
    k: usize,
    name: String,
}

/// 2|q| BᵀB for chain weights `w` ((d+1) rows of d), row-major (d+1)d square.
fn proxy_block(w: &[Vec<f64>], d: usize, measure: f64) -> Vec<f64> {
    let k = w.len() * d;
    let mut h = vec![0.0; k * k];
    for n in 0..w.len() {
        for m in 0..w.len() {
            let dot: f64 = (0..d).map(|c| w[n][c] * w[m][c]).sum();
            for r in 0..d {
                h[(n * d + r) * k + m * d + r] = 2.0 * measure * dot;
            }
        }
    }
    h
}

fn weights(dm_inv: &[f64], d: usize) -> Vec<Vec<f64>> {
    crate::generic_kernel::chain_weights::<f64>(dm_inv, d)
}

impl<const D: usize> LaplacianProxy<D> {
    /// Proxy for a triangle (D = 2) or tet (D = 3) term with rest data
    /// `rest` (one per stencil).
    pub fn new(inner: Box<dyn Term<D>>, rest: &[Rest<D>]) -> Self {
        let hess = rest
            .iter()
            .flat_map(|r| {
                let dm: Vec<f64> = (0..D * D).map(|i| r.dm_inv[(i / D, i % D)]).collect();
                proxy_block(&weights(&dm, D), D, r.measure)
            })
            .collect();
        let name = format!("{}+laplacian-proxy", inner.name());
        LaplacianProxy {
            inner,
            hess,
            k: D * (D + 1),
            name,
        }
    }
}

impl<const D: usize> Term<D> for LaplacianProxy<D> {
    fn name(&self) -> &str {
        &self.name
    }
    fn arity(&self) -> usize {
        self.inner.arity()
    }
    fn stencils(&self) -> &[usize] {
        self.inner.stencils()
    }
    fn is_barrier(&self) -> bool {
        self.inner.is_barrier()
    }
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.inner.value(s, x)
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
        let psi = self.inner.evaluate(s, x, filter, grad, None);
        if let Some(h) = hess {
            let kk = self.k * self.k;
            h.copy_from_slice(&self.hess[s * kk..(s + 1) * kk]);
        }
        psi
    }
}
