//! The `ecc eval --json` object as a serde model (the contract is in
//! `CLI.md`): fields in the documented order, non-finite numbers as `null`
//! (serde_json writes NaN and ±∞ as `null`; JSON has neither), integers such
//! as `dim` as integers and every f64 in serde_json's shortest round-trip
//! form (`1.0`, `-2e-300`).

use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

use crate::point::PointEval;

/// Why every derivative field is `null` when F is outside the domain.
pub const OUTSIDE: &str = "psi = +inf: F is outside the energy's domain (e.g. det F <= 0 for a barrier energy) or psi overflows";

/// What `ecc eval` knows besides the point values.
pub struct EvalMeta<'a> {
    /// The energy's name (file stem).
    pub energy: &'a str,
    /// The file as given.
    pub file: &'a str,
    /// `"invariant"` or `"stretch"`.
    pub path: &'static str,
    /// Every parameter with its value, in declaration order.
    pub params: &'a [(String, f64)],
    /// F by rows, as parsed.
    pub f: &'a [Vec<f64>],
}

/// Parameters as a JSON object in declaration order.
struct Params<'a>(&'a [(String, f64)]);

impl Serialize for Params<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (name, value) in self.0 {
            m.serialize_entry(name, value)?;
        }
        m.end()
    }
}

/// The documented object; `error` appears only outside the domain, where
/// `psi` and every derivative are `null`.
#[derive(Serialize)]
struct EvalJson<'a> {
    energy: &'a str,
    file: &'a str,
    dim: usize,
    path: &'a str,
    params: Params<'a>,
    #[serde(rename = "F")]
    f: &'a [Vec<f64>],
    sigma: &'a [f64],
    domain: &'static str,
    finite: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<&'static str>,
    psi: Option<f64>,
    gradient: Option<&'a [f64]>,
    hessian: Option<&'a [Vec<f64>]>,
    hessian_projected: Option<&'a [Vec<f64>]>,
    eigenvalues: Option<&'a [f64]>,
}

/// The JSON text of one evaluation (pretty-printed, one object).
pub fn render(meta: &EvalMeta<'_>, p: &PointEval) -> Result<String, serde_json::Error> {
    let inside = p.inside_domain();
    let some = |b: bool| b.then_some(());
    let json = EvalJson {
        energy: meta.energy,
        file: meta.file,
        dim: p.dim,
        path: meta.path,
        params: Params(meta.params),
        f: meta.f,
        sigma: &p.sigma,
        domain: if inside { "inside" } else { "outside" },
        finite: inside && p.all_finite(),
        error: (!inside).then_some(OUTSIDE),
        psi: some(inside).map(|_| p.psi),
        gradient: some(inside).map(|_| p.gradient.as_slice()),
        hessian: some(inside).map(|_| p.hessian.as_slice()),
        hessian_projected: some(inside).map(|_| p.hessian_projected.as_slice()),
        eigenvalues: some(inside).map(|_| p.eigenvalues.as_slice()),
    };
    serde_json::to_string_pretty(&json)
}
