//! The simulated body in dimension `D`: rest positions, simplices and the
//! energy density, plus the one dimension-specific operation (building the
//! elastic term over triangles in 2D or tets in 3D).

use std::sync::Arc;

use ecc_fem::elastic::Projection;
use ecc_fem::{Elastic, FemError, Term, Tet, Tri};
use ecc_runtime::Energy;

/// `x` as a `T` when `T` is its own type (`Arc<dyn Energy<D>>` is
/// `Arc<dyn Energy<2>>` when D = 2); `None` never happens for the types used here.
fn same<T: 'static>(x: impl std::any::Any) -> Option<T> {
    (Box::new(x) as Box<dyn std::any::Any>)
        .downcast::<T>()
        .ok()
        .map(|b| *b)
}

/// `Σ_q |q| Ψ(F_q)` over the flat simplices `el` at rest positions `rest`:
/// planar triangles in 2D, tets in 3D (the scene's one choice by dimension).
fn elastic<const D: usize>(
    e: Arc<dyn Energy<D>>,
    rest: &[[f64; D]],
    el: &[usize],
    projection: Projection,
) -> Result<Box<dyn Term<D>>, FemError> {
    let p = rest.as_flattened();
    let term: Box<dyn std::any::Any> = match D {
        2 => {
            let e = same::<Arc<dyn Energy<2>>>(e).expect("D = 2");
            let t = Elastic::<dyn Energy<2>, Tri>::planar(e, p.as_chunks().0, el.as_chunks().0)?
                .with_projection(projection);
            Box::new(Box::new(t) as Box<dyn Term<2>>)
        }
        _ => {
            let e = same::<Arc<dyn Energy<3>>>(e).expect("D = 3");
            let t = Elastic::<dyn Energy<3>, Tet>::new(e, p.as_chunks().0, el.as_chunks().0)?
                .with_projection(projection);
            Box::new(Box::new(t) as Box<dyn Term<3>>)
        }
    };
    Ok(*term.downcast::<Box<dyn Term<D>>>().expect("D = 2 or 3"))
}

/// A body of linear simplices (triangles in 2D, tets in 3D).
#[derive(Clone)]
pub struct Body<const D: usize> {
    /// Rest positions.
    pub rest: Vec<[f64; D]>,
    /// Simplices, flat, `D + 1` vertex ids each.
    pub elements: Vec<usize>,
    /// The energy density Ψ.
    pub energy: Arc<dyn Energy<D>>,
    /// How the elastic term projects element Hessians (default F-space).
    pub projection: Projection,
}

impl Body<2> {
    /// Planar triangles (counter-clockwise).
    pub fn planar(rest: Vec<[f64; 2]>, tris: &[[usize; 3]], energy: Arc<dyn Energy<2>>) -> Self {
        Body {
            rest,
            elements: tris.as_flattened().to_vec(),
            energy,
            projection: Projection::default(),
        }
    }
}

impl Body<3> {
    /// Positively oriented tets.
    pub fn volume(rest: Vec<[f64; 3]>, tets: &[[usize; 4]], energy: Arc<dyn Energy<3>>) -> Self {
        Body {
            rest,
            elements: tets.as_flattened().to_vec(),
            energy,
            projection: Projection::default(),
        }
    }
}

impl<const D: usize> Body<D> {
    /// Vertices per element.
    pub const ARITY: usize = D + 1;

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.rest.len()
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.elements.len() / (D + 1)
    }

    /// Vertex ids of element `q`.
    pub fn element(&self, q: usize) -> &[usize] {
        &self.elements[q * (D + 1)..(q + 1) * (D + 1)]
    }

    /// The same body with element Hessians projected by `projection`.
    pub fn with_projection(mut self, projection: Projection) -> Self {
        self.projection = projection;
        self
    }

    /// The elastic term for the given rest positions (same elements).
    pub fn elastic_at(&self, rest: &[[f64; D]]) -> Result<Box<dyn Term<D>>, FemError> {
        elastic(self.energy.clone(), rest, &self.elements, self.projection)
    }

    /// The elastic term over the body's own rest shape.
    pub fn elastic(&self) -> Result<Box<dyn Term<D>>, FemError> {
        self.elastic_at(&self.rest)
    }

    /// Signed measure of every element at positions `x` (area in 2D, volume in 3D).
    pub fn measures(&self, x: &[[f64; D]]) -> Vec<f64> {
        (0..self.n_elements())
            .map(|q| signed_measure(x, self.element(q)))
            .collect()
    }

    /// Σ|q| of the rest shape.
    pub fn total_rest_measure(&self) -> f64 {
        self.measures(&self.rest).iter().map(|m| m.abs()).sum()
    }
}

/// Signed measure of one simplex: ½ det[e1 e2] in 2D, ⅙ det[e1 e2 e3] in 3D.
pub fn signed_measure<const D: usize>(x: &[[f64; D]], el: &[usize]) -> f64 {
    let p0 = x[el[0]];
    // edge vectors e_k = x_{k+1} − x_0 (a zero third edge in 2D)
    let e: [[f64; D]; 3] = std::array::from_fn(|k| match el.get(k + 1) {
        Some(&v) if k < D => std::array::from_fn(|c| x[v][c] - p0[c]),
        _ => [0.0; D],
    });
    if D == 2 {
        0.5 * (e[0][0] * e[1][1] - e[0][1] * e[1][0])
    } else {
        let (a, b, c) = (&e[0], &e[1], &e[2]);
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))
            / 6.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ecc_runtime::energies::Arap;

    #[test]
    fn measures_and_elastic_terms() {
        let b2 = Body::planar(
            vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            &[[0, 1, 2]],
            Arc::new(Arap),
        );
        assert_eq!(b2.total_rest_measure(), 0.5);
        assert_eq!(b2.elastic().unwrap().n_stencils(), 1);
        let b3 = Body::volume(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            &[[0, 1, 2, 3]],
            Arc::new(Arap),
        );
        assert!((b3.total_rest_measure() - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(b3.elastic().unwrap().arity(), 4);
    }
}
