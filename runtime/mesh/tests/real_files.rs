//! The public meshes in the data folder read with the counts listed in
//! SOURCES.md, and the MEDIT and Gmsh copies of the bar are identical.

mod common;

use common::data;
use ecc_mesh::{AnyMesh, MeshError, read_mesh, read_tet_mesh, read_tri_mesh};

fn referenced(tris: &[[usize; 3]], n: usize) -> usize {
    let mut used = vec![false; n];
    for t in tris {
        for &v in t {
            used[v] = true;
        }
    }
    used.iter().filter(|&&u| u).count()
}

#[test]
fn surface_meshes_have_the_documented_counts() {
    for (name, v, f) in [
        ("hand_1_i_f5000.obj", 2517, 4999),
        ("camelhead.off", 11381, 22704),
        ("armadillo_cut_low.obj", 32121, 62382),
        ("spot.obj", 2930, 5856),
        ("bunny.off", 3485, 6966),
    ] {
        let m = read_tri_mesh(data(name)).unwrap();
        assert_eq!(m.triangles.len(), f, "{name}");
        assert_eq!(referenced(&m.triangles, m.positions.len()), v, "{name}");
        // spot.obj has seams in its texture atlas: no per-vertex uvs.
        assert!(m.uvs.is_none(), "{name}");
    }
}

#[test]
fn tet_meshes_have_the_documented_counts() {
    let hand = read_tet_mesh(data("hand.mesh")).unwrap();
    assert_eq!((hand.positions.len(), hand.tets.len()), (7234, 29998));
    let bar = read_tet_mesh(data("bar-2523.msh")).unwrap();
    assert_eq!((bar.positions.len(), bar.tets.len()), (886, 2523));
}

#[test]
fn bar_mesh_and_msh_are_bit_identical() {
    let a = read_tet_mesh(data("bar-2523.mesh")).unwrap();
    let b = read_tet_mesh(data("bar-2523.msh")).unwrap();
    assert_eq!(a.tets, b.tets);
    assert_eq!(a.positions.len(), b.positions.len());
    for (p, q) in a.positions.iter().zip(&b.positions) {
        for k in 0..3 {
            assert_eq!(p[k].to_bits(), q[k].to_bits());
        }
    }
}

#[test]
fn asking_for_the_wrong_kind_is_a_clear_error() {
    let err = read_tri_mesh(data("hand.mesh")).unwrap_err();
    assert!(matches!(err, MeshError::WrongKind { .. }));
    let msg = err.to_string();
    assert!(
        msg.contains("hand.mesh")
            && msg.contains("expected a triangle mesh but the file holds a tetrahedral mesh"),
        "{msg}"
    );
    let err = read_tet_mesh(data("bunny.off")).unwrap_err();
    assert!(
        err.to_string().contains("expected a tetrahedral mesh"),
        "{err}"
    );
    assert!(matches!(
        read_mesh(data("spot.obj")).unwrap(),
        AnyMesh::Tri(_)
    ));
}

#[test]
fn missing_files_and_unknown_extensions_are_errors() {
    let err = read_mesh("/definitely/not/here.obj").unwrap_err();
    assert!(matches!(err, MeshError::Io { .. }));
    assert!(
        err.to_string().starts_with("/definitely/not/here.obj: "),
        "{err}"
    );
    let err = read_mesh(data("SOURCES.md")).unwrap_err();
    assert!(
        err.to_string()
            .contains("unsupported mesh file extension \"md\""),
        "{err}"
    );
}
