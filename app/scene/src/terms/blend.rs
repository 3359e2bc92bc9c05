//! Shape interpolation (Smith et al. 2019 §6.3, after Chao et al. 2010):
//! E_t(x) = (1 − t) E_1(x) + t E_2(x), where E_i = Σ_q |q_i| Ψ(F_q^i(x)) is
//! the same energy measured against rest shape i (same connectivity).
//!
//! Gradients and Hessians are the same convex combination; each element
//! Hessian is PSD-projected *before* blending, and a non-negative
//! combination of PSD matrices is PSD, so the blend needs no extra
//! projection. For barrier energies both rest shapes are positively
//! oriented, so E_1 and E_2 are finite on the same set (det Ds > 0) and the
//! inversion-free step bound is the smaller of the two (they coincide).
//! Terms with zero weight are not evaluated (t = 0 costs one energy).

use std::sync::Arc;

use ecc_fem::{Filter, MAX_STENCIL_DOFS, Term};

use crate::counters::{Counter, Counters};

/// (1 − t)·a + t·b over the same stencils.
pub struct Blend<const D: usize> {
    a: Box<dyn Term<D>>,
    b: Box<dyn Term<D>>,
    /// Interpolation parameter t ∈ [0, 1].
    pub t: f64,
    counters: Arc<Counters>,
}

impl<const D: usize> Blend<D> {
    /// Blend of two elastic terms over the same elements (checked: same
    /// arity and stencils).
    pub fn new(
        a: Box<dyn Term<D>>,
        b: Box<dyn Term<D>>,
        counters: Arc<Counters>,
    ) -> Result<Self, String> {
        if a.arity() != b.arity() || a.stencils() != b.stencils() {
            return Err("the two rest shapes must have the same elements".into());
        }
        Ok(Blend {
            a,
            b,
            t: 0.0,
            counters,
        })
    }

    fn weights(&self) -> (f64, f64) {
        (1.0 - self.t, self.t)
    }
}

impl<const D: usize> Term<D> for Blend<D> {
    fn name(&self) -> &str {
        "interpolation"
    }

    fn arity(&self) -> usize {
        self.a.arity()
    }

    fn stencils(&self) -> &[usize] {
        self.a.stencils()
    }

    fn is_barrier(&self) -> bool {
        self.a.is_barrier() || self.b.is_barrier()
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.counters.pass(Counter::BlendPass, s);
        let (wa, wb) = self.weights();
        let mut e = 0.0;
        if wa != 0.0 {
            e += wa * self.a.value(s, x);
        }
        if wb != 0.0 {
            e += wb * self.b.value(s, x);
        }
        e
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        filter: Filter,
        grad: &mut [f64],
        mut hess: Option<&mut [f64]>,
    ) -> f64 {
        self.counters.pass(Counter::BlendPass, s);
        let k = self.arity() * D;
        let (wa, wb) = self.weights();
        grad[..k].fill(0.0);
        if let Some(h) = hess.as_deref_mut() {
            h[..k * k].fill(0.0);
        }
        let mut g = [0.0; MAX_STENCIL_DOFS];
        let mut hl = [0.0; MAX_STENCIL_DOFS * MAX_STENCIL_DOFS];
        let mut e = 0.0;
        for (w, term) in [(wa, &self.a), (wb, &self.b)] {
            if w == 0.0 {
                continue;
            }
            let want = hess.is_some();
            let local_h = want.then_some(&mut hl[..k * k]);
            let ei = term.evaluate(s, x, filter, &mut g[..k], local_h);
            e += w * ei;
            for i in 0..k {
                grad[i] += w * g[i];
            }
            if let Some(h) = hess.as_deref_mut() {
                for i in 0..k * k {
                    h[i] += w * hl[i];
                }
            }
        }
        e
    }

    fn max_step(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        self.a.max_step(s, x, dx).min(self.b.max_step(s, x, dx))
    }
}
