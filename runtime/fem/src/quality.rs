//! Element orientation checks: flipped triangles and inverted tets.
//!
//! Signed measures use the same conventions as the rest shapes: a planar
//! triangle (x0, x1, x2) has area ½ (x1−x0)×(x2−x0), a tet volume
//! ((x1−x0)×(x2−x0))·(x3−x0)/6. An element is *flipped* / *inverted* when its
//! signed measure is ≤ 0 (degenerate counts as flipped: a barrier energy is
//! infinite there too).

use rayon::prelude::*;

/// Signed area of a planar triangle.
#[inline]
pub fn tri_signed_area(x: &[[f64; 2]], t: [usize; 3]) -> f64 {
    ecc_mesh::geometry::signed_area_uv(x[t[0]], x[t[1]], x[t[2]])
}

/// Signed volume of a tet.
#[inline]
pub fn tet_signed_volume(x: &[[f64; 3]], t: [usize; 4]) -> f64 {
    let (a, b, c, d) = (x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let e3 = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    let cr = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    (cr[0] * e3[0] + cr[1] * e3[1] + cr[2] * e3[2]) / 6.0
}

/// Number of triangles with signed area ≤ 0.
pub fn count_flipped(x: &[[f64; 2]], tris: &[[usize; 3]]) -> usize {
    tris.par_iter()
        .filter(|&&t| tri_signed_area(x, t).is_nan() || tri_signed_area(x, t) <= 0.0)
        .count()
}

/// Number of tets with signed volume ≤ 0.
pub fn count_inverted(x: &[[f64; 3]], tets: &[[usize; 4]]) -> usize {
    tets.par_iter()
        .filter(|&&t| tet_signed_volume(x, t).is_nan() || tet_signed_volume(x, t) <= 0.0)
        .count()
}

/// Smallest signed triangle area (`+∞` for no triangles).
pub fn min_signed_area(x: &[[f64; 2]], tris: &[[usize; 3]]) -> f64 {
    tris.par_iter()
        .map(|&t| tri_signed_area(x, t))
        .reduce(|| f64::INFINITY, f64::min)
}

/// Smallest signed tet volume (`+∞` for no tets).
pub fn min_signed_volume(x: &[[f64; 3]], tets: &[[usize; 4]]) -> f64 {
    tets.par_iter()
        .map(|&t| tet_signed_volume(x, t))
        .reduce(|| f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_counts() {
        let x = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        let tris = [[0, 1, 2], [1, 3, 2], [0, 2, 1]];
        assert_eq!(tri_signed_area(&x, [0, 1, 2]), 0.5);
        assert_eq!(count_flipped(&x, &tris), 1);
        assert_eq!(min_signed_area(&x, &tris), -0.5);
        let y = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        assert!((tet_signed_volume(&y, [0, 1, 2, 3]) - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(count_inverted(&y, &[[0, 1, 2, 3], [0, 2, 1, 3]]), 1);
        assert!(min_signed_volume(&y, &[[0, 1, 2, 3]]) > 0.0);
    }
}
