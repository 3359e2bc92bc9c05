//! The objective is a sum of terms; a term is a sum over *stencils*.
//!
//! E(x) = Σ_terms Σ_s e_s(x|_s), where a stencil s is a small ordered list of
//! vertices (a triangle, a tet, a single vertex for an anchor or gravity, …)
//! and e_s only reads the positions of those vertices. A term declares its
//! stencils **once**; from them the solver builds the sparsity pattern, the
//! stencil→slot map and a colouring, and it owns all parallelism and
//! scattering. A term only ever computes dense *local* quantities:
//!
//! * [`Term::value`]: e_s (cheap path, used by the line search);
//! * [`Term::evaluate`]: e_s, its local gradient ∂e_s/∂x_s (length k = arity·D,
//!   node-major: `[x0.x, x0.y, (x0.z), x1.x, …]`) and, when asked, the local
//!   Hessian (k×k, row-major, PSD-filtered with the given [`Filter`]);
//! * [`Term::curvature`]: dxᵀ ∇²e_s dx with the raw Hessian (trust-region
//!   ratio; the default goes through [`Term::evaluate`]);
//! * [`Term::max_step`]: the largest α ≤ 1 (or `+∞`) such that the stencil
//!   stays in its domain along x + α·dx (barrier terms).
//!
//! This keeps terms free of threading and of global indices: gravity,
//! inertia, a ground barrier or a shape-interpolation blend are new terms,
//! not solver changes. Terms must be `'static` (`Any` supertrait) so a caller
//! can get a concrete term back from a solver to change its data between solves.

use std::any::Any;

use ecc_runtime::filter::Filter;

/// The largest number of DOFs a stencil may couple (4 vertices in 3D, 6 in 2D).
pub const MAX_STENCIL_DOFS: usize = 12;

/// One additive term of the objective, in dimension `D` (2 or 3).
pub trait Term<const D: usize>: Any + Send + Sync {
    /// Short name, used in reports and per-term timings.
    fn name(&self) -> &str;

    /// Vertices per stencil.
    fn arity(&self) -> usize;

    /// All stencils, flat: stencil `s` is `stencils()[s·arity .. (s+1)·arity]`.
    /// Must not change between solves (the pattern is built from it once).
    fn stencils(&self) -> &[usize];

    /// Number of stencils.
    fn n_stencils(&self) -> usize {
        self.stencils().len() / self.arity().max(1)
    }

    /// Whether the term is `+∞` outside an open domain (e.g. det F > 0) so the
    /// line search must bound the step with [`Term::max_step`].
    fn is_barrier(&self) -> bool {
        false
    }

    /// e_s(x): `+∞` outside the domain, never NaN for finite x.
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64;

    /// e_s, its gradient into `grad` (length arity·D, overwritten) and, if
    /// `hess` is given, its filtered Hessian (row-major (arity·D)², overwritten,
    /// symmetric). Returns e_s.
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64;

    /// dxᵀ ∇²e_s(x) dx with the *raw* (unfiltered) Hessian: the curvature of
    /// e_s along the step for the trust-region ratio. `dx` is the full
    /// per-vertex direction, like `x`. `+∞` where e_s(x) is not finite.
    ///
    /// The default evaluates the local Hessian with [`Filter::None`] and forms
    /// dlᵀ H dl (dl = `dx` on the stencil, node-major); terms that can give
    /// the same number without the k×k Hessian override it.
    fn curvature(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        let arity = self.arity();
        let k = arity * D;
        let mut lg = [0.0f64; MAX_STENCIL_DOFS];
        let mut lh = [0.0f64; MAX_STENCIL_DOFS * MAX_STENCIL_DOFS];
        let psi = self.evaluate(s, x, Filter::None, &mut lg[..k], Some(&mut lh[..k * k]));
        if !psi.is_finite() {
            return f64::INFINITY;
        }
        let st = &self.stencils()[s * arity..(s + 1) * arity];
        let mut dl = [0.0f64; MAX_STENCIL_DOFS];
        for a in 0..k {
            dl[a] = dx[st[a / D]][a % D];
        }
        let mut acc = 0.0;
        for a in 0..k {
            let mut r = 0.0;
            for b in 0..k {
                r += lh[a * k + b] * dl[b];
            }
            acc += dl[a] * r;
        }
        acc
    }

    /// The largest step α ∈ (0, ∞] such that e_s stays finite on [x, x + α·dx)
    /// (only needs to be exact below 1). Non-barrier terms keep the default `+∞`.
    fn max_step(&self, _s: usize, _x: &[[f64; D]], _dx: &[[f64; D]]) -> f64 {
        f64::INFINITY
    }
}
