//! Property tests (proptest) of the readers, writers and validation over
//! random meshes:
//!
//! * any finite coordinates (subnormals, ±0, 1e±300 included) and any
//!   in-range element list round-trip bit-exactly through the OBJ and VTK
//!   writers and the readers;
//! * an out-of-range index put on any face line of a written OBJ / OFF is
//!   reported on exactly that line, naming the index;
//! * a non-finite coordinate anywhere is reported on its line (readers) or
//!   with its vertex id (validation), never accepted;
//! * validation of a random perturbed grid names the first degenerate or
//!   inverted element by its id.
//!
//! Failures are shrunk and saved next to this file
//! (`prop_mesh.proptest-regressions`, committed, replayed first).

use ecc_mesh::{
    AnyMesh, MeshFormat, TetMesh, TriMesh, ValidationError, ValidationOptions, grid_tri,
    parse_mesh_bytes, read_mesh, validate_tri, write_obj, write_vtk_tet, write_vtk_tri,
};
use proptest::prelude::*;

/// Any finite f64, with the awkward ones over-represented.
fn coord() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0f64..10.0,
        1 => prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        1 => prop::sample::select(&[0.0, -0.0, 1e-300, -1e300, f64::MAX, f64::MIN_POSITIVE, 0.1][..]),
    ]
}

fn positions(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<[f64; 3]>> {
    prop::collection::vec([coord(), coord(), coord()], n)
}

/// A triangle mesh with random coordinates and random in-range indices.
fn tri_mesh() -> impl Strategy<Value = TriMesh> {
    positions(3..20).prop_flat_map(|p| {
        let n = p.len();
        prop::collection::vec([0..n, 0..n, 0..n], 1..30).prop_map(move |t| TriMesh {
            positions: p.clone(),
            triangles: t,
            uvs: None,
        })
    })
}

fn tet_mesh() -> impl Strategy<Value = TetMesh> {
    positions(4..20).prop_flat_map(|p| {
        let n = p.len();
        prop::collection::vec([0..n, 0..n, 0..n, 0..n], 1..20).prop_map(move |t| TetMesh {
            positions: p.clone(),
            tets: t,
        })
    })
}

fn bits(p: &[[f64; 3]]) -> Vec<[u64; 3]> {
    p.iter().map(|x| x.map(f64::to_bits)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn triangle_meshes_round_trip_bit_exactly(m in tri_mesh()) {
        let dir = tempfile::tempdir().unwrap();
        for name in ["m.obj", "m.vtk"] {
            let path = dir.path().join(name);
            if name.ends_with("obj") {
                write_obj(&path, &m).unwrap();
            } else {
                write_vtk_tri(&path, &m, &[]).unwrap();
            }
            let back = match read_mesh(&path) {
                Ok(AnyMesh::Tri(t)) => t,
                other => return Err(TestCaseError::fail(format!("{name}: {other:?}"))),
            };
            prop_assert_eq!(bits(&back.positions), bits(&m.positions), "{}", name);
            prop_assert_eq!(&back.triangles, &m.triangles, "{}", name);
        }
    }

    #[test]
    fn tet_meshes_round_trip_bit_exactly(m in tet_mesh()) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.vtk");
        write_vtk_tet(&path, &m, &[]).unwrap();
        let back = match read_mesh(&path) {
            Ok(AnyMesh::Tet(t)) => t,
            other => return Err(TestCaseError::fail(format!("{other:?}"))),
        };
        prop_assert_eq!(bits(&back.positions), bits(&m.positions));
        prop_assert_eq!(&back.tets, &m.tets);
    }

    #[test]
    fn an_out_of_range_index_is_reported_on_its_line(
        nx in 1usize..5, ny in 1usize..5, pick in any::<prop::sample::Index>(), extra in 1usize..1000,
        off in any::<bool>(),
    ) {
        let m = grid_tri(nx, ny, 1.0, 1.0);
        let n = m.positions.len();
        let face = pick.index(m.triangles.len());
        let bad = n + extra; // 0-based in OFF, 1-based n + extra is past the end in OBJ too
        let mut lines: Vec<String> = Vec::new();
        let face_line;
        if off {
            lines.push("OFF".into());
            lines.push(format!("{n} {} 0", m.triangles.len()));
            lines.extend(m.positions.iter().map(|p| format!("{} {} {}", p[0], p[1], p[2])));
            face_line = lines.len() + face + 1;
            lines.extend(m.triangles.iter().enumerate().map(|(k, t)| {
                let c = if k == face { bad } else { t[2] };
                format!("3 {} {} {c}", t[0], t[1])
            }));
        } else {
            lines.extend(m.positions.iter().map(|p| format!("v {} {} {}", p[0], p[1], p[2])));
            face_line = lines.len() + face + 1;
            lines.extend(m.triangles.iter().enumerate().map(|(k, t)| {
                let c = if k == face { bad } else { t[2] + 1 };
                format!("f {} {} {c}", t[0] + 1, t[1] + 1)
            }));
        }
        let text = lines.join("\n") + "\n";
        let format = if off { MeshFormat::Off } else { MeshFormat::Obj };
        let e = parse_mesh_bytes(format, text.as_bytes()).expect_err("index out of range");
        let msg = e.to_string();
        prop_assert!(msg.starts_with(&format!("line {face_line}:")), "{msg}");
        prop_assert!(msg.contains(&bad.to_string()), "{msg}");
    }

    #[test]
    fn a_non_finite_coordinate_is_never_accepted(
        nx in 1usize..4, pick in any::<prop::sample::Index>(), c in 0usize..3,
        bad in prop::sample::select(&["nan", "NaN", "inf", "-inf", "1e999", "-1e400"][..]),
    ) {
        let m = grid_tri(nx, nx, 1.0, 1.0);
        let v = pick.index(m.positions.len());
        let mut text = String::new();
        for (k, p) in m.positions.iter().enumerate() {
            let mut s: Vec<String> = p.iter().map(|x| x.to_string()).collect();
            if k == v {
                s[c] = bad.to_string();
            }
            text += &format!("v {}\n", s.join(" "));
        }
        for t in &m.triangles {
            text += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        let e = parse_mesh_bytes(MeshFormat::Obj, text.as_bytes()).expect_err("not finite");
        let msg = e.to_string();
        prop_assert!(msg.starts_with(&format!("line {}:", v + 1)), "{msg}");
        prop_assert!(msg.contains("not finite"), "{msg}");
        // the same coordinate given to validation directly
        let mut mesh = m.clone();
        mesh.positions[v][c] = f64::NAN;
        let e = validate_tri(mesh, false, &ValidationOptions::default()).expect_err("NaN");
        prop_assert!(
            matches!(e, ValidationError::NonFiniteCoordinate { vertex, .. } if vertex == v),
            "{e}"
        );
    }

    #[test]
    fn validation_names_the_first_bad_element(
        nx in 2usize..6, pick in any::<prop::sample::Index>(), flip in any::<bool>(),
    ) {
        let mut m = grid_tri(nx, nx, 1.0, 1.0);
        let e = pick.index(m.triangles.len());
        if flip {
            m.triangles[e].swap(1, 2);
        } else {
            let t = m.triangles[e];
            m.triangles[e] = [t[0], t[1], t[1]];
        }
        let err = validate_tri(m, true, &ValidationOptions::default()).expect_err("bad element");
        let ok = match &err {
            ValidationError::InvertedElement { element, count, .. } => flip && *element == e && *count == 1,
            ValidationError::DegenerateElement { element, .. } => !flip && *element == e,
            ValidationError::RepeatedVertexInElement { element, .. } => !flip && *element == e,
            _ => false,
        };
        prop_assert!(ok, "element {e}, flip {flip}: {err}");
        prop_assert!(err.to_string().contains(&format!("element {e}")), "{err}");
    }
}
