//! The fibre term: E = Σ_q |q| ψ(I4(F_q, a_q), I5(F_q, a_q)) over triangles or tets.
//!
//! One unit rest-space direction a_q per element (normalised here; a zero or
//! non-finite direction is a [`FemError::BadFibre`] naming its element).
//! Elements, rest data and errors follow the elastic term ([`crate::elastic`]:
//! the same index checks and degenerate-rest errors); the element energy,
//! gradient and PSD-filtered Hessian come from
//! `ecc_runtime::fibre::fibre_element_eval` (closed form for ψ without I4
//! terms, a d² × d² projection otherwise). The term is added next to an
//! [`Elastic`](crate::Elastic) term (each projected to PSD on its own, as
//! HOBAK does); it is never a barrier (ψ(I4, I5) is finite on inverted elements).

use std::sync::Arc;

use ecc_runtime::fibre::{
    FibreDim, FibreEnergy, fibre_element_eval, fibre_element_psi, unit_fibre,
};
use ecc_runtime::{Dim, Filter, Nodes, Rest, RestError, Space};
use nalgebra::SVector;

use crate::error::FemError;
use crate::term::Term;

/// Σ_q |q| ψ(I4, I5) with one fibre per element, for any fibre energy `E`.
pub struct Fibre<E: ?Sized, const D: usize> {
    name: String,
    energy: Arc<E>,
    elements: Vec<usize>,
    rest: Vec<Rest<D>>,
    dirs: Vec<SVector<f64, D>>,
}

/// Rest data of every element (vertex ids checked first, as the elastic
/// term does); the first failure names its element.
fn rest_data<P: Copy, R, const K: usize>(
    rest: &[P],
    elements: &[[usize; K]],
    make: impl Fn([P; K]) -> Result<R, RestError>,
) -> Result<Vec<R>, FemError> {
    if elements.is_empty() {
        return Err(FemError::EmptyMesh);
    }
    for (q, el) in elements.iter().enumerate() {
        if let Some(&v) = el.iter().find(|&&v| v >= rest.len()) {
            return Err(FemError::VertexOutOfRange {
                term: "fibre".into(),
                stencil: q,
                vertex: v,
                n_vertices: rest.len(),
            });
        }
    }
    let degenerate = |q: usize, e: RestError| FemError::DegenerateRest {
        element: q,
        reason: e.to_string(),
    };
    let rest_of =
        |(q, t): (usize, &[usize; K])| make(t.map(|v| rest[v])).map_err(|e| degenerate(q, e));
    elements.iter().enumerate().map(rest_of).collect()
}

/// Unit directions, one per element; the first unusable one is an error.
fn unit_dirs<const D: usize>(
    dirs: &[[f64; D]],
    n: usize,
) -> Result<Vec<SVector<f64, D>>, FemError> {
    FemError::check_len("fibre directions", n, dirs.len())?;
    dirs.iter()
        .enumerate()
        .map(|(q, d)| {
            unit_fibre(d).ok_or_else(|| FemError::BadFibre {
                element: q,
                direction: d.to_vec(),
                reason: if d.iter().all(|x| x.is_finite()) {
                    "zero (or its length under/overflows)"
                } else {
                    "not finite"
                },
            })
        })
        .collect()
}

impl<E: FibreEnergy<2> + ?Sized> Fibre<E, 2> {
    /// Planar triangles (counter-clockwise = positive area), one 2D fibre each.
    pub fn planar(
        energy: Arc<E>,
        rest: &[[f64; 2]],
        tris: &[[usize; 3]],
        dirs: &[[f64; 2]],
    ) -> Result<Self, FemError> {
        let r = rest_data(rest, tris, Rest::<2>::new)?;
        Ok(Self::build(
            energy,
            tris.as_flattened(),
            r,
            unit_dirs(dirs, tris.len())?,
        ))
    }
}

impl<E: FibreEnergy<3> + ?Sized> Fibre<E, 3> {
    /// Tets (positive volume required), one 3D fibre each.
    pub fn tets(
        energy: Arc<E>,
        rest: &[[f64; 3]],
        tets: &[[usize; 4]],
        dirs: &[[f64; 3]],
    ) -> Result<Self, FemError> {
        let r = rest_data(rest, tets, Rest::<3>::new)?;
        Ok(Self::build(
            energy,
            tets.as_flattened(),
            r,
            unit_dirs(dirs, tets.len())?,
        ))
    }
}

impl<E: ?Sized, const D: usize> Fibre<E, D> {
    fn build(
        energy: Arc<E>,
        elements: &[usize],
        rest: Vec<Rest<D>>,
        dirs: Vec<SVector<f64, D>>,
    ) -> Self {
        Fibre {
            name: "fibre".into(),
            energy,
            elements: elements.to_vec(),
            rest,
            dirs,
        }
    }

    /// Rename the term (shown in reports; default "fibre").
    pub fn named(mut self, name: &str) -> Self {
        self.name = name.to_string();
        self
    }

    /// The energy density.
    pub fn energy(&self) -> &Arc<E> {
        &self.energy
    }

    /// Mutable access to the energy (to change parameters between solves);
    /// `None` while the `Arc` is shared.
    pub fn energy_mut(&mut self) -> Option<&mut E> {
        Arc::get_mut(&mut self.energy)
    }

    /// The unit fibre of every element.
    pub fn directions(&self) -> &[SVector<f64, D>] {
        &self.dirs
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.rest.len()
    }

    /// Whether there are no elements (never true for a constructed term).
    pub fn is_empty(&self) -> bool {
        self.rest.is_empty()
    }
}

impl<E: ?Sized, const D: usize> Fibre<E, D>
where
    Space<D>: Dim<D>,
{
    /// Planar triangles (D = 2) or tets (D = 3) given as a flat element list
    /// (`D + 1` vertex ids each), one fibre per element.
    pub fn from_flat(
        energy: Arc<E>,
        rest: &[[f64; D]],
        elements: &[usize],
        dirs: &[[f64; D]],
    ) -> Result<Self, FemError> {
        let k = D + 1;
        if !elements.len().is_multiple_of(k) {
            return Err(FemError::LengthMismatch {
                what: "element vertex list (D + 1 per element)",
                expected: elements.len() / k * k,
                got: elements.len(),
            });
        }
        let n = elements.len() / k;
        if n == 0 {
            return Err(FemError::EmptyMesh);
        }
        if let Some((q, &v)) = elements.iter().enumerate().find(|&(_, &v)| v >= rest.len()) {
            return Err(FemError::VertexOutOfRange {
                term: "fibre".into(),
                stencil: q / k,
                vertex: v,
                n_vertices: rest.len(),
            });
        }
        let r = (0..n)
            .map(|q| {
                let el = &elements[k * q..k * q + k];
                Rest::<D>::new(<Space<D> as Dim<D>>::gather(rest, el)).map_err(|e| {
                    FemError::DegenerateRest {
                        element: q,
                        reason: e.to_string(),
                    }
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::build(energy, elements, r, unit_dirs(dirs, n)?))
    }

    fn nodes(&self, s: usize, x: &[[f64; D]]) -> Nodes<D> {
        let k = D + 1;
        <Space<D> as Dim<D>>::gather(x, &self.elements[k * s..k * s + k])
    }
}

impl<E, const D: usize> Term<D> for Fibre<E, D>
where
    E: FibreEnergy<D> + ?Sized + 'static,
    Space<D>: FibreDim<D>,
{
    fn name(&self) -> &str {
        &self.name
    }

    fn arity(&self) -> usize {
        D + 1
    }

    fn stencils(&self) -> &[usize] {
        &self.elements
    }

    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        fibre_element_psi(
            &*self.energy,
            &self.rest[s],
            &self.nodes(s, x),
            &self.dirs[s],
        )
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
        let ev = fibre_element_eval(
            &*self.energy,
            &self.rest[s],
            &p,
            &self.dirs[s],
            filter,
            hess.is_some(),
        );
        let n = D * (D + 1);
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
}
