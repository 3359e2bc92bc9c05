//! `parameterize` and `deform`: meshes from numpy arrays, solved by ecc-fem
//! with the GIL released.

use std::sync::Arc;

use ecc_fem::NewtonResult;
use ecc_fem::deform::HandleDeformation;
use ecc_fem::param::{ParamOptions, prepare};
use ecc_mesh::{TetMesh, TriMesh, TutteWeights, ValidationOptions, validate_tet, validate_tri};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays::{cells, positions};
use crate::energy::PyEnergy;
use crate::errors::{mesh_error, solve_error};
use crate::hook::{Hook, record_dict};

/// An energy argument: an `ecc.Energy` or a built-in name.
fn energy_arg(e: &Bound<'_, PyAny>) -> PyResult<Py<PyEnergy>> {
    if let Ok(en) = e.cast::<PyEnergy>() {
        return Ok(en.clone().unbind());
    }
    let name: String = e
        .extract()
        .map_err(|_| solve_error("energy must be an ecc.Energy or a built-in name"))?;
    Py::new(e.py(), PyEnergy::builtin_named(&name)?)
}

fn tutte_weights(name: &str) -> PyResult<TutteWeights> {
    match name {
        "uniform" => Ok(TutteWeights::Uniform),
        "mean_value" => Ok(TutteWeights::MeanValue),
        "cotangent" => Ok(TutteWeights::Cotangent),
        _ => Err(solve_error(format!(
            "tutte must be 'uniform', 'mean_value' or 'cotangent', got {name:?}"
        ))),
    }
}

fn status_kind(r: &NewtonResult) -> String {
    serde_json::to_value(&r.status)
        .ok()
        .and_then(|v| v.get("kind").and_then(|k| k.as_str()).map(str::to_string))
        .unwrap_or_else(|| format!("{:?}", r.status))
}

/// The common statistics of a Newton solve.
fn result_dict<'py>(py: Python<'py>, r: &NewtonResult) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("status", status_kind(r))?;
    d.set_item("converged", r.converged())?;
    d.set_item("iterations", r.iterations)?;
    d.set_item("initial_energy", r.initial_energy)?;
    d.set_item("final_energy", r.energy)?;
    d.set_item("grad_inf", r.grad_inf)?;
    d.set_item("seconds", r.times.total)?;
    let recs = PyList::empty(py);
    for rec in &r.records {
        recs.append(record_dict(py, rec)?)?;
    }
    d.set_item("records", recs)?;
    Ok(d)
}

fn flat<'py, const K: usize>(py: Python<'py>, v: &[[f64; K]]) -> PyResult<Bound<'py, PyAny>> {
    let data: Vec<f64> = v.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, data)
        .reshape([v.len(), K])?
        .into_any())
}

/// Low-level parameterisation (use `ecc.parameterize`).
#[pyfunction]
#[pyo3(signature = (v, f, energy, tutte, normalize_area, mean_energy, max_iters, tol, progress))]
#[allow(clippy::too_many_arguments)]
pub fn parameterize<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, i64>,
    energy: &Bound<'py, PyAny>,
    tutte: &str,
    normalize_area: bool,
    mean_energy: bool,
    max_iters: Option<usize>,
    tol: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let pos = positions("V", &v)?;
    let tris = cells::<3>("F", &f, pos.len())?;
    let mesh = validate_tri(
        TriMesh::new(pos, tris),
        false,
        &ValidationOptions::default(),
    )
    .map_err(mesh_error)?
    .mesh;
    let e = energy_arg(energy)?.get().get::<2>()?;
    let mut opts = ParamOptions {
        normalize_area,
        mean_energy,
        tutte: tutte_weights(tutte)?,
        ..ParamOptions::default()
    };
    if let Some(n) = max_iters {
        opts.newton.max_iters = n;
    }
    if let Some(t) = tol {
        opts.newton.tol_abs = t;
    }
    let mut hook = Hook::new(progress);
    let out = py.detach(|| prepare(&mesh, Arc::clone(&e), &opts)?.solve_with(|r, _| hook.step(r)));
    hook.finish()?;
    let p = out.map_err(solve_error)?;
    let d = result_dict(py, &p.result)?;
    d.set_item("uv", flat(py, &p.uv)?)?;
    d.set_item("flipped", p.flipped)?;
    d.set_item("position_scale", p.position_scale)?;
    d.set_item("rest_area", p.rest_area)?;
    Ok(d)
}

/// Low-level handle deformation (use `ecc.deform`).
#[pyfunction]
#[pyo3(signature = (v, t, energy, handles, targets, substeps, max_iters, tol, progress))]
#[allow(clippy::too_many_arguments)]
pub fn deform<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    t: PyReadonlyArray2<'py, i64>,
    energy: &Bound<'py, PyAny>,
    handles: Vec<i64>,
    targets: PyReadonlyArray2<'py, f64>,
    substeps: usize,
    max_iters: Option<usize>,
    tol: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let pos = positions("V", &v)?;
    let n = pos.len();
    let tets = cells::<4>("T", &t, n)?;
    let mesh = validate_tet(TetMesh::new(pos, tets), &ValidationOptions::default())
        .map_err(mesh_error)?
        .mesh;
    let hs: Vec<usize> = handles
        .iter()
        .map(|&h| {
            usize::try_from(h)
                .ok()
                .filter(|&h| h < n)
                .ok_or_else(|| mesh_error(format!("handle index {h} outside 0..{n}")))
        })
        .collect::<PyResult<_>>()?;
    let tg = positions("targets", &targets)?;
    if tg.len() != hs.len() {
        return Err(mesh_error(format!(
            "targets has {} rows for {} handles",
            tg.len(),
            hs.len()
        )));
    }
    let e = energy_arg(energy)?.get().get::<3>()?;
    let mut params = ecc_fem::NewtonParams::default();
    if let Some(k) = max_iters {
        params.max_iters = k;
    }
    if let Some(x) = tol {
        params.tol_abs = x;
    }
    let mut hook = Hook::new(progress);
    let out = py.detach(|| {
        let mut h = HandleDeformation::new(&mesh, e, &hs, params)?;
        let r = h.solve_with(&tg, substeps.max(1), |rec, _| hook.step(rec))?;
        Ok::<_, ecc_fem::FemError>((r, h.positions().to_vec()))
    });
    hook.finish()?;
    let (r, x) = out.map_err(solve_error)?;
    let last = r
        .substeps
        .last()
        .ok_or_else(|| solve_error("the deformation ran no substep"))?;
    let d = result_dict(py, last)?;
    d.set_item("iterations", r.iterations())?;
    d.set_item("converged", r.converged())?;
    d.set_item("substeps", r.substeps.len())?;
    d.set_item("inverted", r.inverted)?;
    d.set_item("x", flat(py, &x)?)?;
    Ok(d)
}
