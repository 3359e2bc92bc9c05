//! The elastic / distortion term: E = Σ_q |q| Ψ(F_q) over triangles or tets.
//!
//! F_q = Ds(x) Dm⁻¹ with the rest data from the runtime ([`Rest`]); the
//! element energy, node-major gradient and PSD-filtered Hessian come from
//! `ecc_runtime::element_eval` (already weighted by |q|), the cheap
//! line-search value from `element_psi` (SVD-free when the energy supports
//! it), the trust-region curvature dxᵀ H dx from `element_curvature` (no
//! element Hessian). One [`Term`] impl serves both dimensions; [`Simplex`] holds the only
//! per-simplex piece, the degree of det Ds(x + α dx) in α. For barrier energies (`info().barrier`)
//! [`Term::max_step`] returns the first root of det Ds(x + α dx) = 0 in
//! (0, 2] (quadratic in 2D, cubic in 3D, see [`crate::roots`]); det Dm > 0
//! for every rest element, so det F and det Ds vanish together. For barrier
//! energies the term itself also enforces the domain: an element with
//! det F ≤ 0 is `+∞` (zero derivatives) whatever the energy's formula gives
//! there (the `Energy` contract says so, but e.g. ½(‖F‖² + ‖F⁻¹‖²) is finite
//! for inverted F), so an inverted start is reported, never minimised.
//!
//! Triangles come in two flavours with the same [`Tri`] type: planar rest
//! shapes ([`Elastic::planar`], 2D positions, signed area must be positive)
//! and surface triangles in 3D ([`Elastic::surface`], each expressed in its
//! own isometric 2D frame: the parameterisation setting). Positions x are
//! always 2D for triangles and 3D for tets.
//!
//! **Projection** ([`Projection`], [`Elastic::with_projection`]): the
//! element Hessian |q| Bᵀ H B is made PSD either in F-space (filter H's
//! analytic eigenvalues, |q| Bᵀ f(H) B: `FSpace`) or exactly at element level
//! (the d²×d² congruence of `ecc_runtime::element_eval_projected`: `Element`),
//! or exactly only on elements whose rest metric M = βᵀβ is far from
//! isotropic (`Hybrid`). They coincide wherever H ⪰ 0 or M ∝ I. `Auto`
//! picks `Element` for triangles and `FSpace` for tetrahedra.

use std::marker::PhantomData;
use std::sync::Arc;

use ecc_runtime::{
    Congruence, Dim, Energy, Filter, Nodes, Rest, RestError, Space, element_curvature,
    element_eval, element_eval_projected, element_psi,
};
use nalgebra::SMatrix;
use rayon::prelude::*;

use crate::error::FemError;
use crate::newton::params::FilterPolicy;
use crate::roots::{first_nonpositive, tet_det_poly, tri_det_poly};
use crate::term::Term;

/// Search interval (0, T] for the inversion-free bound: only steps ≤ 1 are
/// ever taken, T > 1/`barrier_safety` keeps the bound exact where it matters.
const STEP_SEARCH_MAX: f64 = 2.0;

/// Default threshold of [`Projection::hybrid`] on cond(M) (M = βᵀβ, 1 for the
/// regular simplex).
pub const HYBRID_MIN_COND: f64 = 2.0;

/// How an element Hessian is made positive semi-definite (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// |q| Bᵀ f(H) B: the analytic eigenvalues of the F-space Hessian H are
    /// filtered (no eigensolve at all). Exact when M ∝ I or H ⪰ 0.
    FSpace,
    /// The exact projection f(|q| Bᵀ H B) of the element Hessian, through the
    /// d²×d² congruence (one 4×4 / 9×9 eigensolve per indefinite element).
    Element,
    /// `Element` on elements with cond(M) > `min_cond`, `FSpace` elsewhere.
    Hybrid {
        /// Smallest condition number of the rest metric M that gets the exact projection.
        min_cond: f64,
    },
    /// By dimension and Newton filter policy, from the measurements in
    /// `docs/benchmarks/projection.md` ([`Projection::resolve_for`]):
    /// `Element` for triangles under a filter that is always applied (fewer
    /// Newton iterations on the SD parameterisations with the fixed clamp
    /// for a 4×4 Jacobi eigensolve per indefinite element), `FSpace` for
    /// triangles under [`FilterPolicy::TrustRegionNewton`] (the raw Hessian
    /// near the minimiser makes the projection's accuracy moot there, and
    /// f-space took fewer iterations and less time on every measured
    /// parameterisation) and for tetrahedra (the 9×9 eigensolve costs more
    /// than the iterations it saves).
    Auto,
}

impl Default for Projection {
    /// [`Projection::Auto`]; see `docs/benchmarks/projection.md` for the
    /// measurements behind it.
    fn default() -> Self {
        Projection::Auto
    }
}

impl Projection {
    /// [`Projection::Hybrid`] with the default threshold [`HYBRID_MIN_COND`].
    pub fn hybrid() -> Self {
        Projection::Hybrid {
            min_cond: HYBRID_MIN_COND,
        }
    }

    /// The scene/CLI name: `f-space`, `element`, `hybrid` or `auto`.
    pub fn name(&self) -> &'static str {
        match self {
            Projection::FSpace => "f-space",
            Projection::Element => "element",
            Projection::Hybrid { .. } => "hybrid",
            Projection::Auto => "auto",
        }
    }

    /// The explicit choice `self` stands for in dimension `d` under the
    /// default, fixed filter policy: [`Projection::resolve_for`] with
    /// [`FilterPolicy::Fixed`] (what an `Elastic` term uses when nothing
    /// resolved `Auto` before it).
    pub fn resolve(self, d: usize) -> Projection {
        self.resolve_for(d, FilterPolicy::Fixed)
    }

    /// The explicit choice `self` stands for in dimension `d` for a Newton
    /// solve with filter policy `policy` (`Auto` resolved; the others
    /// unchanged). Measured (2026-12-02, SD parameterisations to 1e-4,
    /// `benches/examples/iterations`, specs `element+trn` / `fspace+trn`):
    /// under trust-region Newton f-space took 19 / 42 / 76 iterations and
    /// 0.48 / 2.11 / 0.40 s on camelhead / armadillo_cut_low /
    /// hand_1_i_f5000 against the element projection's 23 / 43 / 83 and
    /// 0.72 / 2.75 / 0.54 s.
    pub fn resolve_for(self, d: usize, policy: FilterPolicy) -> Projection {
        match self {
            Projection::Auto if d == 2 && policy != FilterPolicy::TrustRegionNewton => {
                Projection::Element
            }
            Projection::Auto => Projection::FSpace,
            p => p,
        }
    }
}

/// Linear triangles (2D positions).
#[derive(Clone, Copy, Debug)]
pub struct Tri;
/// Linear tetrahedra (3D positions).
#[derive(Clone, Copy, Debug)]
pub struct Tet;

/// Element kinds: the rest data and the inversion-free step bound per simplex.
pub trait Simplex: Send + Sync + 'static {
    /// Rest data (Dm⁻¹ and measure): `Rest<d>`.
    type Rest: Copy + Send + Sync + std::fmt::Debug;
    /// Rest factors of the exact element projection: `Congruence<d>`.
    type Congruence: Copy + Send + Sync + std::fmt::Debug;
    /// Vertices per element (d + 1).
    const NODES: usize;
    /// The first root α ∈ (0, T] of det Ds(x + α dx) (quadratic in 2D, cubic
    /// in 3D, see [`crate::roots`]) for node-major positions `p` and steps
    /// `d`; `None` when there is none.
    fn first_inversion(p: &[f64], d: &[f64]) -> Option<f64>;
}

/// Edge k of a node-major simplex: node k minus node 0.
fn edge<const D: usize>(p: &[f64], k: usize) -> [f64; D] {
    std::array::from_fn(|i| p[k * D + i] - p[i])
}

impl Simplex for Tri {
    type Rest = Rest<2>;
    type Congruence = Congruence<2>;
    const NODES: usize = 3;
    fn first_inversion(p: &[f64], d: &[f64]) -> Option<f64> {
        let c = tri_det_poly(edge(p, 1), edge(p, 2), edge(d, 1), edge(d, 2));
        first_nonpositive(c, STEP_SEARCH_MAX)
    }
}

impl Simplex for Tet {
    type Rest = Rest<3>;
    type Congruence = Congruence<3>;
    const NODES: usize = 4;
    fn first_inversion(p: &[f64], d: &[f64]) -> Option<f64> {
        let (p1, p2, p3) = (edge(p, 1), edge(p, 2), edge(p, 3));
        let c = tet_det_poly(p1, p2, p3, edge(d, 1), edge(d, 2), edge(d, 3));
        first_nonpositive(c, STEP_SEARCH_MAX)
    }
}

/// Σ_q |q| Ψ(F_q) over the elements of one mesh, for any energy `E`.
pub struct Elastic<E: ?Sized, S: Simplex> {
    name: String,
    energy: Arc<E>,
    elements: Vec<usize>,
    rest: Vec<S::Rest>,
    barrier: bool,
    projection: Projection,
    /// Per element when `projection` is not `FSpace` (else empty).
    congruence: Vec<S::Congruence>,
    _kind: PhantomData<S>,
}

/// A barrier element at det F ≤ 0: outside the domain (Ψ = +∞, zero derivatives).
fn outside(grad: &mut [f64], hess: Option<&mut [f64]>) -> f64 {
    grad.fill(0.0);
    if let Some(h) = hess {
        h.fill(0.0);
    }
    f64::INFINITY
}

fn rest_error(element: usize, e: RestError) -> FemError {
    FemError::DegenerateRest {
        element,
        reason: e.to_string(),
    }
}

fn check_indices<const K: usize>(elements: &[[usize; K]], n: usize) -> Result<(), FemError> {
    if elements.is_empty() {
        return Err(FemError::EmptyMesh);
    }
    for (q, el) in elements.iter().enumerate() {
        for &v in el {
            if v >= n {
                return Err(FemError::VertexOutOfRange {
                    term: "elastic".into(),
                    stencil: q,
                    vertex: v,
                    n_vertices: n,
                });
            }
        }
    }
    Ok(())
}

impl<E: ?Sized, S: Simplex> Elastic<E, S> {
    /// The energy density.
    pub fn energy(&self) -> &Arc<E> {
        &self.energy
    }

    /// Mutable access to the energy (to change parameters between solves);
    /// `None` while the `Arc` is shared.
    pub fn energy_mut(&mut self) -> Option<&mut E> {
        Arc::get_mut(&mut self.energy)
    }

    /// Per-element rest data.
    pub fn rest(&self) -> &[S::Rest] {
        &self.rest
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.rest.len()
    }

    /// Whether there are no elements (never true for a constructed term).
    pub fn is_empty(&self) -> bool {
        self.rest.is_empty()
    }

    /// Rename the term (shown in reports; default "elastic").
    pub fn named(mut self, name: &str) -> Self {
        self.name = name.to_string();
        self
    }
}

/// Rest data of every element (vertex ids checked first), from its K rest
/// positions by `make`; the first failure names its element.
///
/// Built on rayon's threads; on a failure the elements are gone through in
/// order again, so the error is the first one whatever the threads did.
fn rest_data<P: Copy + Sync, R: Send, const K: usize>(
    rest: &[P],
    elements: &[[usize; K]],
    make: impl Fn([P; K]) -> Result<R, RestError> + Sync,
) -> Result<Vec<R>, FemError> {
    check_indices(elements, rest.len())?;
    let one = |(q, t): (usize, &[usize; K])| make(t.map(|v| rest[v])).map_err(|e| rest_error(q, e));
    elements
        .par_iter()
        .with_min_len(REST_GRAIN)
        .enumerate()
        .map(one)
        .collect::<Result<Vec<R>, FemError>>()
        .or_else(|_| elements.iter().enumerate().map(one).collect())
}

/// Elements per rayon task of [`rest_data`].
const REST_GRAIN: usize = 1 << 14;

impl<E: Energy<2> + ?Sized> Elastic<E, Tri> {
    /// Triangles with planar rest positions (counter-clockwise = positive area).
    pub fn planar(
        energy: Arc<E>,
        rest: &[[f64; 2]],
        tris: &[[usize; 3]],
    ) -> Result<Self, FemError> {
        let r = rest_data(rest, tris, Rest::<2>::new)?;
        Ok(Self::from_rest(energy, tris, r))
    }

    /// Surface triangles in 3D, each in its own isometric rest frame.
    pub fn surface(
        energy: Arc<E>,
        rest: &[[f64; 3]],
        tris: &[[usize; 3]],
    ) -> Result<Self, FemError> {
        let r = rest_data(rest, tris, Rest::<2>::from_3d)?;
        Ok(Self::from_rest(energy, tris, r))
    }
}

impl<E: Energy<3> + ?Sized> Elastic<E, Tet> {
    /// Tets with rest positions (positive volume required).
    pub fn new(energy: Arc<E>, rest: &[[f64; 3]], tets: &[[usize; 4]]) -> Result<Self, FemError> {
        let r = rest_data(rest, tets, Rest::<3>::new)?;
        Ok(Self::from_rest(energy, tets, r))
    }
}

impl<E, S, const D: usize> Elastic<E, S>
where
    E: Energy<D> + ?Sized,
    S: Simplex<Rest = Rest<D>, Congruence = Congruence<D>>,
    Space<D>: Dim<D>,
{
    /// From precomputed rest data (one per element; indices are checked by the solver).
    pub fn from_rest<const K: usize>(
        energy: Arc<E>,
        elements: &[[usize; K]],
        rest: Vec<Rest<D>>,
    ) -> Self {
        debug_assert_eq!(K, S::NODES);
        let barrier = energy.info().barrier;
        Elastic {
            name: "elastic".into(),
            energy,
            elements: elements.as_flattened().to_vec(),
            rest,
            barrier,
            projection: Projection::FSpace,
            congruence: Vec::new(),
            _kind: PhantomData,
        }
    }

    /// The same term over its rest shape scaled by `s` (finite, > 0): per
    /// element Dm⁻¹/s and |q|·s^d, what the rest positions times `s` give
    /// (to rounding), without building the rest data again (the
    /// parameterisation's unit-area normalisation). The projection's rest
    /// factors are recomputed.
    pub fn scaled(mut self, s: f64) -> Self {
        let m = s.powi(D as i32);
        for r in &mut self.rest {
            *r = Rest {
                dm_inv: r.dm_inv / s,
                measure: r.measure * m,
            };
        }
        let projection = self.projection;
        self.with_projection(projection)
    }

    /// Use `projection` for the element Hessians (a bare `Elastic` uses
    /// [`Projection::FSpace`]; scenes and `param::ParamOptions` use
    /// [`Projection::default()`], i.e. [`Projection::Auto`]);
    /// computes the rest factors M^{±½} of every element when needed.
    pub fn with_projection(mut self, projection: Projection) -> Self {
        self.congruence = match projection.resolve(D) {
            Projection::FSpace => Vec::new(),
            _ => self.rest.iter().map(Rest::congruence).collect(),
        };
        self.projection = projection;
        self
    }

    /// The projection in use.
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// Whether element `s` gets the exact element projection.
    #[inline]
    fn exact(&self, s: usize) -> bool {
        match self.projection.resolve(D) {
            Projection::FSpace | Projection::Auto => false,
            Projection::Element => true,
            Projection::Hybrid { min_cond } => self.congruence[s].cond() > min_cond,
        }
    }

    /// Σ|q| (total rest area or volume).
    pub fn total_measure(&self) -> f64 {
        self.rest.iter().map(|r| r.measure).sum()
    }

    #[inline]
    fn nodes(&self, s: usize, x: &[[f64; D]]) -> Nodes<D> {
        let k = S::NODES;
        <Space<D> as Dim<D>>::gather(x, &self.elements[k * s..k * s + k])
    }

    /// det F > 0, decided by det Ds (det Dm > 0 for every rest element, so
    /// det Ds has the sign of det F).
    #[inline]
    fn inside(p: &Nodes<D>) -> bool {
        let p = p.as_ref();
        let ds = SMatrix::<f64, D, D>::from_fn(|i, j| p[j + 1][i] - p[0][i]);
        <Space<D> as Dim<D>>::det(&ds) > 0.0
    }
}

impl<E, S, const D: usize> Term<D> for Elastic<E, S>
where
    E: Energy<D> + ?Sized + 'static,
    S: Simplex<Rest = Rest<D>, Congruence = Congruence<D>>,
    Space<D>: Dim<D>,
{
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        S::NODES
    }

    fn stencils(&self) -> &[usize] {
        &self.elements
    }

    fn is_barrier(&self) -> bool {
        self.barrier
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !Self::inside(&p) {
            return f64::INFINITY;
        }
        element_psi(&*self.energy, &self.rest[s], &p)
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !Self::inside(&p) {
            return outside(grad, hess);
        }
        let (e, rest, want) = (&*self.energy, &self.rest[s], hess.is_some());
        let ev = if want && self.exact(s) {
            element_eval_projected(e, rest, &self.congruence[s], &p, filter, true)
        } else {
            element_eval(e, rest, &p, filter, want)
        };
        let n = D * S::NODES;
        for (i, g) in grad.iter_mut().enumerate().take(n) {
            *g = ev.grad[i];
        }
        if let Some(h) = hess {
            // symmetric: column-major storage equals row-major
            for (k, v) in h.iter_mut().enumerate().take(n * n) {
                *v = ev.hess[(k % n, k / n)];
            }
        }
        ev.psi
    }

    /// The raw curvature from the element's eigensystem
    /// ([`element_curvature`]: no 6×6 / 12×12 Hessian is formed); `+∞`
    /// outside a barrier's domain, as [`Term::evaluate`] gives there. The
    /// raw Hessian is the same for every [`Projection`], so is this.
    fn curvature(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !Self::inside(&p) {
            return f64::INFINITY;
        }
        element_curvature(&*self.energy, &self.rest[s], &p, &self.nodes(s, dx))
    }

    fn max_step(&self, s: usize, x: &[[f64; D]], dx: &[[f64; D]]) -> f64 {
        let (p, d) = (self.nodes(s, x), self.nodes(s, dx));
        S::first_inversion(p.as_ref().as_flattened(), d.as_ref().as_flattened())
            .unwrap_or(f64::INFINITY)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ecc_runtime::energies::SymmetricDirichlet;

    /// `n` separate triangles, 3 vertices each, in 3D; `flat` ones collinear.
    fn soup(n: usize, flat: &[usize]) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
        let mut p = Vec::with_capacity(3 * n);
        for q in 0..n {
            let (x, z) = (q as f64, 0.1 * (q % 7) as f64);
            let top = if flat.contains(&q) {
                [x + 2.0, 0.0, z]
            } else {
                [x + 0.3, 1.0 + z, z]
            };
            p.extend([[x, 0.0, z], [x + 1.0, 0.0, z], top]);
        }
        let t = (0..n).map(|q| [3 * q, 3 * q + 1, 3 * q + 2]).collect();
        (p, t)
    }

    /// The rest data is built on several threads, and a failure still names
    /// the first bad element.
    #[test]
    fn the_first_degenerate_element_is_reported() {
        let n = 5 * REST_GRAIN;
        let (p, t) = soup(n, &[4 * REST_GRAIN + 3, REST_GRAIN + 5, 3 * REST_GRAIN]);
        let Err(e) = Elastic::<_, Tri>::surface(Arc::new(SymmetricDirichlet), &p, &t) else {
            panic!("degenerate triangles accepted");
        };
        assert!(
            matches!(e, FemError::DegenerateRest { element, .. } if element == REST_GRAIN + 5),
            "{e}"
        );
    }

    /// `scaled(s)` is the term built from the positions times s, to the
    /// rounding of those positions (edges of length 1 at x up to 100).
    #[test]
    fn a_scaled_term_is_the_term_of_scaled_positions() {
        let (p, t) = soup(100, &[]);
        let s = 0.37;
        let sd = Arc::new(SymmetricDirichlet);
        let scaled_p: Vec<[f64; 3]> = p.iter().map(|x| x.map(|c| c * s)).collect();
        let want = Elastic::<_, Tri>::surface(sd.clone(), &scaled_p, &t).unwrap();
        let got = Elastic::<_, Tri>::surface(sd, &p, &t)
            .unwrap()
            .with_projection(Projection::Element)
            .scaled(s);
        for (a, b) in got.rest().iter().zip(want.rest()) {
            assert!((a.measure - b.measure).abs() <= 1e-13 * b.measure);
            assert!((a.dm_inv - b.dm_inv).norm() <= 1e-13 * b.dm_inv.norm());
        }
        let want = want.with_projection(Projection::Element);
        assert_eq!(got.congruence.len(), want.congruence.len());
        assert!((got.total_measure() - want.total_measure()).abs() < 1e-12 * want.total_measure());
    }
}
