//! The chunked, parallel writers (issue #11, item 6): awkward numbers read
//! back bit-identical, meshes larger than one formatting chunk (8192 lines)
//! keep every line once and in order, and the bytes do not depend on the
//! number of threads.

use std::fs;

use ecc_mesh::{TetMesh, TriMesh, box_tet, disk_tri, read_tet_mesh, read_tri_mesh};
use ecc_mesh::{write_obj, write_vtk_tet};

/// Values whose text form is easy to get wrong.
const AWKWARD: [f64; 22] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    2.0,
    1e15,
    9007199254740992.0, // 2^53
    0.1,
    0.1 + 0.2,
    1.0 / 3.0,
    -2.0 / 3.0,
    1e-5,
    1.5e-5,
    1e-7,
    1e16,
    1e-300,
    5e-324,
    -5e-324,
    1e300,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
];

/// Deterministic finite doubles from random bit patterns (splitmix64):
/// every exponent and mantissa, not just nice decimals.
fn random_finite(count: usize) -> Vec<f64> {
    let mut state = 0x243F_6A88_85A3_08D3_u64;
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        let x = f64::from_bits(z ^ (z >> 31));
        if x.is_finite() {
            out.push(x);
        }
    }
    out
}

fn bits<const N: usize>(p: &[[f64; N]]) -> Vec<[u64; N]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

/// A strip of `n` vertices whose coordinates and uvs are taken in turn
/// from `values`, with triangles `(i, i+1, i+2)`: every vertex is used, so
/// the uvs read back per vertex.
fn strip(values: &[f64], n: usize) -> TriMesh {
    let at = |k: usize| values[k % values.len()];
    TriMesh {
        positions: (0..n)
            .map(|i| [at(5 * i), at(5 * i + 1), at(5 * i + 2)])
            .collect(),
        triangles: (0..n - 2).map(|i| [i, i + 1, i + 2]).collect(),
        uvs: Some((0..n).map(|i| [at(5 * i + 3), at(5 * i + 4)]).collect()),
    }
}

#[test]
fn awkward_and_random_values_read_back_bit_identical() {
    let dir = tempfile::tempdir().unwrap();
    let mut values = AWKWARD.to_vec();
    values.extend(random_finite(20_000));
    let m = strip(&values, values.len() / 5 + 7);
    let path = dir.path().join("awkward.obj");
    write_obj(&path, &m).unwrap();
    let back = read_tri_mesh(&path).unwrap();
    assert_eq!(back.triangles, m.triangles);
    assert_eq!(bits(&back.positions), bits(&m.positions));
    assert_eq!(bits(&back.uvs.unwrap()), bits(m.uvs.as_ref().unwrap()));

    // the first lines, as OBJ readers elsewhere will see them
    let text = fs::read_to_string(&path).unwrap();
    let (nv, nf) = (m.positions.len(), m.triangles.len());
    let head: Vec<&str> = text.lines().take(5).collect();
    assert_eq!(
        head,
        [
            format!("# ecc-mesh: {nv} vertices, {nf} triangles").as_str(),
            "v 0.0 -0.0 1.0",
            "v 1000000000000000.0 9007199254740992.0 0.1",
            "v -0.6666666666666666 0.00001 0.000015",
            "v 1e-300 5e-324 -5e-324",
        ]
    );
    assert!(text.contains("\nvt 1e-7 1e+16\nvt 1e+300 1.7976931348623157e+308\n"));
    // 1-based indices with texture indices; the last face names the last vertex
    let (a, b) = (nv - 2, nv - 1);
    assert!(text.ends_with(&format!("\nf {a}/{a} {b}/{b} {nv}/{nv}\n")));
}

/// `disk_tri(90)`: 24,571 vertices and 48,600 triangles, so vertex, uv
/// and face lines each span several chunks.
fn big_disk() -> TriMesh {
    let mut m = disk_tri(90, 1.0);
    for (i, p) in m.positions.iter_mut().enumerate() {
        p[2] = (i as f64 * 0.37).sin() / 3.0;
    }
    m.uvs = Some(m.positions.iter().map(|p| [p[0] / 7.0, -p[1]]).collect());
    m
}

#[test]
fn obj_spanning_several_chunks_keeps_every_line_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let m = big_disk();
    let (nv, nf) = (m.positions.len(), m.triangles.len());
    assert!(nv > 2 * 8192 && nf > 5 * 8192, "{nv} {nf}");
    let path = dir.path().join("disk.obj");
    write_obj(&path, &m).unwrap();

    let text = fs::read_to_string(&path).unwrap();
    let count = |prefix: &str| text.lines().filter(|l| l.starts_with(prefix)).count();
    assert_eq!(text.lines().count(), 1 + 2 * nv + nf);
    assert_eq!((count("v "), count("vt "), count("f ")), (nv, nv, nf));
    let back = read_tri_mesh(&path).unwrap();
    assert_eq!(back.triangles, m.triangles);
    assert_eq!(bits(&back.positions), bits(&m.positions));
    assert_eq!(bits(&back.uvs.unwrap()), bits(m.uvs.as_ref().unwrap()));

    // without uvs: plain `f a b c` faces
    let plain = TriMesh { uvs: None, ..m };
    write_obj(&path, &plain).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().count(), 1 + nv + nf);
    assert!(!text.contains('/') && !text.contains("vt "));
    assert_eq!(read_tri_mesh(&path).unwrap().triangles, plain.triangles);
}

/// The `POINT_DATA` rows of a VTK file written by `write_vtk_*`: for each
/// array, its name and its values in file order.
fn point_data(text: &str) -> Vec<(String, Vec<f64>)> {
    let (_, data) = text
        .split_once("\nPOINT_DATA ")
        .expect("a POINT_DATA section");
    let mut lines = data.lines().skip(2); // the count, `FIELD FieldData k`
    let mut out = Vec::new();
    while let Some(header) = lines.next() {
        let h: Vec<&str> = header.split(' ').collect();
        let (comps, n): (usize, usize) = (h[1].parse().unwrap(), h[2].parse().unwrap());
        let mut values = Vec::new();
        for row in lines.by_ref().take(n) {
            let row: Vec<f64> = row.split(' ').map(|t| t.parse().unwrap()).collect();
            assert_eq!(row.len(), comps, "{header}");
            values.extend(row);
        }
        out.push((h[0].to_string(), values));
    }
    out
}

#[test]
fn vtk_spanning_several_chunks_keeps_cells_and_point_data() {
    let dir = tempfile::tempdir().unwrap();
    // 9,261 vertices (two chunks), 48,000 tets (six chunks)
    let mut tets: TetMesh = box_tet(20, 20, 20, [1.0, 0.3, 1.0 / 3.0]);
    let n = tets.positions.len();
    tets.positions[17] = [AWKWARD[16], AWKWARD[17], AWKWARD[19]];
    let mut scalar = random_finite(n);
    scalar[..AWKWARD.len()].copy_from_slice(&AWKWARD);
    let vector = random_finite(3 * n);
    let path = dir.path().join("box.vtk");
    write_vtk_tet(&path, &tets, &[("s", &scalar, 1), ("v", &vector, 3)]).unwrap();

    let back = read_tet_mesh(&path).unwrap();
    assert_eq!(back.tets, tets.tets);
    assert_eq!(bits(&back.positions), bits(&tets.positions));
    let text = fs::read_to_string(&path).unwrap();
    let nt = tets.tets.len();
    let types = text.split_once("\nCELL_TYPES ").unwrap().1;
    let types: Vec<&str> = types.lines().skip(1).take_while(|l| *l == "10").collect();
    assert_eq!(types.len(), nt);
    let data = point_data(&text);
    let names: Vec<&str> = data.iter().map(|(name, _)| name.as_str()).collect();
    assert_eq!(names, ["s", "v"]);
    let to_bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(to_bits(&data[0].1), to_bits(&scalar));
    assert_eq!(to_bits(&data[1].1), to_bits(&vector));
}

#[test]
fn bytes_do_not_depend_on_the_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let m = big_disk();
    let write_with = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let path = dir.path().join(format!("t{threads}.obj"));
        pool.install(|| write_obj(&path, &m)).unwrap();
        fs::read(&path).unwrap()
    };
    let one = write_with(1);
    assert_eq!(write_with(3), one);
    assert_eq!(
        fs::read_dir(dir.path()).unwrap().count(),
        2,
        "no temporary left"
    );
}
