//! Every validation error variant, with its message, and the success paths
//! (vertex dropping, warnings) on hand-made and real meshes.

mod common;

use common::data;
use ecc_mesh::{
    TetMesh, TriMesh, ValidationError as E, ValidationOptions, read_tet_mesh, read_tri_mesh,
    validate_tet, validate_tri,
};

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

fn unit_tet() -> TetMesh {
    TetMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        vec![[0, 1, 2, 3]],
    )
}

fn tri_err(m: TriMesh, planar: bool, opts: &ValidationOptions) -> (E, String) {
    let e = validate_tri(m, planar, opts).unwrap_err();
    let s = e.to_string();
    (e, s)
}

#[test]
fn structural_errors() {
    let o = ValidationOptions::default();
    let (e, s) = tri_err(TriMesh::default(), true, &o);
    assert_eq!((e, s.as_str()), (E::NoElements, "the mesh has no elements"));

    let mut m = square();
    m.triangles[1] = [0, 2, 7];
    let (e, s) = tri_err(m, true, &o);
    assert_eq!(
        e,
        E::IndexOutOfRange {
            element: 1,
            index: 7,
            vertex_count: 4
        }
    );
    assert_eq!(
        s,
        "element 1 refers to vertex 7, but there are only 4 vertices (valid ids 0..4)"
    );

    let mut m = square();
    m.triangles[0] = [0, 1, 0];
    let (e, s) = tri_err(m, true, &o);
    assert!(matches!(e, E::RepeatedVertexInElement { element: 0, .. }));
    assert_eq!(s, "element 0 uses a vertex more than once: [0, 1, 0]");

    let mut m = square();
    m.triangles.push([2, 0, 1]);
    let (e, s) = tri_err(m, true, &o);
    assert_eq!(
        e,
        E::DuplicateElement {
            element: 2,
            first: 0
        }
    );
    assert_eq!(s, "element 2 duplicates element 0 (same vertices)");

    let mut m = square();
    m.positions[2][1] = f64::NAN;
    let (e, s) = tri_err(m, true, &o);
    assert!(matches!(e, E::NonFiniteCoordinate { vertex: 2, .. }));
    assert!(
        s.starts_with("vertex 2 has a non-finite coordinate [1.0, NaN, 0.0]"),
        "{s}"
    );

    let mut m = square();
    m.positions[3][2] = 0.5;
    let (e, s) = tri_err(m.clone(), true, &o);
    assert_eq!(e, E::NotPlanar { vertex: 3, z: 0.5 });
    assert_eq!(
        s,
        "vertex 3 of a planar mesh has z = 0.5 (planar meshes need z = 0)"
    );
    assert!(
        validate_tri(m, false, &o).is_ok(),
        "a surface may leave the plane"
    );

    let mut m = square();
    m.uvs = Some(vec![[0.0, 0.0]; 3]);
    let (e, s) = tri_err(m, true, &o);
    assert_eq!(
        e,
        E::UvCountMismatch {
            uvs: 3,
            vertices: 4
        }
    );
    assert_eq!(s, "the mesh has 3 texture coordinates for 4 vertices");

    let mut m = square();
    m.uvs = Some(vec![
        [0.0, 0.0],
        [1.0, f64::INFINITY],
        [0.0, 0.0],
        [0.0, 0.0],
    ]);
    let (e, s) = tri_err(m, true, &o);
    assert!(matches!(e, E::NonFiniteUv { vertex: 1, .. }));
    assert_eq!(
        s,
        "texture coordinate of vertex 1 is not finite: [1.0, inf]"
    );
}

#[test]
fn degenerate_and_inverted_elements() {
    let o = ValidationOptions::default();
    let mut m = square();
    m.positions[2] = [2.0, 0.0, 0.0]; // triangle 0 collapses onto the x axis
    let (e, s) = tri_err(m, true, &o);
    assert!(
        matches!(
            e,
            E::DegenerateElement {
                element: 0,
                dimension: 2,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        s.starts_with("element 0 is degenerate: rest area 0e0 is below the tolerance"),
        "{s}"
    );

    let mut m = square();
    m.triangles[1] = [0, 3, 2];
    let (e, s) = tri_err(m, true, &o);
    assert_eq!(
        e,
        E::InvertedElement {
            element: 1,
            measure: -0.5,
            count: 1,
            total: 2,
            dimension: 2
        }
    );
    assert_eq!(
        s,
        "element 1 is inverted: signed rest area -5e-1 < 0 (1 of 2 elements are inverted)"
    );

    let mut m = square();
    m.triangles = vec![[0, 2, 1], [0, 3, 2]];
    let (_, s) = tri_err(m.clone(), true, &o);
    assert!(s.ends_with("(2 of 2 elements are inverted; the whole mesh has the opposite orientation: swap two vertices of every element)"), "{s}");
    assert!(validate_tri(m, false, &o).is_ok(), "surfaces have no sign");

    let mut t = unit_tet();
    t.tets[0] = [0, 2, 1, 3];
    let e = validate_tet(t, &o).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "element 0 is inverted: signed rest volume {:e} < 0 (1 of 1 elements are inverted; the whole mesh has the opposite orientation: swap two vertices of every element)",
            -1.0 / 6.0
        )
    );

    let mut t = unit_tet();
    t.positions[3] = [0.3, 0.3, 1e-14];
    let e = validate_tet(t, &o).unwrap_err();
    assert!(
        matches!(
            e,
            E::DegenerateElement {
                element: 0,
                dimension: 3,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("rest volume"));

    // The tolerance is relative: a tiny but well-shaped mesh is fine.
    let mut m = square();
    for p in &mut m.positions {
        p[0] *= 1e-9;
        p[1] *= 1e-9;
    }
    assert!(validate_tri(m, true, &o).is_ok());
}

/// Every topological requirement switched on.
fn strict() -> ValidationOptions {
    ValidationOptions {
        require_manifold: true,
        require_oriented: true,
        require_single_component: true,
        ..Default::default()
    }
}

#[test]
fn non_manifold_edges_and_vertices_are_errors_when_required() {
    let strict = strict();
    // Three triangles on edge (0, 1).
    let fin = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -1.0, 0.0],
            [0.5, 0.0, 1.0],
        ],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    );
    let (e, s) = tri_err(fin.clone(), false, &strict);
    assert_eq!(
        e,
        E::NonManifoldEdge {
            edge: [0, 1],
            faces: vec![0, 1, 2]
        }
    );
    assert_eq!(
        s,
        "edge [0, 1] is non-manifold: it is shared by triangles [0, 1, 2]"
    );
    assert!(validate_tri(fin, false, &ValidationOptions::default()).is_ok());

    // Two triangles touching at vertex 0 only.
    let bowtie = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-1.0, -1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    let opts = ValidationOptions {
        require_manifold: true,
        ..Default::default()
    };
    let (e, s) = tri_err(bowtie, true, &opts);
    assert!(matches!(e, E::NonManifoldVertex { vertex: 0, .. }));
    assert_eq!(
        s,
        "vertex 0 is non-manifold: its 2 triangles form 2 separate fans (pinched vertex)"
    );
}

#[test]
fn orientation_and_component_errors() {
    let strict = strict();
    let mut m = square();
    m.positions[3][2] = 1.0;
    m.triangles[1] = [0, 3, 2];
    let (e, s) = tri_err(m, false, &strict);
    assert_eq!(
        e,
        E::InconsistentOrientation {
            edge: [2, 0],
            faces: [0, 1]
        }
    );
    assert_eq!(
        s,
        "triangles [0, 1] are inconsistently oriented: both traverse edge [2, 0] in the same direction"
    );

    let mut two = square();
    two.positions
        .extend([[3.0, 0.0, 0.0], [4.0, 0.0, 0.0], [3.0, 1.0, 0.0]]);
    two.triangles.push([4, 5, 6]);
    let (e, s) = tri_err(two.clone(), true, &strict);
    assert_eq!(e, E::MultipleComponents { count: 2 });
    assert_eq!(s, "the mesh has 2 connected components (one is required)");
    let v = validate_tri(two, true, &ValidationOptions::default()).unwrap();
    assert_eq!(
        v.warnings,
        vec!["the mesh has 2 connected components".to_string()]
    );
}

#[test]
fn non_manifold_tet_faces_are_errors_when_required() {
    let strict = strict();
    // Three tets on one face.
    let t = TetMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [0.2, 0.2, 2.0],
        ],
        vec![[0, 1, 2, 3], [0, 2, 1, 4], [0, 1, 2, 5]],
    );
    let e = validate_tet(t.clone(), &strict).unwrap_err();
    assert_eq!(
        e,
        E::NonManifoldFace {
            face: [0, 1, 2],
            tets: vec![0, 1, 2]
        }
    );
    assert_eq!(
        e.to_string(),
        "face [0, 1, 2] is non-manifold: it is shared by tets [0, 1, 2]"
    );
    assert!(validate_tet(t, &ValidationOptions::default()).is_ok());
}

fn square_with_strays() -> TriMesh {
    let mut m = square();
    m.positions.insert(0, [f64::NAN, 9.0, 9.0]); // unreferenced: not checked for finiteness
    m.positions.push([5.0, 5.0, 0.0]);
    m.uvs = Some((0..6).map(|i| [i as f64, 0.0]).collect());
    for t in &mut m.triangles {
        *t = t.map(|v| v + 1);
    }
    m
}

#[test]
fn unreferenced_vertices_are_refused_by_default() {
    let e = validate_tri(square_with_strays(), true, &ValidationOptions::default()).unwrap_err();
    assert_eq!(
        e,
        E::UnreferencedVertices {
            count: 2,
            first: vec![0, 5]
        }
    );
    assert_eq!(
        e.to_string(),
        "2 vertices are used by no element (ids 0, 5); remove them from the file or let them be dropped"
    );
    let mut t = unit_tet();
    t.positions.push([0.0, 0.0, 9.0]);
    let e = validate_tet(t, &ValidationOptions::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "1 vertex is used by no element (id 4); remove it from the file or let it be dropped"
    );
}

#[test]
fn unreferenced_vertices_are_dropped_with_a_map_on_request() {
    let opts = ValidationOptions {
        drop_unreferenced: true,
        ..Default::default()
    };
    let v = validate_tri(square_with_strays(), true, &opts).unwrap();
    assert_eq!(
        v.vertex_map,
        vec![None, Some(0), Some(1), Some(2), Some(3), None]
    );
    assert_eq!(v.mesh.triangles, square().triangles);
    assert_eq!(v.mesh.positions, square().positions);
    assert_eq!(v.mesh.uvs.unwrap()[0], [1.0, 0.0]);
    assert_eq!(
        v.warnings,
        vec![
            "dropped 2 unreferenced vertices (ids 0, 5); vertex_map gives old → new ids"
                .to_string()
        ]
    );
}

#[test]
fn real_surfaces_validate_as_manifold_single_components() {
    let strict = ValidationOptions {
        require_manifold: true,
        require_oriented: true,
        require_single_component: true,
        ..Default::default()
    };
    for name in [
        "hand_1_i_f5000.obj",
        "camelhead.off",
        "armadillo_cut_low.obj",
        "spot.obj",
        "bunny.off",
    ] {
        let m = read_tri_mesh(data(name)).unwrap();
        let v = validate_tri(m, false, &strict).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            v.warnings.iter().all(|w| w.starts_with("dropped")),
            "{name}: {:?}",
            v.warnings
        );
    }
}

#[test]
fn real_tet_meshes_validate() {
    let strict = ValidationOptions {
        require_manifold: true,
        require_single_component: true,
        ..Default::default()
    };
    for (name, v, t) in [
        ("hand.mesh", 7234, 29998),
        ("bar-2523.msh", 886, 2523),
        ("bar-2523.mesh", 886, 2523),
    ] {
        let m = read_tet_mesh(data(name)).unwrap();
        let out = validate_tet(m, &strict).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            (out.mesh.positions.len(), out.mesh.tets.len()),
            (v, t),
            "{name}"
        );
        assert!(out.warnings.is_empty(), "{name}: {:?}", out.warnings);
    }
}

/// The degeneracy tolerance `1e-12 · L^d` sits orders of magnitude below the
/// smallest genuine elements of the real data (see the `validate` docs).
#[test]
fn default_tolerance_leaves_a_wide_margin_on_real_data() {
    let camel = read_tri_mesh(data("camelhead.off")).unwrap();
    let l = camel.bbox_diagonal();
    let min_area = (0..camel.triangles.len())
        .map(|t| camel.area(t).unwrap())
        .fold(f64::INFINITY, f64::min);
    let rel = min_area / (l * l);
    eprintln!("camelhead: L = {l}, min area = {min_area:e}, relative {rel:e}");
    assert!(rel > 1e-9 && rel < 1e-5, "relative min area {rel:e}");

    let hand = read_tet_mesh(data("hand.mesh")).unwrap();
    let l = hand.bbox_diagonal();
    let min_vol = (0..hand.tets.len())
        .map(|t| hand.signed_volume(t).unwrap())
        .fold(f64::INFINITY, f64::min);
    let rel = min_vol / (l * l * l);
    eprintln!("hand.mesh: L = {l}, min volume = {min_vol:e}, relative {rel:e}");
    assert!(rel > 1e-11, "relative min volume {rel:e}");
}

/// The checks run side by side, but a mesh with several problems still
/// gets the first in the module docs' order (duplicate, then rest areas,
/// then manifoldness, then components), and the warnings come in that
/// order too (slivers, components, dropped vertices).
#[test]
fn several_problems_report_the_first_in_the_docs_order() {
    let strict = strict();
    let mut m = square();
    m.positions.extend([
        [0.5, 0.5, 1.0], // 4: a third triangle on edge (0, 2)
        [5.0, 0.0, 0.0], // 5–7: collinear, a second component
        [6.0, 0.0, 0.0],
        [7.0, 0.0, 0.0],
    ]);
    m.triangles.extend([[0, 2, 4], [5, 6, 7], [2, 0, 1]]);
    let (e, _) = tri_err(m.clone(), false, &strict);
    assert_eq!(
        e,
        E::DuplicateElement {
            element: 4,
            first: 0
        }
    );
    m.triangles.pop();
    let (e, _) = tri_err(m.clone(), false, &strict);
    assert!(matches!(e, E::DegenerateElement { .. }), "{e:?}");
    // a sliver (quality ≈ 1.4e-6 < 1e-5), no longer degenerate
    m.positions[7] = [7.0, 1e-5, 0.0];
    let (e, _) = tri_err(m.clone(), false, &strict);
    assert!(
        matches!(e, E::NonManifoldEdge { edge: [0, 2], .. }),
        "{e:?}"
    );
    m.triangles.remove(2);
    let (e, _) = tri_err(m.clone(), false, &strict);
    assert_eq!(e, E::MultipleComponents { count: 2 });
    // vertex 4 is no longer used: dropped, the last warning
    let opts = ValidationOptions {
        drop_unreferenced: true,
        ..Default::default()
    };
    let w = validate_tri(m, false, &opts).unwrap().warnings;
    assert_eq!(w.len(), 3, "{w:?}");
    assert!(w[0].contains("sliver"), "{w:?}");
    assert!(w[1].contains("components"), "{w:?}");
    assert!(w[2].contains("unreferenced"), "{w:?}");
}
