//! Tutte embedding: bijective on the real disk meshes with uniform and
//! mean-value weights, boundary on the unit circle, linear precision of
//! cotangent and mean-value weights on planar meshes, and every error.

mod common;

use std::time::Instant;

use common::data;
use ecc_mesh::geometry::signed_area_uv;
use ecc_mesh::{
    TriMesh, TutteError, TutteWeights, ValidationError, disk_tri, grid_tri, read_tri_mesh,
    tutte_embedding, tutte_embedding_in_order, tutte_embedding_report,
};

const ALL: [TutteWeights; 3] = [
    TutteWeights::Uniform,
    TutteWeights::MeanValue,
    TutteWeights::Cotangent,
];

fn assert_bijective_disk(mesh: &TriMesh, w: TutteWeights, name: &str) {
    let start = Instant::now();
    let e = tutte_embedding_report(mesh, w).unwrap_or_else(|e| panic!("{name} {w:?}: {e}"));
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "{name} {w:?}: {} vertices, {} triangles, {secs:.3} s (dev profile)",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    assert!(
        e.flipped.is_empty(),
        "{name} {w:?}: {} flipped, first {:?}",
        e.flipped.len(),
        e.flipped.first()
    );
    for &v in &e.boundary {
        let [x, y] = e.uv[v];
        assert!(
            (x.hypot(y) - 1.0).abs() < 1e-12,
            "{name}: boundary vertex {v} off the circle"
        );
    }
    let mut on_boundary = vec![false; mesh.positions.len()];
    for &v in &e.boundary {
        on_boundary[v] = true;
    }
    for (v, p) in e.uv.iter().enumerate() {
        if !on_boundary[v] {
            assert!(
                p[0].hypot(p[1]) < 1.0,
                "{name}: interior vertex {v} outside the disk"
            );
        }
    }
    // A bijection onto the boundary polygon: the areas add up to it.
    let nb = e.boundary.len();
    let polygon: f64 = (0..nb)
        .map(|i| {
            signed_area_uv(
                [0.0, 0.0],
                e.uv[e.boundary[i]],
                e.uv[e.boundary[(i + 1) % nb]],
            )
        })
        .sum();
    let total: f64 = mesh
        .triangles
        .iter()
        .map(|t| signed_area_uv(e.uv[t[0]], e.uv[t[1]], e.uv[t[2]]))
        .sum();
    assert!(
        (total - polygon).abs() < 1e-9 * polygon,
        "{name}: {total} vs {polygon}"
    );
}

#[test]
fn real_disks_embed_bijectively_with_uniform_and_mean_value_weights() {
    for name in ["hand_1_i_f5000.obj", "camelhead.off"] {
        let m = read_tri_mesh(data(name)).unwrap();
        for w in [TutteWeights::Uniform, TutteWeights::MeanValue] {
            assert_bijective_disk(&m, w, name);
        }
    }
}

#[test]
fn cotangent_weights_on_real_disks_report_flips_honestly() {
    for name in ["hand_1_i_f5000.obj", "camelhead.off"] {
        let m = read_tri_mesh(data(name)).unwrap();
        let e = tutte_embedding_report(&m, TutteWeights::Cotangent).unwrap();
        eprintln!("{name} Cotangent: {} flipped triangles", e.flipped.len());
        for &f in &e.flipped {
            let t = m.triangles[f];
            assert!(signed_area_uv(e.uv[t[0]], e.uv[t[1]], e.uv[t[2]]) <= 0.0);
        }
        match tutte_embedding(&m, TutteWeights::Cotangent) {
            Ok(uv) => assert!(e.flipped.is_empty() && uv == e.uv),
            Err(TutteError::Flipped { count, first, uv }) => {
                assert_eq!((count, first), (e.flipped.len(), e.flipped[0]));
                assert_eq!(uv, e.uv);
            }
            Err(other) => panic!("{name}: {other}"),
        }
    }
}

#[test]
fn generated_disks_embed_bijectively_with_all_weights() {
    for w in ALL {
        assert_bijective_disk(&disk_tri(12, 2.0), w, "disk_tri(12)");
        assert_bijective_disk(&grid_tri(20, 10, 2.0, 1.0), w, "grid_tri(20, 10)");
    }
}

/// The order is asked for only where it is used: not with mean-value
/// weights (LU), not for a mesh rejected before the solve; with uniform
/// weights, once.
#[test]
fn the_order_is_asked_for_only_when_used() {
    let disk = disk_tri(6, 1.0);
    let never = || -> Option<Vec<usize>> { panic!("the order was asked for") };
    let mv = tutte_embedding_in_order(&disk, TutteWeights::MeanValue, never).unwrap();
    assert_eq!(mv, tutte_embedding(&disk, TutteWeights::MeanValue).unwrap());
    let mut two = disk.clone();
    two.triangles.truncate(1);
    two.positions.push([9.0, 9.0, 9.0]);
    assert!(tutte_embedding_in_order(&two, TutteWeights::Uniform, never).is_err());
    let mut asked = 0;
    let uv = tutte_embedding_in_order(&disk, TutteWeights::Uniform, || {
        asked += 1;
        None::<Vec<usize>>
    })
    .unwrap();
    assert_eq!(asked, 1);
    assert_eq!(uv, tutte_embedding(&disk, TutteWeights::Uniform).unwrap());
}

/// In the mesh's own dissection (shared with the Newton solver) the map
/// is the one in the interior's dissection, to rounding, on real disks and
/// with every weight; an order that is not a permutation of the vertices is
/// not used (the same map as [`tutte_embedding`], bit for bit).
#[test]
fn a_shared_vertex_order_gives_the_same_map() {
    let camel = read_tri_mesh(data("camelhead.off")).unwrap();
    let meshes = [camel, disk_tri(12, 2.0), grid_tri(20, 10, 2.0, 1.0)];
    for (case, mesh) in meshes.iter().enumerate() {
        let n = mesh.positions.len();
        let order =
            ecc_mesh::dissection::mesh_dissection(&mesh.positions, &mesh.triangles).unwrap();
        let mut repeated = order.clone();
        repeated[1] = repeated[0];
        let beyond: Vec<usize> = (1..=n).collect();
        for w in [TutteWeights::Uniform, TutteWeights::Cotangent] {
            let own = match tutte_embedding(mesh, w) {
                Ok(uv) | Err(TutteError::Flipped { uv, .. }) => uv,
                Err(e) => panic!("case {case} {w:?}: {e}"),
            };
            let shared = match tutte_embedding_in_order(mesh, w, || Some(&order)) {
                Ok(uv) | Err(TutteError::Flipped { uv, .. }) => uv,
                Err(e) => panic!("case {case} {w:?}: {e}"),
            };
            let gap = own
                .iter()
                .zip(&shared)
                .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
                .fold(0.0, f64::max);
            assert!(gap < 1e-12, "case {case} {w:?}: maps differ by {gap}");
            let none = tutte_embedding_in_order(mesh, w, || None::<Vec<usize>>);
            match none {
                Ok(uv) | Err(TutteError::Flipped { uv, .. }) => {
                    assert!(uv == own, "case {case} {w:?}: no order is not the own one")
                }
                Err(e) => panic!("case {case} {w:?}: {e}"),
            }
            for bad in [&repeated[..], &order[1..], &beyond[..]] {
                match tutte_embedding_in_order(mesh, w, || Some(bad)) {
                    Ok(uv) | Err(TutteError::Flipped { uv, .. }) => {
                        assert!(uv == own, "case {case} {w:?}: a bad order was used")
                    }
                    Err(e) => panic!("case {case} {w:?}: {e}"),
                }
            }
        }
    }
}

/// Mean-value and cotangent weights reproduce linear functions on planar
/// meshes, and a regular disk's boundary by arc length is its own boundary
/// (up to rotation): so the embedding is a rotation of the input.
#[test]
fn linear_precision_on_a_planar_disk() {
    let m = disk_tri(8, 1.0);
    for w in [TutteWeights::MeanValue, TutteWeights::Cotangent] {
        let e = tutte_embedding_report(&m, w).unwrap();
        let b0 = e.boundary[0];
        let phi = e.uv[b0][1].atan2(e.uv[b0][0]) - m.positions[b0][1].atan2(m.positions[b0][0]);
        let (c, s) = (phi.cos(), phi.sin());
        for (p, q) in m.positions.iter().zip(&e.uv) {
            let r = [c * p[0] - s * p[1], s * p[0] + c * p[1]];
            assert!(
                (r[0] - q[0]).abs() < 1e-12 && (r[1] - q[1]).abs() < 1e-12,
                "{w:?}: {p:?} -> {q:?}"
            );
        }
    }
    // Uniform weights do not have linear precision on this mesh.
    let e = tutte_embedding_report(&m, TutteWeights::Uniform).unwrap();
    let off = m
        .positions
        .iter()
        .zip(&e.uv)
        .map(|(p, q)| (p[0].hypot(p[1]) - q[0].hypot(q[1])).abs())
        .fold(0.0, f64::max);
    assert!(off > 1e-3);
}

/// The unit square as two triangles (a valid disk).
fn square() -> TriMesh {
    TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// The error of the uniform-weight embedding of `m`.
fn err(m: &TriMesh) -> TutteError {
    tutte_embedding(m, TutteWeights::Uniform).unwrap_err()
}

#[test]
fn bad_elements_and_coordinates_are_rejected_with_reasons() {
    assert_eq!(
        err(&TriMesh::default()),
        TutteError::Invalid(ValidationError::NoElements)
    );
    let mut m = square();
    m.triangles[0][2] = 9;
    assert!(matches!(
        err(&m),
        TutteError::Invalid(ValidationError::IndexOutOfRange {
            element: 0,
            index: 9,
            ..
        })
    ));
    let mut m = square();
    m.positions.push([5.0, 5.0, 5.0]);
    let e = err(&m);
    assert_eq!(e, TutteError::UnreferencedVertex { vertex: 4 });
    assert_eq!(
        e.to_string(),
        "vertex 4 is not used by any triangle (validate_tri with drop_unreferenced drops it)"
    );
    let mut m = square();
    m.positions[1][0] = f64::NAN;
    assert!(matches!(
        err(&m),
        TutteError::Invalid(ValidationError::NonFiniteCoordinate { vertex: 1, .. })
    ));
}

#[test]
fn meshes_that_are_not_one_manifold_disk_are_rejected() {
    let bunny = read_tri_mesh(data("bunny.off")).unwrap();
    let e = err(&bunny);
    assert_eq!(e, TutteError::NotADisk { loops: 0 });
    assert_eq!(
        e.to_string(),
        "a Tutte embedding needs a disk (exactly one boundary loop), but the mesh has 0 boundary loops"
    );

    let annulus = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [1.0, 2.0, 0.0],
        ],
        vec![
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ],
    );
    assert_eq!(err(&annulus), TutteError::NotADisk { loops: 2 });

    let mut two = square();
    two.positions
        .extend([[3.0, 0.0, 0.0], [4.0, 0.0, 0.0], [3.0, 1.0, 0.0]]);
    two.triangles.push([4, 5, 6]);
    let e = err(&two);
    assert_eq!(e, TutteError::Disconnected { count: 2 });

    let fin = TriMesh::new(
        vec![
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -1.0, 0.0],
            [0.5, 0.0, 1.0],
        ],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    );
    assert!(matches!(
        err(&fin),
        TutteError::Invalid(ValidationError::NonManifoldEdge { .. })
    ));
}

#[test]
fn degenerate_boundaries_and_infinite_weights_are_rejected() {
    let mut m = square();
    m.positions = vec![[1.0, 1.0, 1.0]; 4];
    assert_eq!(err(&m), TutteError::DegenerateBoundary);
    assert_eq!(
        TutteError::DegenerateBoundary.to_string(),
        "the boundary loop has zero length"
    );

    // A collinear interior triangle makes the cotangent weight infinite.
    let mut m = disk_tri(2, 1.0);
    m.positions[1] = [0.0, 0.0, 0.0];
    m.positions[0] = [0.25, 0.0, 0.0];
    let e = tutte_embedding(&m, TutteWeights::Cotangent).unwrap_err();
    assert!(
        matches!(
            e,
            TutteError::BadWeight {
                weights: TutteWeights::Cotangent,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("weight of edge"), "{e}");
}

/// A valid planar fan whose cotangent weights are negative enough to fold
/// the map: `tutte_embedding` returns the flips (and the map) as an error,
/// `tutte_embedding_report` lists them; mean-value weights do not fold.
#[test]
fn cotangent_weights_can_fold_and_the_fold_is_reported() {
    let ring = [
        [1.86, 0.93],
        [-0.72, 0.05],
        [-2.04, 0.12],
        [-0.3, -0.75],
        [0.09, -0.32],
    ];
    let mut positions = vec![[0.0, 0.0, 0.0]];
    positions.extend(ring.iter().map(|p| [p[0], p[1], 0.0]));
    let triangles = (0..5).map(|i| [0, 1 + i, 1 + (i + 1) % 5]).collect();
    let m = TriMesh::new(positions, triangles);
    ecc_mesh::validate_tri(m.clone(), true, &Default::default()).unwrap();
    let report = tutte_embedding_report(&m, TutteWeights::Cotangent).unwrap();
    assert!(!report.flipped.is_empty());
    match tutte_embedding(&m, TutteWeights::Cotangent).unwrap_err() {
        TutteError::Flipped { count, first, uv } => {
            assert_eq!((count, first), (report.flipped.len(), report.flipped[0]));
            assert_eq!(uv, report.uv);
            let e = TutteError::Flipped { count, first, uv };
            assert_eq!(
                e.to_string(),
                format!(
                    "the embedding is not bijective: {count} triangles have non-positive signed area (first: {first})"
                )
            );
        }
        other => panic!("expected Flipped, got {other}"),
    }
    for w in [TutteWeights::Uniform, TutteWeights::MeanValue] {
        assert!(tutte_embedding(&m, w).is_ok(), "{w:?}");
    }
}
