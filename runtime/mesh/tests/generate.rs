//! Generated meshes are valid, positively oriented, have the documented
//! sizes and the expected topology.

use ecc_mesh::{
    ValidationOptions, bar_tet, boundary_loops, box_tet, box_tet_with_at_least, disk_tri, grid_tri,
    grid_tri_with_at_least, tet_boundary_faces, validate_tet, validate_tri,
};

fn strict() -> ValidationOptions {
    ValidationOptions {
        require_manifold: true,
        require_oriented: true,
        require_single_component: true,
        ..Default::default()
    }
}

fn edge_count(tris: &[[usize; 3]]) -> usize {
    let mut e: Vec<[usize; 2]> = tris
        .iter()
        .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
        .collect();
    e.sort_unstable();
    e.dedup();
    e.len()
}

#[test]
fn grids_and_disks_are_valid_disks() {
    for m in [grid_tri(7, 3, 2.0, 0.5), disk_tri(1, 1.0), disk_tri(9, 3.0)] {
        let n = (m.positions.len(), m.triangles.len());
        let loops = boundary_loops(&m.triangles).unwrap();
        assert_eq!(loops.len(), 1);
        let chi =
            m.positions.len() as i64 - edge_count(&m.triangles) as i64 + m.triangles.len() as i64;
        assert_eq!(chi, 1, "Euler characteristic of a disk");
        let v = validate_tri(m, true, &strict()).unwrap();
        assert!(v.warnings.is_empty(), "{:?}", v.warnings);
        assert_eq!((v.mesh.positions.len(), v.mesh.triangles.len()), n);
    }
    assert_eq!(
        boundary_loops(&grid_tri(7, 3, 1.0, 1.0).triangles).unwrap()[0].len(),
        20
    );
    let disk = disk_tri(9, 3.0);
    let outer = &boundary_loops(&disk.triangles).unwrap()[0];
    assert_eq!(outer.len(), 54);
    for &v in outer {
        let p = disk.positions[v];
        assert!((p[0].hypot(p[1]) - 3.0).abs() < 1e-12);
    }
    let area: f64 = (0..disk.triangles.len())
        .map(|t| disk.signed_area_2d(t).unwrap())
        .sum();
    // Inscribed 54-gon area.
    let polygon = 0.5 * 54.0 * 9.0 * (std::f64::consts::TAU / 54.0).sin();
    assert!((area - polygon).abs() < 1e-10, "{area} vs {polygon}");
}

#[test]
fn boxes_and_bars_are_valid_and_fill_their_volume() {
    let m = box_tet(3, 2, 4, [1.5, 1.0, 2.0]);
    let volume: f64 = (0..m.tets.len()).map(|t| m.signed_volume(t).unwrap()).sum();
    assert!((volume - 3.0).abs() < 1e-12);
    // Boundary: 2 triangles per boundary square.
    assert_eq!(
        tet_boundary_faces(&m.tets).len(),
        4 * (3 * 2 + 2 * 4 + 4 * 3)
    );
    let v = validate_tet(m, &strict()).unwrap();
    assert!(v.warnings.is_empty());

    let bar = bar_tet(3);
    assert_eq!(bar.tets.len(), 24 * 27);
    let lo = bar.positions.iter().fold([f64::MAX; 3], |a, p| {
        [a[0].min(p[0]), a[1].min(p[1]), a[2].min(p[2])]
    });
    let hi = bar.positions.iter().fold([f64::MIN; 3], |a, p| {
        [a[0].max(p[0]), a[1].max(p[1]), a[2].max(p[2])]
    });
    assert_eq!((lo, hi), ([-2.0, -0.5, -0.5], [2.0, 0.5, 0.5]));
    validate_tet(bar, &strict()).unwrap();
}

#[test]
fn benchmark_sizes_reach_their_targets() {
    let big = grid_tri_with_at_least(1_000_000);
    assert_eq!(big.triangles.len(), 1_002_528);
    assert_eq!(big.positions.len(), 709 * 709);
    let big = box_tet_with_at_least(300_000);
    assert_eq!(big.tets.len(), 303_918);
    assert_eq!(big.positions.len(), 38 * 38 * 38);
}
