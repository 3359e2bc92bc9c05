//! What every mesh fuzz target does with its input: parse it (the pure
//! parser, no file system), and if that succeeds, validate it with every
//! check switched on and run the topology helpers and — for small disk-like
//! triangle meshes — the Tutte embedding. Any panic is a bug; errors are
//! the expected outcome for almost every input.

use ecc_mesh::{
    AnyMesh, MeshFormat, TutteWeights, ValidationOptions, boundary_loops, components,
    parse_mesh_bytes, tet_boundary_faces, tutte_embedding_report, validate_tet, validate_tri,
};

pub fn run(format: MeshFormat, data: &[u8]) {
    let Ok(mesh) = parse_mesh_bytes(format, data) else {
        return;
    };
    // The error text is what users see: rendering it must not panic either.
    let strict = ValidationOptions {
        require_manifold: true,
        require_oriented: true,
        require_single_component: true,
        drop_unreferenced: true,
        ..Default::default()
    };
    match mesh {
        AnyMesh::Tri(m) => {
            let _ = components(&m.triangles);
            let _ = boundary_loops(&m.triangles).map_err(|e| e.to_string());
            let _ = validate_tri(m.clone(), true, &ValidationOptions::default())
                .map_err(|e| e.to_string());
            if let Ok(v) = validate_tri(m, false, &strict)
                && v.mesh.positions.len() <= 300
            {
                let _ = tutte_embedding_report(&v.mesh, TutteWeights::MeanValue)
                    .map_err(|e| e.to_string());
            }
        }
        AnyMesh::Tet(m) => {
            let _ = components(&m.tets);
            let _ = tet_boundary_faces(&m.tets);
            let _ =
                validate_tet(m.clone(), &ValidationOptions::default()).map_err(|e| e.to_string());
            let _ = validate_tet(m, &strict).map_err(|e| e.to_string());
        }
    }
}
