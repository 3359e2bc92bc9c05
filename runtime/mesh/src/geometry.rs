//! Element measures and rest frames.
//!
//! * planar triangle signed area: `A = ((b − a) × (c − a))_z / 2`
//!   (positive for counter-clockwise vertices);
//! * surface triangle area: `A = |(b − a) × (c − a)| / 2`;
//! * tet signed volume: `V = ((b − a) × (c − a)) · (d − a) / 6`;
//! * isometric rest frame of a surface triangle: `e1 = (b − a)/|b − a|`,
//!   `n = (b − a) × (c − a)`, `e2 = n̂ × e1`; the 2D rest positions are
//!   `(0, 0)`, `(|b − a|, 0)`, `((c − a)·e1, (c − a)·e2)`, which preserves
//!   lengths and angles and gives positive signed area.

use crate::types::{TetMesh, TriMesh};

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Signed area of the triangle `(a, b, c)` projected to the xy plane.
pub fn signed_area_2d(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    signed_area_uv([a[0], a[1]], [b[0], b[1]], [c[0], c[1]])
}

/// Signed area of a triangle given by 2D points: ½ (b − a) × (c − a),
/// positive for counter-clockwise order. The workspace's one copy of this
/// formula outside the eigensystem core (which cannot depend on ecc-mesh).
pub fn signed_area_uv(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// Unsigned area of the triangle `(a, b, c)` in 3D.
pub fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    0.5 * norm(cross(sub(b, a), sub(c, a)))
}

/// Signed volume of the tet `(a, b, c, d)`.
pub fn tet_signed_volume(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    dot(cross(sub(b, a), sub(c, a)), sub(d, a)) / 6.0
}

/// Isometric 2D rest frame of a 3D triangle (see the module docs).
/// Returns `None` when the triangle is degenerate (zero edge or zero area).
pub fn triangle_rest_frame(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<[[f64; 2]; 3]> {
    let e = sub(b, a);
    let f = sub(c, a);
    let len = norm(e);
    let n = cross(e, f);
    let nn = norm(n);
    if len == 0.0 || nn == 0.0 || !len.is_finite() || !nn.is_finite() {
        return None;
    }
    let e1 = [e[0] / len, e[1] / len, e[2] / len];
    let nh = [n[0] / nn, n[1] / nn, n[2] / nn];
    let e2 = cross(nh, e1);
    Some([[0.0, 0.0], [len, 0.0], [dot(f, e1), dot(f, e2)]])
}

/// Axis-aligned bounding box `(min, max)` of some points, `None` if empty.
pub fn bounding_box(points: impl IntoIterator<Item = [f64; 3]>) -> Option<([f64; 3], [f64; 3])> {
    let mut it = points.into_iter();
    let first = it.next()?;
    let (mut lo, mut hi) = (first, first);
    for p in it {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Some((lo, hi))
}

/// Length of the bounding-box diagonal (0 for an empty set).
pub fn bbox_diagonal(points: impl IntoIterator<Item = [f64; 3]>) -> f64 {
    match bounding_box(points) {
        Some((lo, hi)) => norm(sub(hi, lo)),
        None => 0.0,
    }
}

impl TriMesh {
    /// A mesh without uvs.
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[usize; 3]>) -> Self {
        TriMesh {
            positions,
            triangles,
            uvs: None,
        }
    }

    /// The positions of triangle `t`'s corners, `None` if `t` or one of its
    /// indices is out of range.
    pub fn corners(&self, t: usize) -> Option<[[f64; 3]; 3]> {
        let tri = self.triangles.get(t)?;
        Some([
            *self.positions.get(tri[0])?,
            *self.positions.get(tri[1])?,
            *self.positions.get(tri[2])?,
        ])
    }

    /// Signed xy-area of triangle `t` (planar meshes).
    pub fn signed_area_2d(&self, t: usize) -> Option<f64> {
        let [a, b, c] = self.corners(t)?;
        Some(signed_area_2d(a, b, c))
    }

    /// Unsigned 3D area of triangle `t`.
    pub fn area(&self, t: usize) -> Option<f64> {
        let [a, b, c] = self.corners(t)?;
        Some(triangle_area(a, b, c))
    }

    /// Isometric 2D rest frame of triangle `t` (positive signed area), for
    /// parameterising surfaces. For a planar counter-clockwise triangle it is
    /// a rigid motion of the xy coordinates.
    pub fn rest_frame(&self, t: usize) -> Option<[[f64; 2]; 3]> {
        let [a, b, c] = self.corners(t)?;
        triangle_rest_frame(a, b, c)
    }

    /// `true` if every vertex has `z = 0`.
    pub fn is_planar(&self) -> bool {
        self.positions.iter().all(|p| p[2] == 0.0)
    }

    /// Bounding-box diagonal of all vertices.
    pub fn bbox_diagonal(&self) -> f64 {
        bbox_diagonal(self.positions.iter().copied())
    }
}

impl TetMesh {
    /// A tet mesh.
    pub fn new(positions: Vec<[f64; 3]>, tets: Vec<[usize; 4]>) -> Self {
        TetMesh { positions, tets }
    }

    /// The positions of tet `t`'s corners, `None` if out of range.
    pub fn corners(&self, t: usize) -> Option<[[f64; 3]; 4]> {
        let tet = self.tets.get(t)?;
        Some([
            *self.positions.get(tet[0])?,
            *self.positions.get(tet[1])?,
            *self.positions.get(tet[2])?,
            *self.positions.get(tet[3])?,
        ])
    }

    /// Signed volume of tet `t`.
    pub fn signed_volume(&self, t: usize) -> Option<f64> {
        let [a, b, c, d] = self.corners(t)?;
        Some(tet_signed_volume(a, b, c, d))
    }

    /// Bounding-box diagonal of all vertices.
    pub fn bbox_diagonal(&self) -> f64 {
        bbox_diagonal(self.positions.iter().copied())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_frame_preserves_lengths_and_is_positive() {
        let a = [1.0, 2.0, 3.0];
        let b = [2.0, 2.5, 3.7];
        let c = [0.3, 3.1, 2.2];
        let f = triangle_rest_frame(a, b, c).unwrap();
        let d2 = |p: [f64; 2], q: [f64; 2]| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
        assert!((d2(f[0], f[1]) - norm(sub(b, a))).abs() < 1e-14);
        assert!((d2(f[0], f[2]) - norm(sub(c, a))).abs() < 1e-14);
        assert!((d2(f[1], f[2]) - norm(sub(c, b))).abs() < 1e-14);
        let area = signed_area_uv(f[0], f[1], f[2]);
        assert!((area - triangle_area(a, b, c)).abs() < 1e-14);
        assert!(area > 0.0);
        assert!(triangle_rest_frame(a, a, c).is_none());
    }

    #[test]
    fn unit_tet_volume_and_orientation() {
        let o = [0.0; 3];
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(tet_signed_volume(o, x, y, z), 1.0 / 6.0);
        assert_eq!(tet_signed_volume(o, y, x, z), -1.0 / 6.0);
        assert_eq!(signed_area_2d(o, x, y), 0.5);
    }
}
