//! Writers: OBJ (with per-vertex uvs) and legacy ASCII VTK unstructured
//! grids with point data. Every writer checks its input first (indices in
//! range, finite numbers, data lengths) so that it never writes a file it
//! could not read back, then writes atomically (see [`super::atomic`]).
//! Numbers are printed in Rust's shortest round-trip form, so reading a
//! written file gives bit-identical coordinates.

use std::path::Path;

use super::atomic::write_atomic;
use crate::error::{MeshError, ValidationError};
use crate::types::{TetMesh, TriMesh};
use crate::validate::check_all_finite;

/// One named point-data array: `(name, values, components)`, with
/// `values.len() == vertex_count · components`, stored vertex-major.
pub type PointData<'a> = (&'a str, &'a [f64], usize);

fn check_elements<const K: usize>(
    elements: &[[usize; K]],
    positions: &[[f64; 3]],
) -> Result<(), MeshError> {
    let n = positions.len();
    for (e, el) in elements.iter().enumerate() {
        if let Some(&index) = el.iter().find(|&&v| v >= n) {
            return Err(ValidationError::IndexOutOfRange {
                element: e,
                index,
                vertex_count: n,
            }
            .into());
        }
    }
    check_all_finite(positions)?;
    Ok(())
}

fn check_point_data(path: &Path, n: usize, data: &[PointData<'_>]) -> Result<(), MeshError> {
    let bad = |message: String| MeshError::Data {
        path: path.to_path_buf(),
        message,
    };
    for (i, (name, values, comps)) in data.iter().enumerate() {
        if name.is_empty() || name.chars().any(|c| c.is_whitespace() || c.is_control()) {
            return Err(bad(format!(
                "point-data name {name:?} must be non-empty without spaces"
            )));
        }
        if data[..i].iter().any(|(other, _, _)| other == name) {
            return Err(bad(format!("point-data name {name:?} is used twice")));
        }
        if *comps == 0 || Some(values.len()) != n.checked_mul(*comps) {
            return Err(bad(format!(
                "point data {name:?} has {} values, expected {n} vertices × {comps} components",
                values.len()
            )));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(bad(format!(
                "point data {name:?} has a non-finite value {} at vertex {} component {}",
                values[k],
                k / comps,
                k % comps
            )));
        }
    }
    Ok(())
}

/// Write an OBJ file: `v x y z` per vertex, then (when `mesh.uvs` is set)
/// `vt u v` per vertex and faces `f a/a b/b c/c`, else `f a b c`.
pub fn write_obj(path: impl AsRef<Path>, mesh: &TriMesh) -> Result<(), MeshError> {
    let path = path.as_ref();
    check_elements(&mesh.triangles, &mesh.positions)?;
    if let Some(uvs) = &mesh.uvs {
        if uvs.len() != mesh.positions.len() {
            return Err(ValidationError::UvCountMismatch {
                uvs: uvs.len(),
                vertices: mesh.positions.len(),
            }
            .into());
        }
        if let Some((vertex, uv)) = uvs
            .iter()
            .enumerate()
            .find(|(_, uv)| !uv[0].is_finite() || !uv[1].is_finite())
        {
            return Err(ValidationError::NonFiniteUv { vertex, uv: *uv }.into());
        }
    }
    write_atomic(path, |w| {
        writeln!(
            w,
            "# ecc-mesh: {} vertices, {} triangles",
            mesh.positions.len(),
            mesh.triangles.len()
        )?;
        for p in &mesh.positions {
            writeln!(w, "v {:?} {:?} {:?}", p[0], p[1], p[2])?;
        }
        match &mesh.uvs {
            Some(uvs) => {
                for uv in uvs {
                    writeln!(w, "vt {:?} {:?}", uv[0], uv[1])?;
                }
                for t in &mesh.triangles {
                    let [a, b, c] = t.map(|i| i + 1);
                    writeln!(w, "f {a}/{a} {b}/{b} {c}/{c}")?;
                }
            }
            None => {
                for t in &mesh.triangles {
                    let [a, b, c] = t.map(|i| i + 1);
                    writeln!(w, "f {a} {b} {c}")?;
                }
            }
        }
        Ok(())
    })
}

fn write_vtk<const K: usize>(
    path: &Path,
    positions: &[[f64; 3]],
    elements: &[[usize; K]],
    cell_type: u8,
    data: &[PointData<'_>],
) -> Result<(), MeshError> {
    check_elements(elements, positions)?;
    check_point_data(path, positions.len(), data)?;
    write_atomic(path, |w| {
        writeln!(w, "# vtk DataFile Version 3.0")?;
        writeln!(w, "ecc-mesh output")?;
        writeln!(w, "ASCII")?;
        writeln!(w, "DATASET UNSTRUCTURED_GRID")?;
        writeln!(w, "POINTS {} double", positions.len())?;
        for p in positions {
            writeln!(w, "{:?} {:?} {:?}", p[0], p[1], p[2])?;
        }
        writeln!(w, "CELLS {} {}", elements.len(), elements.len() * (K + 1))?;
        for el in elements {
            write!(w, "{K}")?;
            for v in el {
                write!(w, " {v}")?;
            }
            writeln!(w)?;
        }
        writeln!(w, "CELL_TYPES {}", elements.len())?;
        for _ in elements {
            writeln!(w, "{cell_type}")?;
        }
        if !data.is_empty() {
            writeln!(w, "POINT_DATA {}", positions.len())?;
            writeln!(w, "FIELD FieldData {}", data.len())?;
            for (name, values, comps) in data {
                writeln!(w, "{name} {comps} {} double", positions.len())?;
                for row in values.chunks(*comps) {
                    let mut first = true;
                    for v in row {
                        if !first {
                            write!(w, " ")?;
                        }
                        first = false;
                        write!(w, "{v:?}")?;
                    }
                    writeln!(w)?;
                }
            }
        }
        Ok(())
    })
}

/// Write a triangle mesh as a legacy ASCII VTK unstructured grid (cell
/// type 5) with optional point data (written as a `FIELD` of `double`
/// arrays, one tuple per vertex).
pub fn write_vtk_tri(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    point_data: &[PointData<'_>],
) -> Result<(), MeshError> {
    write_vtk(
        path.as_ref(),
        &mesh.positions,
        &mesh.triangles,
        5,
        point_data,
    )
}

/// Write a tet mesh as a legacy ASCII VTK unstructured grid (cell type 10)
/// with optional point data.
pub fn write_vtk_tet(
    path: impl AsRef<Path>,
    mesh: &TetMesh,
    point_data: &[PointData<'_>],
) -> Result<(), MeshError> {
    write_vtk(path.as_ref(), &mesh.positions, &mesh.tets, 10, point_data)
}
