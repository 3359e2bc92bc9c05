//! The exception hierarchy: `ecc.Error` and its subclasses `EnergyError`
//! (with `line`, `column`, `diagnostic`), `MeshError`, `SceneError`,
//! `SolveError`. Rust errors stay typed until they are turned into one of
//! these here, once.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    ecc,
    Error,
    PyException,
    "Base class of every error raised by ecc."
);
create_exception!(
    ecc,
    EnergyError,
    Error,
    "An energy could not be loaded or evaluated. Attributes: `line`, `column` \
     (1-based, None when the error is not located in the text) and \
     `diagnostic` (the rendered report)."
);
create_exception!(
    ecc,
    MeshError,
    Error,
    "Bad mesh input: wrong array shape or dtype, non-finite coordinates, \
     out-of-range indices, degenerate or non-manifold elements."
);
create_exception!(
    ecc,
    SceneError,
    Error,
    "A scene file could not be read, validated or run."
);
create_exception!(
    ecc,
    SolveError,
    Error,
    "A solve could not be run (setup failed, or it was interrupted)."
);

/// Add the exception classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("EnergyError", py.get_type::<EnergyError>())?;
    m.add("MeshError", py.get_type::<MeshError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    Ok(())
}

/// An `EnergyError` with its location and rendered diagnostic.
pub fn energy_error(message: &str, at: Option<(usize, usize)>, diagnostic: &str) -> PyErr {
    Python::attach(|py| {
        let err = EnergyError::new_err(message.to_string());
        let value = err.value(py);
        let (line, column) = match at {
            Some((l, c)) => (Some(l), Some(c)),
            None => (None, None),
        };
        let set = || -> PyResult<()> {
            value.setattr("line", line)?;
            value.setattr("column", column)?;
            value.setattr("diagnostic", diagnostic)?;
            Ok(())
        };
        match set() {
            Ok(()) => err,
            Err(e) => e,
        }
    })
}

/// An `EnergyError` not located in a text (parameters, dimension, I/O).
pub fn energy_plain(message: impl std::fmt::Display) -> PyErr {
    let m = message.to_string();
    energy_error(&m, None, &m)
}

/// A `MeshError`.
pub fn mesh_error(message: impl std::fmt::Display) -> PyErr {
    MeshError::new_err(message.to_string())
}

/// A `SolveError`.
pub fn solve_error(message: impl std::fmt::Display) -> PyErr {
    SolveError::new_err(message.to_string())
}

/// A `SceneError`.
pub fn scene_error(message: impl std::fmt::Display) -> PyErr {
    SceneError::new_err(message.to_string())
}
