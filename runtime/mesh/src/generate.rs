//! Built-in generated meshes: planar grids and disks of triangles, boxes
//! and bars of tets. All elements are positively oriented (counter-
//! clockwise triangles in the xy plane, positive-volume tets), every
//! vertex is referenced, and the meshes pass [`crate::validate_tri`] /
//! [`crate::validate_tet`] with every requirement switched on.
//!
//! A zero resolution gives an empty mesh (no vertices, no elements).
//! The one exception to "passes validation" is [`disk_with_ear`], a fixture
//! for the validation rule itself (a sliver, or a degenerate triangle).

use std::f64::consts::TAU;

use crate::types::{TetMesh, TriMesh};

/// A `width × height` rectangle `[0, width] × [0, height]` (z = 0) split
/// into `nx × ny` cells of two triangles each: `(nx + 1)(ny + 1)` vertices,
/// `2 nx ny` triangles. Vertex `(i, j)` has id `j (nx + 1) + i`.
pub fn grid_tri(nx: usize, ny: usize, width: f64, height: f64) -> TriMesh {
    if nx == 0 || ny == 0 {
        return TriMesh::default();
    }
    let mut positions = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            let x = width * i as f64 / nx as f64;
            let y = height * j as f64 / ny as f64;
            positions.push([x, y, 0.0]);
        }
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let mut triangles = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles)
}

/// A unit-square grid with at least `target` triangles: `n × n` cells
/// with `n = ⌈√(target / 2)⌉` (e.g. `10_000 → 71² · 2 = 10_082`,
/// `1_000_000 → 708² · 2 = 1_002_528`).
pub fn grid_tri_with_at_least(target: usize) -> TriMesh {
    let mut n = ((target as f64 / 2.0).sqrt().ceil() as usize).max(1);
    while 2 * n * n < target {
        n += 1;
    }
    grid_tri(n, n, 1.0, 1.0)
}

/// A disk of the given radius centred at the origin (z = 0): a centre
/// vertex and `rings` concentric rings, ring `k` with `6k` vertices at
/// radius `k · radius / rings`. Neighbouring rings are zipped together by
/// angle: `1 + 3 rings (rings + 1)` vertices, `6 rings²` triangles, one
/// boundary loop (the outer ring, `6 rings` vertices).
pub fn disk_tri(rings: usize, radius: f64) -> TriMesh {
    if rings == 0 {
        return TriMesh::default();
    }
    let mut positions = vec![[0.0, 0.0, 0.0]];
    let mut ring_start = vec![0usize];
    for k in 1..=rings {
        ring_start.push(positions.len());
        let r = radius * k as f64 / rings as f64;
        let n = 6 * k;
        for i in 0..n {
            let a = TAU * i as f64 / n as f64;
            positions.push([r * a.cos(), r * a.sin(), 0.0]);
        }
    }
    let mut triangles = Vec::with_capacity(6 * rings * rings);
    for i in 0..6 {
        triangles.push([0, 1 + i, 1 + (i + 1) % 6]);
    }
    for k in 2..=rings {
        let (inner, outer) = (ring_start[k - 1], ring_start[k]);
        let (n_in, n_out) = (6 * (k - 1), 6 * k);
        let (mut i, mut j) = (0usize, 0usize); // steps taken on outer / inner
        while i < n_out || j < n_in {
            // Compare the angles of the next outer (i+1)/n_out and the next
            // inner (j+1)/n_in vertex exactly: (i+1)(k-1) vs (j+1)k.
            let advance_outer = j == n_in || (i < n_out && (i + 1) * (k - 1) <= (j + 1) * k);
            let cur_in = inner + j % n_in;
            let cur_out = outer + i % n_out;
            if advance_outer {
                triangles.push([cur_in, cur_out, outer + (i + 1) % n_out]);
                i += 1;
            } else {
                triangles.push([cur_in, cur_out, inner + (j + 1) % n_in]);
                j += 1;
            }
        }
    }
    TriMesh::new(positions, triangles)
}

/// The 6 tets of the Kuhn (Freudenthal) split of a unit cube, as corner
/// bit masks (bit 0 = x, bit 1 = y, bit 2 = z), positively oriented. Tet
/// `(0, e_a, e_a + e_b, 1)` for each axis order `(a, b, c)` has volume
/// `sign(a b c) / 6`; odd orders get their last two vertices swapped. The
/// split is the same in every cube, so neighbouring cubes share faces.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 3, 7], // x y z (even)
    [0, 2, 6, 7], // y z x (even)
    [0, 4, 5, 7], // z x y (even)
    [0, 1, 7, 5], // x z y (odd, swapped)
    [0, 2, 7, 3], // y x z (odd, swapped)
    [0, 4, 7, 6], // z y x (odd, swapped)
];

/// A box `[0, size_x] × [0, size_y] × [0, size_z]` of `nx × ny × nz` cubes,
/// 6 positively oriented tets each: `(nx+1)(ny+1)(nz+1)` vertices,
/// `6 nx ny nz` tets. Vertex `(i, j, k)` has id `(k (ny+1) + j)(nx+1) + i`.
pub fn box_tet(nx: usize, ny: usize, nz: usize, size: [f64; 3]) -> TetMesh {
    if nx == 0 || ny == 0 || nz == 0 {
        return TetMesh::default();
    }
    let mut positions = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                positions.push([
                    size[0] * i as f64 / nx as f64,
                    size[1] * j as f64 / ny as f64,
                    size[2] * k as f64 / nz as f64,
                ]);
            }
        }
    }
    let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
    let mut tets = Vec::with_capacity(6 * nx * ny * nz);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let corner = |m: usize| id(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1));
                for t in KUHN {
                    tets.push(t.map(corner));
                }
            }
        }
    }
    TetMesh::new(positions, tets)
}

/// A unit cube `[0, 1]³` with at least `target` tets: `n³` cubes with
/// `n = ⌈∛(target / 6)⌉` (e.g. `10_000 → 12³ · 6 = 10_368`,
/// `300_000 → 37³ · 6 = 303_918`).
pub fn box_tet_with_at_least(target: usize) -> TetMesh {
    let mut n = ((target as f64 / 6.0).cbrt().ceil() as usize).max(1);
    while 6 * n * n * n < target {
        n += 1;
    }
    box_tet(n, n, n, [1.0; 3])
}

/// A bar `[-2, 2] × [-0.5, 0.5] × [-0.5, 0.5]` (length 4 along x, centred
/// at the origin) of `4r × r × r` cubes: `24 r³` tets. `r = 0` gives an
/// empty mesh.
pub fn bar_tet(resolution: usize) -> TetMesh {
    let r = resolution;
    let mut m = box_tet(4 * r, r, r, [4.0, 1.0, 1.0]);
    for p in &mut m.positions {
        p[0] -= 2.0;
        p[1] -= 0.5;
        p[2] -= 0.5;
    }
    m
}

/// `disk_tri(6, 1)` with a tiny ear on its boundary, the fixture of the
/// per-element validation rule: boundary edge (a, b) of triangle T is split
/// at m = a + ε(b − a) (T becomes (a, m, c) and (m, b, c)) and the ear
/// (a, p, m) is added outside, p at height `h` over the middle of am. With
/// |am| ≈ 7.7e-4 and h = 1.4e-8 the ear has area ≈ 5.3e-12 (below
/// 1e-12 × the bounding-box diagonal² ≈ 8e-12, a whole-mesh tolerance) and
/// quality area ÷ longest edge² ≈ 9e-6: a genuine sliver. `h = 0` puts p on
/// am: a degenerate ear. Returns the mesh and the ear's triangle id.
pub fn disk_with_ear(h: f64) -> (TriMesh, usize) {
    let mut m = disk_tri(6, 1.0);
    let lp = crate::boundary_loops(&m.triangles).expect("a disk has one boundary loop");
    let (a, b) = (lp[0][0], lp[0][1]);
    let t = m
        .triangles
        .iter()
        .position(|t| t.contains(&a) && t.contains(&b))
        .expect("a boundary edge has a triangle");
    let (pa, pb) = (m.positions[a], m.positions[b]);
    let ab = ((pb[0] - pa[0]).powi(2) + (pb[1] - pa[1]).powi(2)).sqrt();
    let eps = 7.7e-4 / ab;
    let pm = [
        pa[0] + eps * (pb[0] - pa[0]),
        pa[1] + eps * (pb[1] - pa[1]),
        0.0,
    ];
    let mid = [(pa[0] + pm[0]) / 2.0, (pa[1] + pm[1]) / 2.0];
    let r = (mid[0] * mid[0] + mid[1] * mid[1]).sqrt();
    let pp = [mid[0] + h * mid[0] / r, mid[1] + h * mid[1] / r, 0.0];
    let (im, ip) = (m.positions.len(), m.positions.len() + 1);
    m.positions.push(pm);
    m.positions.push(pp);
    let tri = m.triangles[t];
    m.triangles[t] = tri.map(|v| if v == b { im } else { v });
    m.triangles.push(tri.map(|v| if v == a { im } else { v }));
    let ear = if crate::geometry::signed_area_2d(pa, pp, pm) >= 0.0 {
        [a, ip, im]
    } else {
        [a, im, ip]
    };
    m.triangles.push(ear);
    let id = m.triangles.len() - 1;
    (m, id)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::tet_signed_volume;

    #[test]
    fn kuhn_tets_are_positive_and_fill_the_cube() {
        let corner = |m: usize| [(m & 1) as f64, ((m >> 1) & 1) as f64, ((m >> 2) & 1) as f64];
        let mut total = 0.0;
        for t in KUHN {
            let v = tet_signed_volume(corner(t[0]), corner(t[1]), corner(t[2]), corner(t[3]));
            assert!((v - 1.0 / 6.0).abs() < 1e-15, "{t:?}: {v}");
            total += v;
        }
        assert!((total - 1.0).abs() < 1e-15);
    }

    #[test]
    fn sizes_and_empty_meshes() {
        assert_eq!(grid_tri(3, 2, 1.0, 1.0).triangles.len(), 12);
        assert_eq!(grid_tri(3, 2, 1.0, 1.0).positions.len(), 12);
        assert_eq!(disk_tri(4, 1.0).triangles.len(), 96);
        assert_eq!(disk_tri(4, 1.0).positions.len(), 61);
        assert_eq!(box_tet(2, 3, 4, [1.0; 3]).tets.len(), 144);
        assert_eq!(bar_tet(2).tets.len(), 192);
        assert!(grid_tri(0, 5, 1.0, 1.0).triangles.is_empty());
        assert!(disk_tri(0, 1.0).positions.is_empty());
        assert!(box_tet(1, 0, 1, [1.0; 3]).tets.is_empty());
        assert_eq!(grid_tri_with_at_least(10_000).triangles.len(), 10_082);
        assert_eq!(box_tet_with_at_least(10_000).tets.len(), 10_368);
        assert_eq!(grid_tri_with_at_least(0).triangles.len(), 2);
    }
}
