//! `ecc.Energy`: an energy loaded from `.psi` text, a file or the standard
//! library, evaluated by the interpreter (the `ecc eval` code path).

use std::sync::Arc;

use ecc_dsl::{LoadError, Source};
use ecc_runtime::{Dim, Energy, Space};
use nalgebra::SMatrix;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyDictMethods};

use crate::builtin;
use crate::errors::{energy_error, energy_plain};
use crate::point::{PointOut, evaluate};

/// An energy density Ψ(F), isotropic, in 2D and/or 3D.
///
/// `Energy(text, *, name="energy", **params)` compiles `.psi` text, e.g.
/// `Energy("I2 - 2*I1 + d")`; `Energy.from_file(path, **params)` a file;
/// `Energy.builtin(name, **params)` a standard energy (`ecc.builtin_names()`),
/// e.g. `Energy.builtin("snh", mu=1, lambda_=10)` (`lambda_` is `lambda`).
/// `eval(F)` returns Ψ, ∂Ψ/∂F, the raw and projected Hessians and the
/// eigenvalues as numpy arrays; `report()` the Markdown analysis,
/// `emit_rust()` the generated Rust. Bad text raises `EnergyError` with
/// `line`, `column` and `diagnostic`.
#[pyclass(name = "Energy", module = "ecc", frozen)]
pub struct PyEnergy {
    name: String,
    /// The compiled text(s): one, or for a built-in one per dimension file.
    sources: Vec<Source>,
    params: Vec<(String, f64)>,
    e2: Option<Arc<dyn Energy<2>>>,
    e3: Option<Arc<dyn Energy<3>>>,
}

/// `lambda_=10` → `("lambda", 10.0)`: one trailing underscore is dropped
/// (Python keywords cannot be parameter names).
pub fn params_from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, f64)>> {
    let mut out = Vec::new();
    if let Some(kw) = kwargs {
        for (k, v) in kw.iter() {
            let key: String = k.extract()?;
            let name = key.strip_suffix('_').unwrap_or(&key).to_string();
            let value: f64 = v
                .extract()
                .map_err(|_| energy_plain(format!("parameter `{name}` must be a number")))?;
            out.push((name, value));
        }
    }
    Ok(out)
}

/// A load error as `EnergyError`; syntax errors carry line and column.
fn load_error(e: LoadError, text: Option<&str>, name: &str) -> PyErr {
    match &e {
        LoadError::Syntax { rendered, .. } => {
            let at = text.and_then(|t| match ecc_dsl::compile(t, name) {
                Err(d) => d.errors.first().map(|err| err.span().line_col(t)),
                Ok(_) => None,
            });
            let first = rendered.lines().next().unwrap_or("invalid energy");
            energy_error(first.trim_start_matches("error: "), at, rendered)
        }
        LoadError::Io { .. } => energy_plain(e.to_string()),
    }
}

fn build<const D: usize>(
    sources: &[Source],
    params: &[(String, f64)],
) -> PyResult<Option<Arc<dyn Energy<D>>>>
where
    Space<D>: Dim<D>,
{
    let dim = u8::try_from(D).unwrap_or(0);
    let Some(src) = sources.iter().find(|s| s.module.dim(dim).is_some()) else {
        return Ok(None);
    };
    let e = ecc_interp::energy_from_module::<D>(&src.module, &src.shown, params)
        .map_err(energy_plain)?;
    Ok(Some(Arc::new(e)))
}

impl PyEnergy {
    /// A built-in energy with its default parameters.
    pub fn builtin_named(name: &str) -> PyResult<Self> {
        Self::builtin_with(name, Vec::new())
    }

    fn builtin_with(name: &str, params: Vec<(String, f64)>) -> PyResult<Self> {
        let Some(canon) = builtin::canonical(name) else {
            return Err(energy_plain(format!(
                "unknown energy `{name}` (known: {})",
                builtin::names().join(", ")
            )));
        };
        let mut sources: Vec<Source> = Vec::new();
        for dim in [2, 3] {
            for stem in builtin::stems(canon, dim) {
                let Some(src) = builtin::compiled(&stem) else {
                    continue;
                };
                if sources.iter().any(|s| s.name == stem) {
                    break;
                }
                let src = src.map_err(|e| load_error(e, builtin::file(&stem), &stem))?;
                if src.module.dim(dim as u8).is_some() {
                    sources.push(src);
                    break;
                }
            }
        }
        if sources.is_empty() {
            return Err(energy_plain(format!("no standard file for `{canon}`")));
        }
        Self::from_sources(canon.to_string(), sources, params)
    }

    fn from_sources(
        name: String,
        sources: Vec<Source>,
        params: Vec<(String, f64)>,
    ) -> PyResult<Self> {
        let e2 = build::<2>(&sources, &params)?;
        let e3 = build::<3>(&sources, &params)?;
        if e2.is_none() && e3.is_none() {
            let why: Vec<String> = sources[0]
                .module
                .skipped
                .iter()
                .map(|(d, w)| format!("{d}D: {w}"))
                .collect();
            return Err(energy_plain(format!(
                "`{name}` compiles in no dimension ({})",
                why.join("; ")
            )));
        }
        Ok(PyEnergy {
            name,
            sources,
            params,
            e2,
            e3,
        })
    }

    /// The energy in dimension `D`, shared (solves hold it across threads).
    pub fn get<const D: usize>(&self) -> PyResult<Arc<dyn Energy<D>>>
    where
        Space<D>: Dim<D>,
    {
        let e: Option<&dyn std::any::Any> = match D {
            2 => Some(&self.e2),
            3 => Some(&self.e3),
            _ => None,
        };
        e.and_then(|e| e.downcast_ref::<Option<Arc<dyn Energy<D>>>>())
            .and_then(|e| e.clone())
            .ok_or_else(|| {
                energy_plain(format!(
                    "`{}` has no {D}D version (it exists in {})",
                    self.name,
                    self.dims_text()
                ))
            })
    }

    fn dims_text(&self) -> String {
        let d: Vec<String> = self.dim_list().iter().map(|d| format!("{d}D")).collect();
        d.join(" and ")
    }

    fn dim_list(&self) -> Vec<usize> {
        [(2, self.e2.is_some()), (3, self.e3.is_some())]
            .into_iter()
            .filter(|(_, ok)| *ok)
            .map(|(d, _)| d)
            .collect()
    }

    fn source_for(&self, dim: Option<usize>) -> PyResult<&Source> {
        let Some(d) = dim else {
            return Ok(&self.sources[0]);
        };
        let d8 = u8::try_from(d).unwrap_or(0);
        self.sources
            .iter()
            .find(|s| s.module.dim(d8).is_some())
            .ok_or_else(|| energy_plain(format!("`{}` has no {d}D version", self.name)))
    }
}

#[pymethods]
impl PyEnergy {
    /// Energy(text, *, name="energy", **params)
    ///
    /// Compile `.psi` text, e.g. `Energy("I2 - 2*I1 + d")` or
    /// `Energy("param mu = 1\npsi = mu*(I2 - d)", mu=2)`. Keyword arguments
    /// override declared parameters (`lambda_` means `lambda`). Raises
    /// `EnergyError` (with `line`, `column`, `diagnostic`) on bad text.
    #[new]
    #[pyo3(signature = (text, *, name = "energy", **params))]
    fn new(text: &str, name: &str, params: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let params = params_from_kwargs(params)?;
        let file = format!("<{name}>");
        let mut src =
            ecc_dsl::load_text(text, &file).map_err(|e| load_error(e, Some(text), name))?;
        src.name = name.to_string();
        Self::from_sources(name.to_string(), vec![src], params)
    }

    /// Energy.from_file(path, **params): compile a `.psi` file.
    #[staticmethod]
    #[pyo3(signature = (path, **params))]
    fn from_file(path: std::path::PathBuf, params: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let params = params_from_kwargs(params)?;
        let text = std::fs::read_to_string(&path).ok();
        let name = ecc_dsl::energy_name(&path.display().to_string());
        let src = ecc_dsl::load_file(&path).map_err(|e| load_error(e, text.as_deref(), &name))?;
        Self::from_sources(src.name.clone(), vec![src], params)
    }

    /// Energy.builtin(name, **params): a standard energy (energies/psi), e.g.
    /// `Energy.builtin("snh", mu=1, lambda_=10)`; see `ecc.builtin_names()`.
    #[staticmethod]
    #[pyo3(signature = (name, **params))]
    fn builtin(name: &str, params: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        Self::builtin_with(name, params_from_kwargs(params)?)
    }

    /// The energy's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The dimensions it exists in, e.g. `[2, 3]`.
    #[getter]
    fn dims(&self) -> Vec<usize> {
        self.dim_list()
    }

    /// The parameter values in force, `{name: value}`.
    #[getter]
    fn params(&self) -> Vec<(String, f64)> {
        match (&self.e3, &self.e2) {
            (Some(e), _) => e.params(),
            (None, Some(e)) => e.params(),
            _ => self.params.clone(),
        }
    }

    /// The `.psi` source text (for a built-in with per-dimension files: the
    /// file of `dim`, default the first).
    #[pyo3(signature = (dim = None))]
    fn source(&self, dim: Option<usize>) -> PyResult<String> {
        Ok(self.source_for(dim)?.text.clone())
    }

    /// The Markdown analysis report (`ecc FILE.psi --emit report`).
    #[pyo3(signature = (dim = None))]
    fn report(&self, dim: Option<usize>) -> PyResult<String> {
        let s = self.source_for(dim)?;
        Ok(ecc_codegen::report_markdown(&s.module, &s.name))
    }

    /// Rust source implementing `ecc_runtime::Energy` (`ecc FILE.psi --emit rs`).
    #[pyo3(signature = (type_name = None, dim = None))]
    fn emit_rust(&self, type_name: Option<String>, dim: Option<usize>) -> PyResult<String> {
        let s = self.source_for(dim)?;
        let ty = type_name.unwrap_or_else(|| ecc_codegen::type_name_from_stem(&s.name));
        ecc_codegen::generate_pretty(&s.module, &ecc_codegen::GenOptions::named(ty))
            .map_err(energy_plain)
    }

    /// Ψ(σ) at signed singular values σ (length 2 or 3).
    fn psi(&self, sigma: Vec<f64>) -> PyResult<f64> {
        match sigma.len() {
            2 => Ok(self.get::<2>()?.psi(&[sigma[0], sigma[1]])),
            3 => Ok(self.get::<3>()?.psi(&[sigma[0], sigma[1], sigma[2]])),
            n => Err(energy_plain(format!(
                "sigma must have 2 or 3 entries, got {n}"
            ))),
        }
    }

    /// eval(F) -> dict: evaluate at one d×d matrix F or a batch (N, d, d), d = 2 or 3.
    ///
    /// Returns numpy arrays, the quantities of `ecc eval --json`:
    /// `psi` (float or (N,); +inf outside the energy's domain), `gradient`
    /// (vec(∂Ψ/∂F), column-major: (d²,) or (N, d²)), `P` (∂Ψ/∂F as (d, d)
    /// or (N, d, d)), `hessian` (raw ∂²Ψ/∂f², (d², d²) or (N, d², d²)),
    /// `hessian_projected` (negative eigenvalues clamped to 0),
    /// `eigenvalues` (of the raw Hessian, ascending) and `sigma` (signed
    /// singular values). Outside the domain the derivatives are NaN (null in
    /// the CLI's JSON). Raises EnergyError on a bad shape or non-finite F.
    #[pyo3(name = "eval")]
    fn eval_py<'py>(&self, py: Python<'py>, f: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        let np = py.import("numpy")?;
        let arr = np
            .call_method1("asarray", (f, np.getattr("float64")?))
            .map_err(|e| energy_plain(format!("F is not a numeric array: {e}")))?;
        let arr = arr
            .cast_into::<PyArrayDyn<f64>>()
            .map_err(|e| energy_plain(e.to_string()))?;
        let ro = arr.readonly();
        let shape = ro.shape().to_vec();
        let (single, n, d) = match shape.as_slice() {
            [a, b] if a == b && (*a == 2 || *a == 3) => (true, 1, *a),
            [m, a, b] if a == b && (*a == 2 || *a == 3) => (false, *m, *a),
            _ => {
                return Err(energy_plain(format!(
                    "F must have shape (d, d) or (N, d, d) with d = 2 or 3, got {shape:?}"
                )));
            }
        };
        let view = ro.as_array();
        if view.iter().any(|x| !x.is_finite()) {
            return Err(energy_plain("F has a NaN or infinite entry"));
        }
        let fs: Vec<f64> = view.iter().copied().collect(); // logical C order
        let out = match d {
            2 => py.detach(|| eval_all::<2>(self.get::<2>(), &fs, n))?,
            _ => py.detach(|| eval_all::<3>(self.get::<3>(), &fs, n))?,
        };
        out.into_dict(py, single, n, d)
    }

    fn __repr__(&self) -> String {
        format!(
            "ecc.Energy({:?}, dims={:?}, params={:?})",
            self.name,
            self.dim_list(),
            self.params()
        )
    }
}

/// Flat results of a batch evaluation.
struct Batch {
    sigma: Vec<f64>,
    psi: Vec<f64>,
    gradient: Vec<f64>,
    hessian: Vec<f64>,
    hessian_projected: Vec<f64>,
    eigenvalues: Vec<f64>,
}

fn eval_all<const D: usize>(
    e: PyResult<Arc<dyn Energy<D>>>,
    fs: &[f64],
    n: usize,
) -> PyResult<Batch>
where
    Space<D>: Dim<D>,
{
    let e = e?;
    let (d2, d4) = (D * D, D * D * D * D);
    let mut b = Batch {
        sigma: vec![0.0; n * D],
        psi: vec![0.0; n],
        gradient: vec![0.0; n * d2],
        hessian: vec![0.0; n * d4],
        hessian_projected: vec![0.0; n * d4],
        eigenvalues: vec![0.0; n * d2],
    };
    for i in 0..n {
        let m = SMatrix::<f64, D, D>::from_fn(|r, c| fs[i * d2 + r * D + c]);
        let out = PointOut {
            sigma: &mut b.sigma[i * D..(i + 1) * D],
            psi: &mut b.psi[i],
            gradient: &mut b.gradient[i * d2..(i + 1) * d2],
            hessian: &mut b.hessian[i * d4..(i + 1) * d4],
            hessian_projected: &mut b.hessian_projected[i * d4..(i + 1) * d4],
            eigenvalues: &mut b.eigenvalues[i * d2..(i + 1) * d2],
        };
        evaluate::<D>(e.as_ref(), &m, out);
    }
    Ok(b)
}

impl Batch {
    /// The dict of arrays; `single` drops the leading batch axis.
    fn into_dict(
        self,
        py: Python<'_>,
        single: bool,
        n: usize,
        d: usize,
    ) -> PyResult<Bound<'_, PyDict>> {
        let dict = PyDict::new(py);
        let d2 = d * d;
        let shaped = |v: Vec<f64>, shape: &[usize]| -> PyResult<Bound<'_, PyArrayDyn<f64>>> {
            let full: Vec<usize> = if single {
                shape.to_vec()
            } else {
                [&[n], shape].concat()
            };
            PyArray1::from_vec(py, v).reshape(full)
        };
        // P[r][c] = ∂Ψ/∂F_rc = gradient[c·d + r] (vec is column-major)
        let mut p = vec![0.0; self.gradient.len()];
        for (k, chunk) in self.gradient.chunks(d2).enumerate() {
            for r in 0..d {
                for c in 0..d {
                    p[k * d2 + r * d + c] = chunk[c * d + r];
                }
            }
        }
        if single {
            dict.set_item("psi", self.psi[0])?;
        } else {
            dict.set_item("psi", shaped(self.psi, &[])?)?;
        }
        dict.set_item("sigma", shaped(self.sigma, &[d])?)?;
        dict.set_item("gradient", shaped(self.gradient, &[d2])?)?;
        dict.set_item("P", shaped(p, &[d, d])?)?;
        dict.set_item("hessian", shaped(self.hessian, &[d2, d2])?)?;
        dict.set_item(
            "hessian_projected",
            shaped(self.hessian_projected, &[d2, d2])?,
        )?;
        dict.set_item("eigenvalues", shaped(self.eigenvalues, &[d2])?)?;
        Ok(dict)
    }
}

/// builtin_names() -> list of the standard energies' names.
#[pyfunction]
pub fn builtin_names() -> Vec<&'static str> {
    builtin::names()
}
