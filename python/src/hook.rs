//! Between Newton iterations (the solve runs with the GIL released): take
//! the GIL briefly, deliver pending signals (Ctrl-C raises
//! `KeyboardInterrupt`) and call the user's progress callback; either one
//! stops the solve cleanly with status `Interrupted` and the error is
//! re-raised once the solve has returned.

use std::ops::ControlFlow;

use ecc_fem::IterationRecord;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The per-iteration hook of one solve.
pub struct Hook {
    progress: Option<Py<PyAny>>,
    /// The first Python error met (re-raised after the solve).
    pub error: Option<PyErr>,
}

/// A record as a dict (the keys of the per-iteration statistics).
pub fn record_dict<'py>(py: Python<'py>, r: &IterationRecord) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("iter", r.iter)?;
    d.set_item("energy", r.energy)?;
    d.set_item("grad_inf", r.grad_inf)?;
    d.set_item("step", r.step)?;
    d.set_item("max_step", r.max_step)?;
    d.set_item("decrement", r.decrement)?;
    d.set_item("dx_inf", r.dx_inf)?;
    d.set_item("filter", &r.filter)?;
    d.set_item("shift", r.shift)?;
    d.set_item("line_search_evals", r.line_search_evals)?;
    let secs = r.t_assembly + r.t_factor + r.t_solve + r.t_line_search;
    d.set_item("seconds", secs)?;
    Ok(d)
}

impl Hook {
    /// A hook calling `progress(record_dict)` (if given) after every step.
    pub fn new(progress: Option<Py<PyAny>>) -> Self {
        Hook {
            progress,
            error: None,
        }
    }

    /// Called by the solver after each accepted step.
    pub fn step(&mut self, rec: &IterationRecord) -> ControlFlow<()> {
        let res = Python::attach(|py| -> PyResult<bool> {
            py.check_signals()?;
            let Some(cb) = &self.progress else {
                return Ok(true);
            };
            let out = cb.call1(py, (record_dict(py, rec)?,))?;
            // returning False asks to stop; None or True continue
            Ok(!out.bind(py).is(pyo3::types::PyBool::new(py, false)))
        });
        match res {
            Ok(true) => ControlFlow::Continue(()),
            Ok(false) => ControlFlow::Break(()),
            Err(e) => {
                self.error = Some(e);
                ControlFlow::Break(())
            }
        }
    }

    /// Re-raise the error the hook met, if any.
    pub fn finish(self) -> PyResult<()> {
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}
