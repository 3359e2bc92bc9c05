//! Replays the committed cargo-fuzz corpora of the mesh readers
//! (`fuzz/corpus/mesh_*`, minimised: every input in them reached new code
//! during fuzzing) and the seeds, through exactly the code the fuzz targets
//! run (`fuzz/fuzz_targets/mesh_common.rs`: parse, then validate with every
//! check on, topology helpers and a Tutte embedding of small disks). Any
//! panic fails the test; this is the CI-cheap part of the fuzzing (no
//! libFuzzer, no nightly flags). See `fuzz/README.md`.

#[path = "../../../fuzz/fuzz_targets/mesh_common.rs"]
mod mesh_common;

use std::path::PathBuf;

use ecc_mesh::MeshFormat;

fn inputs(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fuzz"));
    let mut out = Vec::new();
    for dir in ["corpus", "seeds"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir).join(target)) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_file() {
                out.push((p.clone(), std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

fn replay(target: &str, format: MeshFormat) {
    let all = inputs(target);
    assert!(all.len() >= 3, "{target}: only {} inputs found", all.len());
    for (path, bytes) in &all {
        let r = std::panic::catch_unwind(|| mesh_common::run(format, bytes));
        assert!(r.is_ok(), "{target}: {} panics", path.display());
    }
    println!("{target}: {} inputs replayed", all.len());
}

#[test]
fn obj_corpus() {
    replay("mesh_obj", MeshFormat::Obj);
}

#[test]
fn off_corpus() {
    replay("mesh_off", MeshFormat::Off);
}

#[test]
fn medit_corpus() {
    replay("mesh_medit", MeshFormat::Medit);
}

#[test]
fn gmsh_corpus() {
    replay("mesh_gmsh", MeshFormat::Gmsh);
}

#[test]
fn vtk_corpus() {
    replay("mesh_vtk", MeshFormat::Vtk);
}
