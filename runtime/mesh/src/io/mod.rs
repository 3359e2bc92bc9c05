//! Mesh file input and output.
//!
//! Every reader is split into a pure parser over text (`parse_obj`,
//! `parse_off`, `parse_medit`, `parse_gmsh`, `parse_vtk`, or
//! [`parse_mesh_bytes`] for raw bytes) that never panics, and a thin file
//! wrapper that attaches the path to errors. Parsers check counts, numbers
//! (finite), index bases and ranges, and element types, and report the
//! 1-based line of the problem.

mod atomic;
pub mod fibres;
pub mod gmsh;
pub mod medit;
pub mod obj;
pub mod off;
mod text;
pub mod vtk;
mod write;

use std::path::Path;

pub use fibres::{DEFAULT_FIBRE_NAMES, parse_medit_references, parse_vtk_cell_vectors};
pub use gmsh::parse_gmsh;
pub use medit::parse_medit;
pub use obj::parse_obj;
pub use off::parse_off;
pub use vtk::parse_vtk;
pub use write::{PointData, write_obj, write_vtk_tet, write_vtk_tri};

use crate::error::{MeshError, ParseError};
use crate::types::{AnyMesh, TetMesh, TriMesh};

/// The file formats we read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshFormat {
    /// Wavefront `.obj` (triangles).
    Obj,
    /// `.off` (triangles).
    Off,
    /// MEDIT `.mesh` (triangles or tets).
    Medit,
    /// Gmsh `.msh` v2 / v4 ASCII (triangles or tets).
    Gmsh,
    /// Legacy VTK `.vtk` unstructured grid (triangles or tets).
    Vtk,
}

impl MeshFormat {
    /// The format for a file extension (case-insensitive, without the dot).
    pub fn from_extension(ext: &str) -> Option<Self> {
        Some(match ext.to_ascii_lowercase().as_str() {
            "obj" => MeshFormat::Obj,
            "off" => MeshFormat::Off,
            "mesh" => MeshFormat::Medit,
            "msh" => MeshFormat::Gmsh,
            "vtk" => MeshFormat::Vtk,
            _ => return None,
        })
    }
}

/// Parse raw file bytes of a given format (invalid UTF-8 is replaced, so
/// binary input fails with a parse error, never a panic). This is the
/// entry point for fuzzing.
pub fn parse_mesh_bytes(format: MeshFormat, bytes: &[u8]) -> Result<AnyMesh, ParseError> {
    let text = text::decode(bytes);
    match format {
        MeshFormat::Obj => parse_obj(&text).map(AnyMesh::Tri),
        MeshFormat::Off => parse_off(&text).map(AnyMesh::Tri),
        MeshFormat::Medit => parse_medit(&text),
        MeshFormat::Gmsh => parse_gmsh(&text),
        MeshFormat::Vtk => parse_vtk(&text),
    }
}

/// Read a mesh, choosing the format by extension: `.obj .off .mesh .msh
/// .vtk`. MEDIT, Gmsh and VTK files give a tet mesh when they hold tets,
/// else a triangle mesh. The mesh is not validated: see
/// [`crate::validate_tri`] / [`crate::validate_tet`].
pub fn read_mesh(path: impl AsRef<Path>) -> Result<AnyMesh, MeshError> {
    let path = path.as_ref();
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    let format =
        MeshFormat::from_extension(&extension).ok_or_else(|| MeshError::UnsupportedExtension {
            path: path.to_path_buf(),
            extension: extension.clone(),
        })?;
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_mesh_bytes(format, &bytes).map_err(|e| e.at(path))
}

/// Read a triangle mesh; a file holding tets is a [`MeshError::WrongKind`].
pub fn read_tri_mesh(path: impl AsRef<Path>) -> Result<TriMesh, MeshError> {
    let path = path.as_ref();
    match read_mesh(path)? {
        AnyMesh::Tri(m) => Ok(m),
        other => Err(MeshError::WrongKind {
            path: path.to_path_buf(),
            expected: "triangle",
            found: other.kind(),
        }),
    }
}

/// Read a tet mesh; a file holding only triangles is a
/// [`MeshError::WrongKind`].
pub fn read_tet_mesh(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    let path = path.as_ref();
    match read_mesh(path)? {
        AnyMesh::Tet(m) => Ok(m),
        other => Err(MeshError::WrongKind {
            path: path.to_path_buf(),
            expected: "tetrahedral",
            found: other.kind(),
        }),
    }
}
