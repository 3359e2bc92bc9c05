//! Writers: round trips are bit-exact, bad data is refused before anything
//! is written, and failed writes leave no partial file.

mod common;

use std::fs;

use common::data;
use ecc_mesh::{
    AnyMesh, MeshError, PointData, TriMesh, TutteWeights, ValidationError, box_tet, disk_tri,
    parse_vtk, read_mesh, read_tet_mesh, read_tri_mesh, tutte_embedding, write_obj, write_vtk_tet,
    write_vtk_tri,
};

fn bits(p: &[[f64; 3]]) -> Vec<[u64; 3]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

#[test]
fn obj_round_trip_with_tutte_uvs_is_bit_exact() {
    let dir = tempfile::tempdir().unwrap();
    let mut m = read_tri_mesh(data("hand_1_i_f5000.obj")).unwrap();
    // hand has no unreferenced vertices, so the map is per vertex.
    m.uvs = Some(tutte_embedding(&m, TutteWeights::MeanValue).unwrap());
    let path = dir.path().join("hand_param.obj");
    write_obj(&path, &m).unwrap();
    let back = read_tri_mesh(&path).unwrap();
    assert_eq!(back.triangles, m.triangles);
    assert_eq!(bits(&back.positions), bits(&m.positions));
    let (a, b) = (back.uvs.unwrap(), m.uvs.unwrap());
    assert!(
        a.iter()
            .zip(&b)
            .all(|(p, q)| p[0].to_bits() == q[0].to_bits() && p[1].to_bits() == q[1].to_bits())
    );

    // Without uvs, plain `f a b c`; awkward magnitudes survive.
    let mut m = disk_tri(2, 1.0);
    m.positions[0] = [1e-300, -0.0, 0.1 + 0.2];
    m.positions[1][0] = 5e-324;
    let path = dir.path().join("disk.obj");
    write_obj(&path, &m).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.contains("\nf 1 2 3\n"), "{text}");
    let back = read_tri_mesh(&path).unwrap();
    assert_eq!(bits(&back.positions), bits(&m.positions));
    assert!(back.uvs.is_none());
}

#[test]
fn vtk_round_trips_keep_meshes_and_write_point_data() {
    let dir = tempfile::tempdir().unwrap();
    let tets = read_tet_mesh(data("bar-2523.msh")).unwrap();
    let n = tets.positions.len();
    let scalar: Vec<f64> = (0..n).map(|i| i as f64 * 0.1).collect();
    let disp: Vec<f64> = tets
        .positions
        .iter()
        .flat_map(|p| [p[0], -p[1], 1e-20 * p[2]])
        .collect();
    let path = dir.path().join("bar.vtk");
    write_vtk_tet(
        &path,
        &tets,
        &[("heat", &scalar, 1), ("displacement", &disp, 3)],
    )
    .unwrap();
    let back = read_tet_mesh(&path).unwrap();
    assert_eq!(back.tets, tets.tets);
    assert_eq!(bits(&back.positions), bits(&tets.positions));
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.contains(&format!(
        "POINT_DATA {n}\nFIELD FieldData 2\nheat 1 {n} double\n0.0\n0.1\n"
    )));
    assert!(text.contains(&format!("displacement 3 {n} double\n")));

    let tris = disk_tri(3, 1.0);
    let path = dir.path().join("disk.vtk");
    write_vtk_tri(&path, &tris, &[]).unwrap();
    match read_mesh(&path).unwrap() {
        AnyMesh::Tri(m) => {
            assert_eq!(m.triangles, tris.triangles);
            assert_eq!(bits(&m.positions), bits(&tris.positions));
        }
        other => panic!("expected triangles, got {}", other.kind()),
    }
    // What we write, the fuzz-facing parser reads.
    assert!(parse_vtk(&fs::read_to_string(&path).unwrap()).is_ok());
}

#[test]
fn bad_data_is_refused_before_writing() {
    let dir = tempfile::tempdir().unwrap();
    let tets = box_tet(1, 1, 1, [1.0; 3]);
    let n = tets.positions.len();
    let ok = vec![0.0; n];
    let path = dir.path().join("x.vtk");
    let cases: Vec<(Vec<PointData<'_>>, &str)> = vec![
        (
            vec![("a", &ok[..n - 1], 1)],
            "point data \"a\" has 7 values, expected 8 vertices × 1 components",
        ),
        (vec![("a", &ok, 0)], "expected 8 vertices × 0 components"),
        (
            vec![("two words", &ok, 1)],
            "must be non-empty without spaces",
        ),
        (vec![("", &ok, 1)], "must be non-empty without spaces"),
        (
            vec![("a", &ok, 1), ("a", &ok, 1)],
            "point-data name \"a\" is used twice",
        ),
    ];
    for (pd, want) in &cases {
        let e = write_vtk_tet(&path, &tets, pd).unwrap_err();
        assert!(matches!(e, MeshError::Data { .. }));
        assert!(e.to_string().contains(want), "{e}");
    }
    let mut nan = ok.clone();
    nan[5] = f64::NAN;
    let e = write_vtk_tet(&path, &tets, &[("p", &nan, 1)]).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("point data \"p\" has a non-finite value NaN at vertex 5 component 0"),
        "{e}"
    );

    let mut bad = tets.clone();
    bad.tets[2][1] = 99;
    let e = write_vtk_tet(&path, &bad, &[]).unwrap_err();
    assert!(matches!(
        e,
        MeshError::Invalid(ValidationError::IndexOutOfRange {
            element: 2,
            index: 99,
            ..
        })
    ));
    assert_eq!(
        e.to_string(),
        "invalid mesh: element 2 refers to vertex 99, but there are only 8 vertices (valid ids 0..8)"
    );

    let mut m = disk_tri(1, 1.0);
    m.uvs = Some(vec![[0.0, 0.0]; 2]);
    let e = write_obj(dir.path().join("x.obj"), &m).unwrap_err();
    assert!(matches!(
        e,
        MeshError::Invalid(ValidationError::UvCountMismatch {
            uvs: 2,
            vertices: 7
        })
    ));
    m.uvs = Some(vec![[0.0, f64::NAN]; 7]);
    assert!(matches!(
        write_obj(dir.path().join("x.obj"), &m).unwrap_err(),
        MeshError::Invalid(ValidationError::NonFiniteUv { vertex: 0, .. })
    ));
    let mut m = disk_tri(1, 1.0);
    m.positions[3][2] = f64::INFINITY;
    assert!(matches!(
        write_vtk_tri(&path, &m, &[]).unwrap_err(),
        MeshError::Invalid(ValidationError::NonFiniteCoordinate { vertex: 3, .. })
    ));
    assert_eq!(
        fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing may be written"
    );
}

#[test]
fn failed_writes_leave_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let m = disk_tri(2, 1.0);
    let missing = dir.path().join("missing").join("out.obj");
    let e = write_obj(&missing, &m).unwrap_err();
    assert!(matches!(e, MeshError::Io { .. }));
    assert!(
        e.to_string().starts_with(&missing.display().to_string()),
        "{e}"
    );
    assert!(!dir.path().join("missing").exists());

    // A read-only folder (skipped when running as root, who may write anyway).
    let ro = dir.path().join("ro");
    fs::create_dir(&ro).unwrap();
    let mut perm = fs::metadata(&ro).unwrap().permissions();
    perm.set_readonly(true);
    fs::set_permissions(&ro, perm.clone()).unwrap();
    let probe = fs::File::create(ro.join("probe"));
    if probe.is_err() {
        let e = write_vtk_tri(ro.join("out.vtk"), &m, &[]).unwrap_err();
        assert!(matches!(e, MeshError::Io { .. }), "{e}");
        assert_eq!(fs::read_dir(&ro).unwrap().count(), 0);
    } else {
        eprintln!("running with privileges that ignore read-only folders: read-only case skipped");
        fs::remove_file(ro.join("probe")).unwrap();
    }
    #[allow(clippy::permissions_set_readonly_false)]
    perm.set_readonly(false);
    fs::set_permissions(&ro, perm).unwrap();

    // A failure after the data was written (the final rename onto an
    // existing non-empty folder) removes the temporary file.
    let target = dir.path().join("taken.obj");
    fs::create_dir(&target).unwrap();
    fs::write(target.join("keep"), "x").unwrap();
    let e = write_obj(&target, &m).unwrap_err();
    assert!(matches!(e, MeshError::Io { .. }), "{e}");
    let names: Vec<_> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        names.len(),
        2,
        "only `ro` and `taken.obj` remain: {names:?}"
    );
    fs::remove_dir_all(&target).unwrap();

    // Writing over an existing file replaces it completely.
    let path = dir.path().join("mesh.obj");
    fs::write(
        &path,
        "old content that is longer than nothing\n".repeat(1000),
    )
    .unwrap();
    write_obj(
        &path,
        &TriMesh::new(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        ),
    )
    .unwrap();
    assert_eq!(read_tri_mesh(&path).unwrap().triangles, vec![[0, 1, 2]]);
    let names: Vec<_> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "no temporary files left: {names:?}");
}
