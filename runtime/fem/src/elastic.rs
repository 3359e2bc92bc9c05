//! The elastic / distortion term: E = Σ_q |q| Ψ(F_q) over triangles or tets.
//!
//! F_q = Ds(x) Dm⁻¹ with the rest data from the runtime ([`TriRest`],
//! [`TetRest`]); the element energy, node-major gradient and PSD-filtered
//! Hessian come from `ecc_runtime::{tri_eval, tet_eval}` (already weighted
//! by |q|), the cheap line-search value from `tri_psi` / `tet_psi` (SVD-free
//! when the energy supports it). For barrier energies (`info().barrier`)
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

use std::marker::PhantomData;
use std::sync::Arc;

use ecc_runtime::{
    Energy, Filter, RestError, TetRest, TriRest, tet_eval, tet_psi, tri_eval, tri_psi,
};

use crate::error::FemError;
use crate::roots::{first_nonpositive, tet_det_poly, tri_det_poly};
use crate::term::Term;

/// Search interval (0, T] for the inversion-free bound: only steps ≤ 1 are
/// ever taken, T > 1/`barrier_safety` keeps the bound exact where it matters.
const STEP_SEARCH_MAX: f64 = 2.0;

/// Linear triangles (2D positions).
#[derive(Clone, Copy, Debug)]
pub struct Tri;
/// Linear tetrahedra (3D positions).
#[derive(Clone, Copy, Debug)]
pub struct Tet;

/// Element kinds: the rest data type per simplex.
pub trait Simplex: Send + Sync + 'static {
    /// Rest data (Dm⁻¹ and measure).
    type Rest: Copy + Send + Sync + std::fmt::Debug;
    /// Vertices per element.
    const NODES: usize;
}

impl Simplex for Tri {
    type Rest = TriRest;
    const NODES: usize = 3;
}

impl Simplex for Tet {
    type Rest = TetRest;
    const NODES: usize = 4;
}

/// Σ_q |q| Ψ(F_q) over the elements of one mesh, for any energy `E`.
pub struct Elastic<E: ?Sized, S: Simplex> {
    name: String,
    energy: Arc<E>,
    elements: Vec<usize>,
    rest: Vec<S::Rest>,
    barrier: bool,
    _kind: PhantomData<S>,
}

/// det Ds of a triangle (same sign as det F: det Dm > 0 for every rest shape).
#[inline]
fn tri_det(p: &[[f64; 2]; 3]) -> f64 {
    (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])
}

/// det Ds of a tet (same sign as det F).
#[inline]
fn tet_det(p: &[[f64; 3]; 4]) -> f64 {
    let e = |k: usize| [p[k][0] - p[0][0], p[k][1] - p[0][1], p[k][2] - p[0][2]];
    let (a, b, c) = (e(1), e(2), e(3));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
        + c[0] * (a[1] * b[2] - a[2] * b[1])
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

impl<E: Energy<2> + ?Sized> Elastic<E, Tri> {
    /// Triangles with planar rest positions (counter-clockwise = positive area).
    pub fn planar(
        energy: Arc<E>,
        rest: &[[f64; 2]],
        tris: &[[usize; 3]],
    ) -> Result<Self, FemError> {
        check_indices(tris, rest.len())?;
        let r = tris
            .iter()
            .enumerate()
            .map(|(q, t)| {
                TriRest::from_2d([rest[t[0]], rest[t[1]], rest[t[2]]]).map_err(|e| rest_error(q, e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_rest(energy, tris, r))
    }

    /// Surface triangles in 3D, each in its own isometric rest frame.
    pub fn surface(
        energy: Arc<E>,
        rest: &[[f64; 3]],
        tris: &[[usize; 3]],
    ) -> Result<Self, FemError> {
        check_indices(tris, rest.len())?;
        let r = tris
            .iter()
            .enumerate()
            .map(|(q, t)| {
                TriRest::from_3d([rest[t[0]], rest[t[1]], rest[t[2]]]).map_err(|e| rest_error(q, e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_rest(energy, tris, r))
    }

    /// From precomputed rest data (one per triangle; indices are checked by the solver).
    pub fn from_rest(energy: Arc<E>, tris: &[[usize; 3]], rest: Vec<TriRest>) -> Self {
        let barrier = energy.info().barrier;
        Elastic {
            name: "elastic".into(),
            energy,
            elements: tris.as_flattened().to_vec(),
            rest,
            barrier,
            _kind: PhantomData,
        }
    }

    /// Σ|q| (total rest area).
    pub fn total_measure(&self) -> f64 {
        self.rest.iter().map(|r| r.area).sum()
    }

    #[inline]
    fn nodes(&self, s: usize, x: &[[f64; 2]]) -> [[f64; 2]; 3] {
        let e = &self.elements[3 * s..3 * s + 3];
        [x[e[0]], x[e[1]], x[e[2]]]
    }
}

impl<E: Energy<3> + ?Sized> Elastic<E, Tet> {
    /// Tets with rest positions (positive volume required).
    pub fn new(energy: Arc<E>, rest: &[[f64; 3]], tets: &[[usize; 4]]) -> Result<Self, FemError> {
        check_indices(tets, rest.len())?;
        let r = tets
            .iter()
            .enumerate()
            .map(|(q, t)| {
                TetRest::new([rest[t[0]], rest[t[1]], rest[t[2]], rest[t[3]]])
                    .map_err(|e| rest_error(q, e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_rest(energy, tets, r))
    }

    /// From precomputed rest data (one per tet).
    pub fn from_rest(energy: Arc<E>, tets: &[[usize; 4]], rest: Vec<TetRest>) -> Self {
        let barrier = energy.info().barrier;
        Elastic {
            name: "elastic".into(),
            energy,
            elements: tets.as_flattened().to_vec(),
            rest,
            barrier,
            _kind: PhantomData,
        }
    }

    /// Σ|q| (total rest volume).
    pub fn total_measure(&self) -> f64 {
        self.rest.iter().map(|r| r.volume).sum()
    }

    #[inline]
    fn nodes(&self, s: usize, x: &[[f64; 3]]) -> [[f64; 3]; 4] {
        let e = &self.elements[4 * s..4 * s + 4];
        [x[e[0]], x[e[1]], x[e[2]], x[e[3]]]
    }
}

impl<E: Energy<2> + ?Sized + 'static> Term<2> for Elastic<E, Tri> {
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        3
    }

    fn stencils(&self) -> &[usize] {
        &self.elements
    }

    fn is_barrier(&self) -> bool {
        self.barrier
    }

    fn value(&self, s: usize, x: &[[f64; 2]]) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !tri_det(&p).gt(&0.0) {
            return f64::INFINITY;
        }
        tri_psi(&*self.energy, &self.rest[s], &p)
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; 2]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !tri_det(&p).gt(&0.0) {
            return outside(grad, hess);
        }
        let ev = tri_eval(&*self.energy, &self.rest[s], &p, filter, hess.is_some());
        grad.copy_from_slice(ev.grad.as_slice());
        if let Some(h) = hess {
            // symmetric: column-major storage equals row-major
            h.copy_from_slice(ev.hess.as_slice());
        }
        ev.psi
    }

    fn max_step(&self, s: usize, x: &[[f64; 2]], dx: &[[f64; 2]]) -> f64 {
        let p = self.nodes(s, x);
        let d = self.nodes(s, dx);
        let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        let c = tri_det_poly(
            sub(p[1], p[0]),
            sub(p[2], p[0]),
            sub(d[1], d[0]),
            sub(d[2], d[0]),
        );
        first_nonpositive(c, STEP_SEARCH_MAX).unwrap_or(f64::INFINITY)
    }
}

impl<E: Energy<3> + ?Sized + 'static> Term<3> for Elastic<E, Tet> {
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        4
    }

    fn stencils(&self) -> &[usize] {
        &self.elements
    }

    fn is_barrier(&self) -> bool {
        self.barrier
    }

    fn value(&self, s: usize, x: &[[f64; 3]]) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !tet_det(&p).gt(&0.0) {
            return f64::INFINITY;
        }
        tet_psi(&*self.energy, &self.rest[s], &p)
    }

    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; 3]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let p = self.nodes(s, x);
        if self.barrier && !tet_det(&p).gt(&0.0) {
            return outside(grad, hess);
        }
        let ev = tet_eval(&*self.energy, &self.rest[s], &p, filter, hess.is_some());
        grad.copy_from_slice(ev.grad.as_slice());
        if let Some(h) = hess {
            h.copy_from_slice(ev.hess.as_slice());
        }
        ev.psi
    }

    fn max_step(&self, s: usize, x: &[[f64; 3]], dx: &[[f64; 3]]) -> f64 {
        let p = self.nodes(s, x);
        let d = self.nodes(s, dx);
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let c = tet_det_poly(
            sub(p[1], p[0]),
            sub(p[2], p[0]),
            sub(p[3], p[0]),
            sub(d[1], d[0]),
            sub(d[2], d[0]),
            sub(d[3], d[0]),
        );
        first_nonpositive(c, STEP_SEARCH_MAX).unwrap_or(f64::INFINITY)
    }
}
