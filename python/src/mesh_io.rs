//! Mesh files through ecc-mesh's readers and writers (OBJ, OFF, MEDIT,
//! Gmsh, VTK in; OBJ out, atomically).

use std::path::PathBuf;

use ecc_mesh::{AnyMesh, TriMesh};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{cells, positions};
use crate::errors::mesh_error;

fn array<'py, T: numpy::Element + Copy, const K: usize>(
    py: Python<'py>,
    v: &[[T; K]],
) -> PyResult<Bound<'py, PyAny>> {
    let data: Vec<T> = v.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, data)
        .reshape([v.len(), K])?
        .into_any())
}

/// Low-level reader (use `ecc.read_mesh`).
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let mesh = py
        .detach(|| ecc_mesh::read_mesh(&path))
        .map_err(mesh_error)?;
    let d = PyDict::new(py);
    match mesh {
        AnyMesh::Tri(m) => {
            d.set_item("vertices", array(py, &m.positions)?)?;
            let t: Vec<[i64; 3]> = m.triangles.iter().map(|t| t.map(|i| i as i64)).collect();
            d.set_item("triangles", array(py, &t)?)?;
            if let Some(uv) = &m.uvs {
                d.set_item("uv", array(py, uv)?)?;
            }
        }
        AnyMesh::Tet(m) => {
            d.set_item("vertices", array(py, &m.positions)?)?;
            let t: Vec<[i64; 4]> = m.tets.iter().map(|t| t.map(|i| i as i64)).collect();
            d.set_item("tets", array(py, &t)?)?;
        }
    }
    Ok(d)
}

/// Low-level OBJ writer (use `ecc.write_obj`).
#[pyfunction]
#[pyo3(signature = (path, v, f, uv = None))]
pub fn write_obj(
    py: Python<'_>,
    path: PathBuf,
    v: PyReadonlyArray2<'_, f64>,
    f: PyReadonlyArray2<'_, i64>,
    uv: Option<PyReadonlyArray2<'_, f64>>,
) -> PyResult<()> {
    let pos = positions("V", &v)?;
    let tris = cells::<3>("F", &f, pos.len())?;
    let uvs = match uv {
        Some(u) => {
            let u3 = positions("uv", &u)?;
            Some(u3.iter().map(|p| [p[0], p[1]]).collect())
        }
        None => None,
    };
    let mesh = TriMesh {
        positions: pos,
        triangles: tris,
        uvs,
    };
    py.detach(|| ecc_mesh::write_obj(&path, &mesh))
        .map_err(mesh_error)
}
