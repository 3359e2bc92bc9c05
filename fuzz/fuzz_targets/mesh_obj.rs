//! Fuzz the Obj reader (`ecc_mesh::parse_mesh_bytes(MeshFormat::Obj, …)`)
//! and everything a scene does with a parsed mesh (see `mesh_common.rs`).
#![no_main]

mod mesh_common;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    mesh_common::run(ecc_mesh::MeshFormat::Obj, data);
});
