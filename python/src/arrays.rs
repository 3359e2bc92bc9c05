//! Checking numpy arrays before anything touches them: shape, finiteness and
//! index range. Views are read in place (C or Fortran order, no copy of the
//! caller's array beyond the solver's own storage).

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};

use crate::errors::mesh_error;
use pyo3::PyResult;

/// Vertex positions of shape (n, 2) or (n, 3); 2D points get z = 0.
pub fn positions(name: &str, v: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 3]>> {
    let [n, c] = [v.shape()[0], v.shape()[1]];
    if !(c == 2 || c == 3) || n == 0 {
        return Err(mesh_error(format!(
            "{name} must have shape (n, 3) or (n, 2) with n > 0, got ({n}, {c})"
        )));
    }
    let a = v.as_array();
    let mut out = Vec::with_capacity(n);
    for (i, row) in a.outer_iter().enumerate() {
        let p = [row[0], row[1], if c == 3 { row[2] } else { 0.0 }];
        if p.iter().any(|x| !x.is_finite()) {
            return Err(mesh_error(format!("{name}[{i}] is not finite: {p:?}")));
        }
        out.push(p);
    }
    Ok(out)
}

/// Elements of shape (m, K) with every index in 0..n.
pub fn cells<const K: usize>(
    name: &str,
    t: &PyReadonlyArray2<'_, i64>,
    n: usize,
) -> PyResult<Vec<[usize; K]>> {
    let [m, c] = [t.shape()[0], t.shape()[1]];
    if c != K || m == 0 {
        return Err(mesh_error(format!(
            "{name} must have shape (m, {K}) with m > 0, got ({m}, {c})"
        )));
    }
    let a = t.as_array();
    let mut out = Vec::with_capacity(m);
    for (i, row) in a.outer_iter().enumerate() {
        let mut e = [0usize; K];
        for k in 0..K {
            let x = row[k];
            if x < 0 || x as u64 >= n as u64 {
                return Err(mesh_error(format!(
                    "{name}[{i}] has vertex index {x} outside 0..{n}"
                )));
            }
            e[k] = x as usize;
        }
        out.push(e);
    }
    Ok(out)
}
