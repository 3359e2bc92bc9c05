//! ecc-mesh: triangle and tetrahedral meshes for ecc.
//!
//! (Validation, generators and the Tutte embedding are being added; the
//! types in [`types`] and [`error`] are the stable contract.)

pub mod error;
pub mod generate;
pub mod geometry;
pub mod io;
pub mod topology;
pub mod tutte;
pub mod types;
pub mod validate;

pub use error::{MeshError, ParseError, TutteError, ValidationError};
pub use generate::{
    bar_tet, box_tet, box_tet_with_at_least, disk_tri, grid_tri, grid_tri_with_at_least,
};
pub use io::{
    MeshFormat, PointData, parse_gmsh, parse_medit, parse_mesh_bytes, parse_obj, parse_off,
    parse_vtk, read_mesh, read_tet_mesh, read_tri_mesh, write_obj, write_vtk_tet, write_vtk_tri,
};
pub use topology::{Components, boundary_loops, components, tet_boundary_faces};
pub use tutte::{TutteEmbedding, tutte_embedding, tutte_embedding_report};
pub use types::{AnyMesh, TetMesh, TriMesh, TutteWeights, Validated, ValidationOptions};
pub use validate::{validate_tet, validate_tri};
