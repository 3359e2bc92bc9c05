//! ecc-mesh: triangle and tetrahedral meshes for ecc — readers, writers,
//! validation, generators and the Tutte embedding.
//!
//! # Meshes
//! * [`TriMesh`]: triangles in the plane (`z = 0`, counter-clockwise for
//!   positive area) or a triangle surface in 3D; optional per-vertex `uvs`.
//!   Each surface triangle has an isometric 2D rest frame
//!   ([`TriMesh::rest_frame`], [`geometry::triangle_rest_frame`]) for
//!   parameterisation.
//! * [`TetMesh`]: tets `[a, b, c, d]`, positive when
//!   `((b − a) × (c − a)) · (d − a) > 0`.
//! * [`AnyMesh`]: either, as read from a file.
//!
//! # Reading
//! [`read_mesh`] picks the format by extension; [`read_tri_mesh`] /
//! [`read_tet_mesh`] also insist on the kind ([`MeshError::WrongKind`]).
//!
//! | ext | format | elements |
//! |---|---|---|
//! | `.obj` | Wavefront OBJ ([`io::obj`]) | triangles, `vt` → per-vertex uvs when seamless |
//! | `.off` | OFF ([`io::off`]) | triangles |
//! | `.mesh` | MEDIT ASCII ([`io::medit`]) | triangles or tets |
//! | `.msh` | Gmsh ASCII 2.x / 4.0 / 4.1 ([`io::gmsh`]) | triangles or tets |
//! | `.vtk` | legacy VTK unstructured grid, ASCII ([`io::vtk`]) | triangles or tets |
//!
//! Readers never panic. Each is a pure `parse_xxx(&str)` (or
//! [`parse_mesh_bytes`] for raw bytes, the fuzzing entry point) returning a
//! [`ParseError`] with the 1-based line and what was expected: truncated
//! files, wrong counts, non-numeric or non-finite numbers, 0-based/1-based
//! index confusion, out-of-range indices, unsupported element types
//! (quads, hexes, second-order elements, polygons: nothing is silently
//! split or dropped), binary variants and empty files. Files holding both
//! tets and triangles give the tets (the triangles are boundary faces);
//! points and lines are ignored. Reading does not validate.
//!
//! # Writing
//! [`write_obj`] (with `vt` and `f a/a b/b c/c` when uvs are present) and
//! [`write_vtk_tri`] / [`write_vtk_tet`] (legacy ASCII, with named
//! point-data arrays). Input is checked first (indices, finiteness, data
//! lengths and names); output is atomic: a temporary file in the same
//! folder is written, synced and renamed over the destination, and removed
//! on failure. Floats use Rust's shortest round-trip form, so a round trip
//! is bit-exact.
//!
//! # Validation
//! [`validate_tri`] / [`validate_tet`] return the first problem as a
//! [`ValidationError`] naming the element / vertex ids, or a
//! [`Validated`] mesh and warnings. Vertices no element uses are an error
//! unless [`ValidationOptions::drop_unreferenced`] asks to drop them
//! ([`Validated::vertex_map`] old → new). Degeneracy is
//! relative: `|measure| ≤ tol · L^d` with `L` the bounding-box diagonal
//! (default `tol = 1e-12`; see [`validate`] for why this keeps camelhead's
//! tiny folded faces and hand.mesh's slivers). Manifoldness, orientation
//! and a single component are opt-in ([`ValidationOptions`]).
//!
//! ```
//! use ecc_mesh::{ValidationOptions, disk_tri, validate_tri};
//! let opts = ValidationOptions { require_manifold: true, ..Default::default() };
//! let v = validate_tri(disk_tri(4, 1.0), true, &opts).unwrap();
//! assert_eq!(v.mesh.triangles.len(), 96);
//! ```
//!
//! # Topology
//! [`boundary_loops`], [`tet_boundary_faces`] (outward), [`components`].
//!
//! # Generators
//! [`grid_tri`] (`[0, w] × [0, h]`), [`disk_tri`] (centred), [`box_tet`]
//! (`[0, size]`), [`bar_tet`] (`[-2, 2] × [-0.5, 0.5]²`), and the
//! benchmark sizes [`grid_tri_with_at_least`] (e.g. `1_000_000` →
//! 1,002,528 triangles) and [`box_tet_with_at_least`] (`300_000` → 303,918
//! tets). All are valid, positively oriented and fully referenced. Sizes
//! are trusted: callers taking them from users should bound them.
//!
//! # Tutte embedding
//! [`tutte_embedding`] maps a disk-topology mesh into the unit disk
//! (boundary on the circle by arc length, interior by uniform, mean-value
//! or cotangent weights; faer sparse Cholesky / LU), oriented so that a
//! consistently oriented mesh gets positive uv areas. It fails with
//! [`TutteError::Flipped`] (carrying the map) if any triangle folds;
//! [`tutte_embedding_report`] lists the flipped triangles instead. Uniform
//! and mean-value weights are bijective (Floater); cotangent weights may
//! fold (10 of 62,382 triangles on armadillo_cut_low).
//!
//! ```
//! use ecc_mesh::{TutteWeights, disk_tri, tutte_embedding};
//! let uv = tutte_embedding(&disk_tri(3, 2.0), TutteWeights::MeanValue).unwrap();
//! assert!(uv.iter().all(|p| p[0].hypot(p[1]) <= 1.0 + 1e-12));
//! ```

pub mod data;
pub mod dissection;
pub mod error;
pub mod fibre;
pub mod generate;
pub mod geometry;
pub mod io;
pub mod topology;
pub mod tutte;
pub mod types;
pub mod validate;

pub use data::{data_dir, data_file};
pub use error::{MeshError, ParseError, TutteError, ValidationError};
pub use fibre::{
    FibreError, FibreGenerator, centroids, check_directions, from_references, read_vtk_fibres,
};
pub use generate::{
    bar_tet, box_tet, box_tet_with_at_least, disk_tri, disk_with_ear, grid_tri,
    grid_tri_with_at_least,
};
pub use io::{
    MeshFormat, PointData, parse_gmsh, parse_medit, parse_mesh_bytes, parse_obj, parse_off,
    parse_vtk, read_mesh, read_tet_mesh, read_tri_mesh, write_obj, write_vtk_tet, write_vtk_tri,
};
pub use topology::{Components, boundary_loops, components, tet_boundary_faces};
pub use tutte::{
    TutteEmbedding, tutte_embedding, tutte_embedding_in_order, tutte_embedding_report,
};
pub use types::{
    AnyMesh, DEGENERATE_REL_TOL, TetMesh, TriMesh, TutteWeights, Validated, ValidationOptions,
};
pub use validate::{validate_tet, validate_tri};
