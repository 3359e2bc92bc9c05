//! # ecc-python: the native part of the `ecc` Python package (`ecc._ecc`)
//!
//! Thin bindings over the library code paths the `ecc` CLI uses — nothing
//! here re-implements the maths:
//!
//! | Python | Rust |
//! |---|---|
//! | `Energy(text)`, `Energy.from_file`, `Energy.builtin` | [`ecc_dsl::load_text`] / [`ecc_dsl::load_file`] + [`ecc_interp::energy_from_module`] |
//! | `Energy.eval(F)` | the runtime's signed SVD and F-space formulas ([`ecc_runtime::gradient_f`], [`ecc_runtime::hessian_f`], [`ecc_runtime::eigen_f`]), as `ecc eval` |
//! | `Energy.report()`, `Energy.emit_rust()` | [`ecc_codegen::report_markdown`], [`ecc_codegen::generate_pretty`] |
//! | `parameterize(V, F, …)` | [`ecc_fem::param::parameterize`] |
//! | `deform(V, T, …)` | [`ecc_fem::deform::HandleDeformation`] |
//! | `simulate(scene, …)` | [`ecc_scene::run_scene`] |
//! | `read_mesh(path)`, `write_obj(path, …)` | [`ecc_mesh::read_mesh`], [`ecc_mesh::write_obj`] |
//!
//! Solves run with the GIL released; the progress callback and Ctrl-C are
//! serviced between Newton iterations. Errors are raised as `ecc.Error`
//! subclasses (see `errors`); arrays are validated before any solve, so bad
//! input raises and never crashes the interpreter.

use pyo3::prelude::*;

mod arrays;
mod builtin;
mod energy;
mod errors;
mod hook;
mod mesh_io;
mod point;
mod scene;
mod solve;

/// The native module `ecc._ecc` (re-exported by `ecc/__init__.py`).
#[pymodule]
fn _ecc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<energy::PyEnergy>()?;
    m.add_function(wrap_pyfunction!(energy::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(solve::parameterize, m)?)?;
    m.add_function(wrap_pyfunction!(solve::deform, m)?)?;
    m.add_function(wrap_pyfunction!(scene::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(mesh_io::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(mesh_io::write_obj, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
