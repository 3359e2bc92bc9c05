//! No parser panics: truncations and byte mutations of valid inputs (small
//! hand-written files and the heads of the real files), fed to every
//! parser. A deterministic stand-in for the cargo-fuzz targets.

mod common;

use common::data;
use ecc_mesh::{MeshFormat, parse_mesh_bytes};

const FORMATS: [MeshFormat; 5] = [
    MeshFormat::Obj,
    MeshFormat::Off,
    MeshFormat::Medit,
    MeshFormat::Gmsh,
    MeshFormat::Vtk,
];

const SMALL: &[&str] = &[
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1/1 2/2/1 -1/-1/1\n",
    "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nEdges 1\n1 2 0\nTriangles\n1\n1 3 2 5\nTetrahedra\n1\n1 2 3 4 0\nEnd\n",
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n",
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n2\n1 15 2 0 1 1\n3 2 2 1 1 1 2 3\n$EndElements\n",
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0\n0 1 0 0 0 1\nCELLS 2 7\n4 0 1 2 3\n1 0\nCELL_TYPES 2\n10\n1\n",
    "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\nMETADATA\nINFORMATION 0\n\nCELLS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2\nCELL_TYPES 1\n5\n",
];

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) as usize
    }
}

fn parse_everywhere(bytes: &[u8]) {
    for f in FORMATS {
        let _ = parse_mesh_bytes(f, bytes);
    }
}

fn corpus() -> Vec<Vec<u8>> {
    let mut c: Vec<Vec<u8>> = SMALL.iter().map(|s| s.as_bytes().to_vec()).collect();
    for name in [
        "hand_1_i_f5000.obj",
        "camelhead.off",
        "hand.mesh",
        "bar-2523.msh",
        "bar-2523.mesh",
    ] {
        let bytes = std::fs::read(data(name)).unwrap();
        c.push(bytes[..bytes.len().min(3000)].to_vec());
    }
    c
}

#[test]
fn every_truncation_is_handled() {
    for sample in corpus() {
        for cut in 0..=sample.len() {
            parse_everywhere(&sample[..cut]);
        }
    }
}

#[test]
fn byte_mutations_are_handled() {
    let alphabet = b"0123456789-+. \n\t$#/eE9xOFF\xff\x00";
    let mut rng = Lcg(7);
    for sample in corpus() {
        for _ in 0..150 {
            let mut m = sample.clone();
            for _ in 0..1 + rng.next() % 4 {
                let i = rng.next() % m.len();
                match rng.next() % 3 {
                    0 => m[i] = alphabet[rng.next() % alphabet.len()],
                    1 => {
                        m.remove(i);
                    }
                    _ => m.insert(i, alphabet[rng.next() % alphabet.len()]),
                }
            }
            parse_everywhere(&m);
        }
    }
}

#[test]
fn pathological_counts_and_indices_are_errors() {
    let cases: &[(MeshFormat, &str)] = &[
        (
            MeshFormat::Off,
            "OFF\n18446744073709551615 18446744073709551615 0\n",
        ),
        (MeshFormat::Obj, "v 1 2 3\nf 1 1 -9223372036854775808\n"),
        (MeshFormat::Obj, "v 1 2 3\nf 18446744073709551615 1 1\n"),
        (
            MeshFormat::Medit,
            "MeshVersionFormatted 1\nDimension 3\nVertices 1\n0 0 0 0\nTetrahedra 1\n18446744073709551615 1 1 1 0\n",
        ),
        (
            MeshFormat::Gmsh,
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n18446744073709551615 1 1 1\n",
        ),
        (
            MeshFormat::Gmsh,
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n0 1 18446744073709551615 1\n",
        ),
        (
            MeshFormat::Vtk,
            "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 0 float\nCELLS 1 18446744073709551615\n18446744073709551615\n",
        ),
        (
            MeshFormat::Vtk,
            "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nFIELD f 1\na 18446744073709551615 18446744073709551615 double\n",
        ),
    ];
    for (f, text) in cases {
        assert!(
            parse_mesh_bytes(*f, text.as_bytes()).is_err(),
            "{f:?}: {text:?}"
        );
    }
}
