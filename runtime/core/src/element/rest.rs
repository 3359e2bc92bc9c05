//! Rest-state data of linear triangles and tetrahedra.
//!
//! F = Ds Dm⁻¹ with Dm = [p1−p0, p2−p0(, p3−p0)] at rest and Ds the same at the
//! current positions. Rest measures: area = det(Dm)/2, volume = det(Dm)/6.
//!
//! A rest element is rejected as *degenerate* when a coordinate is not finite
//! or |det Dm| ≤ 10⁻¹² · L^d (L = longest rest edge): its Dm⁻¹ would be
//! meaningless. Planar triangles and tetrahedra with a negative signed
//! measure are *inverted*; surface triangles (from 3D points) have no sign.

use crate::dim::{Dim, Nodes, Space};
use nalgebra::{Matrix2, Matrix3, SMatrix};

/// Relative tolerance on |det Dm| / L^d below which a rest element is degenerate.
pub const DEGENERATE_REL_TOL: f64 = 1e-12;

/// Why a rest element cannot be used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RestError {
    /// Zero (to [`DEGENERATE_REL_TOL`]) or non-finite measure; `measure` is the
    /// signed area/volume (NaN when a coordinate is not finite).
    Degenerate { measure: f64 },
    /// Negative signed area (planar triangle) or volume (tetrahedron).
    Inverted { measure: f64 },
}

impl std::fmt::Display for RestError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RestError::Degenerate { measure } => {
                write!(f, "degenerate rest element (signed measure {measure:e})")
            }
            RestError::Inverted { measure } => {
                write!(f, "inverted rest element (signed measure {measure:e} < 0)")
            }
        }
    }
}

impl std::error::Error for RestError {}

/// Rest data of a linear simplex (triangle for D = 2, tetrahedron for D = 3):
/// Dm⁻¹ (d×d) and the rest measure (area or volume, > 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rest<const D: usize> {
    /// Inverse of the rest edge matrix Dm = [p1−p0, …, p_d−p0].
    pub dm_inv: SMatrix<f64, D, D>,
    /// Rest measure |q| = |det Dm| / d! (area or volume, > 0).
    pub measure: f64,
}

impl<const D: usize> Rest<D>
where
    Space<D>: Dim<D>,
{
    /// Rest data of a planar triangle (D = 2, counter-clockwise = positive
    /// area) or a tetrahedron (D = 3, positive volume when
    /// (p1−p0, p2−p0, p3−p0) is right-handed).
    pub fn new(p: Nodes<D>) -> Result<Self, RestError> {
        <Space<D> as Dim<D>>::rest(&p)
    }
}

/// [`Rest::new`] for a planar triangle.
pub(crate) fn planar_triangle(p: &[[f64; 2]; 3]) -> Result<Rest<2>, RestError> {
    let e1 = sub(&p[1], &p[0]);
    let e2 = sub(&p[2], &p[0]);
    let dm = Matrix2::new(e1[0], e2[0], e1[1], e2[1]);
    let det = dm.determinant();
    check(det, 2.0, longest_edge(p), 2, true)?;
    Ok(Rest {
        dm_inv: inverse2(&dm, det),
        measure: 0.5 * det,
    })
}

fn sub<const D: usize>(a: &[f64; D], b: &[f64; D]) -> [f64; D] {
    std::array::from_fn(|i| a[i] - b[i])
}

fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Longest edge of the simplex with vertices `p`.
fn longest_edge<const D: usize>(p: &[[f64; D]]) -> f64 {
    let mut l = 0.0f64;
    for i in 0..p.len() {
        for j in (i + 1)..p.len() {
            l = l.max(norm(&sub(&p[i], &p[j])));
        }
    }
    l
}

/// Classify det Dm: Ok when usable, otherwise the error (measure = det/den).
fn check(det: f64, den: f64, l: f64, d: i32, signed: bool) -> Result<(), RestError> {
    let measure = det / den;
    let usable = det.abs() > DEGENERATE_REL_TOL * l.powi(d); // false for NaN
    if !usable || !l.is_finite() {
        return Err(RestError::Degenerate {
            measure: if l.is_finite() { measure } else { f64::NAN },
        });
    }
    if signed && det < 0.0 {
        return Err(RestError::Inverted { measure });
    }
    Ok(())
}

impl Rest<2> {
    /// Rest data of a surface triangle in 3D, expressed in an isometric 2D
    /// frame: e1 = p1 − p0 maps to (|e1|, 0) and e2 = p2 − p0 to
    /// (e1·e2/|e1|, |e1×e2|/|e1|), so the area is always positive.
    pub fn from_3d(p: [[f64; 3]; 3]) -> Result<Self, RestError> {
        let e1 = sub(&p[1], &p[0]);
        let e2 = sub(&p[2], &p[0]);
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let l1 = norm(&e1);
        let det = norm(&c);
        check(det, 2.0, longest_edge(&p), 2, false)?;
        let dm = Matrix2::new(
            l1,
            (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1,
            0.0,
            det / l1,
        );
        Ok(Rest {
            dm_inv: inverse2(&dm, det),
            measure: 0.5 * det,
        })
    }
}

/// [`Rest::new`] for a tetrahedron.
pub(crate) fn tetrahedron(p: &[[f64; 3]; 4]) -> Result<Rest<3>, RestError> {
    let e: [[f64; 3]; 3] = std::array::from_fn(|k| sub(&p[k + 1], &p[0]));
    let dm = Matrix3::from_fn(|i, j| e[j][i]);
    let det = dm.determinant();
    check(det, 6.0, longest_edge(p), 3, true)?;
    // Cofactor inverse: exact formula, no pivoting needed for a checked det.
    let inv = Matrix3::new(
        dm[(1, 1)] * dm[(2, 2)] - dm[(1, 2)] * dm[(2, 1)],
        dm[(0, 2)] * dm[(2, 1)] - dm[(0, 1)] * dm[(2, 2)],
        dm[(0, 1)] * dm[(1, 2)] - dm[(0, 2)] * dm[(1, 1)],
        dm[(1, 2)] * dm[(2, 0)] - dm[(1, 0)] * dm[(2, 2)],
        dm[(0, 0)] * dm[(2, 2)] - dm[(0, 2)] * dm[(2, 0)],
        dm[(0, 2)] * dm[(1, 0)] - dm[(0, 0)] * dm[(1, 2)],
        dm[(1, 0)] * dm[(2, 1)] - dm[(1, 1)] * dm[(2, 0)],
        dm[(0, 1)] * dm[(2, 0)] - dm[(0, 0)] * dm[(2, 1)],
        dm[(0, 0)] * dm[(1, 1)] - dm[(0, 1)] * dm[(1, 0)],
    ) / det;
    Ok(Rest {
        dm_inv: inv,
        measure: det / 6.0,
    })
}

fn inverse2(dm: &Matrix2<f64>, det: f64) -> Matrix2<f64> {
    Matrix2::new(dm[(1, 1)], -dm[(0, 1)], -dm[(1, 0)], dm[(0, 0)]) / det
}

impl<const D: usize> Rest<D> {
    /// The rest-time factors of the exact element projection
    /// ([`crate::element_eval_projected`]): M^{±½} of M = βᵀβ, see
    /// [`crate::element::Congruence`].
    pub fn congruence(&self) -> super::Congruence<D> {
        super::Congruence::new(self)
    }
}
