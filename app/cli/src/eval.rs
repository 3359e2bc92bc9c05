//! `ecc eval FILE.psi --dim D --F "…" [--param NAME=VALUE]... [--json]`.
//!
//! Evaluates any `.psi` energy at one deformation gradient without rebuilding
//! anything: the CAS derivatives are interpreted (ecc-interp) and fed to the
//! runtime's generic invariant/stretch formulas. See `CLI.md` for the JSON
//! contract.

use std::path::PathBuf;

use ecc_dsl::Path as IrPath;
use ecc_runtime::Energy;
use nalgebra::SMatrix;

use crate::error::CliError;
use crate::input::{MatrixArg, parse_matrix, parse_params};
use crate::output::print_stdout;
use crate::point::{PointEval, evaluate};
use crate::source::{Loaded, load};

/// Arguments of `ecc eval`.
#[derive(clap::Args, Debug)]
#[command(after_long_help = EVAL_HELP)]
pub struct EvalArgs {
    /// The energy: a `.psi` file.
    pub file: PathBuf,
    /// Dimension (2 or 3); inferred from the number of rows of --F if omitted.
    #[arg(long, value_name = "D", value_parser = clap::value_parser!(u8).range(2..=3))]
    pub dim: Option<u8>,
    /// The deformation gradient, row-major, rows separated by `;`
    /// (e.g. "1 0 0; 0 1 0; 0 0 1").
    #[arg(long = "F", value_name = "ROWS", allow_hyphen_values = true)]
    pub f: String,
    /// Override a parameter (repeatable), e.g. --param mu=2.5.
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// Print one JSON object (the documented contract) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The fibre direction "ax ay \[az\]" of an energy with `fiber a`
    /// (normalised); adds the `fibre` object (I4, I5, ψ, eigenvalues).
    #[arg(
        long = "fiber",
        alias = "fibre",
        value_name = "DIR",
        allow_hyphen_values = true
    )]
    pub fiber: Option<String>,
}

const EVAL_HELP: &str = "\
JSON output (--json), one object:
  psi                number: the energy density Ψ(F)
  gradient           d² numbers: vec(∂Ψ/∂F), column-major
  hessian            d² rows of d² numbers: the raw ∂²Ψ/∂f²
  hessian_projected  the same with negative eigenvalues clamped to 0
  eigenvalues        the d² eigenvalues of the raw Hessian, ascending
  plus energy, file, dim, path, params, F, sigma, domain, finite.
  fibre              (only with --fiber, for an energy with `fiber a`) the
                     fibre part: direction, I4, I5, domain, psi, partials,
                     gradient, eigenvalues, eigensystem; psi above is then
                     the isotropic part, the total is their sum.

Non-finite numbers (JSON has no Infinity/NaN) are written as null:
  * F outside the energy's domain (Ψ = +∞, e.g. det F ≤ 0 for a log barrier,
    or Ψ overflowing):
    exit status 0, \"domain\": \"outside\", psi and every derivative field null,
    and an \"error\" message;
  * a genuine singularity of the energy at F (e.g. ARAP's twist eigenvalue
    at σi + σj = 0): the affected entries are null and \"finite\" is false.
Bad input (unreadable file, DSL errors, malformed --F or --param, NaN/inf
values, unknown parameter, wrong dimension) exits non-zero with a message on
stderr.

Example:
  ecc eval energies/psi/snh.psi --dim 3 --F \"1.1 0 0; 0 0.9 0; 0 0 1\" --param mu=2 --json";

/// Run `ecc eval`.
pub fn run(args: &EvalArgs) -> Result<(), CliError> {
    let params = parse_params(&args.params)?;
    let f = parse_matrix(&args.f, args.dim.map(usize::from))?;
    let loaded = load(&args.file)?;
    let text = match f.dim() {
        2 => eval_dim::<2>(&loaded, &f, &params, args)?,
        _ => eval_dim::<3>(&loaded, &f, &params, args)?,
    };
    print_stdout(&text)
}

fn eval_dim<const D: usize>(
    loaded: &Loaded,
    f: &MatrixArg,
    params: &[(String, f64)],
    args: &EvalArgs,
) -> Result<String, CliError>
where
    ecc_runtime::Space<D>: ecc_runtime::Dim<D>,
{
    // The isotropic part; the fibre part (if any) is `fibre_value` below.
    let energy = ecc_interp::iso_part_from_module::<D>(&loaded.module, &loaded.shown, params)?;
    let m = SMatrix::<f64, D, D>::from_fn(|r, c| f.rows[r][c]);
    let point = evaluate::<D>(&energy, &m);
    let fibre = crate::eval_fibre::fibre_value::<D>(loaded, params, &m, args.fiber.as_deref())?;
    let meta = Meta {
        energy: &loaded.name,
        file: &loaded.shown,
        path: match energy.path() {
            IrPath::Invariant => "invariant",
            IrPath::Stretch => "stretch",
        },
        params: energy.params(),
        f: &f.rows,
    };
    match (args.json, fibre) {
        (true, None) => to_json(&meta, &point),
        (true, Some(v)) => crate::eval_fibre::append_to_json(&to_json(&meta, &point)?, &v),
        (false, None) => Ok(to_table(&meta, &point)),
        (false, Some(v)) => Ok(format!(
            "{}fibre: {}\n",
            to_table(&meta, &point),
            serde_json::to_string(&v)?
        )),
    }
}

struct Meta<'a> {
    energy: &'a str,
    file: &'a str,
    path: &'static str,
    params: Vec<(String, f64)>,
    f: &'a [Vec<f64>],
}

/// The documented JSON object (see [`EVAL_HELP`] and `CLI.md`).
fn to_json(meta: &Meta, p: &PointEval) -> Result<String, CliError> {
    let meta = crate::eval_json::EvalMeta {
        energy: meta.energy,
        file: meta.file,
        path: meta.path,
        params: &meta.params,
        f: meta.f,
    };
    Ok(crate::eval_json::render(&meta, p)?)
}

fn fmt_num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:>14.6e}")
    } else {
        format!("{x:>14}")
    }
}

fn fmt_row(xs: &[f64]) -> String {
    xs.iter().map(|&x| fmt_num(x)).collect::<Vec<_>>().join(" ")
}

/// A readable report of the same quantities.
fn to_table(meta: &Meta, p: &PointEval) -> String {
    let mut s = String::new();
    let mut line = |l: String| {
        s.push_str(&l);
        s.push('\n');
    };
    line(format!(
        "energy   {} ({}D, {} path) from {}",
        meta.energy, p.dim, meta.path, meta.file
    ));
    if !meta.params.is_empty() {
        let ps: Vec<String> = meta
            .params
            .iter()
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        line(format!("params   {}", ps.join(", ")));
    }
    line("F".into());
    for r in meta.f {
        line(format!("  {}", fmt_row(r)));
    }
    line(format!("sigma    {}", fmt_row(&p.sigma)));
    if !p.inside_domain() {
        line("psi      +inf: F is outside the energy's domain (no derivatives)".into());
        return s;
    }
    line(format!("psi      {}", fmt_num(p.psi)));
    line("gradient vec(dPsi/dF), column-major".into());
    line(format!("  {}", fmt_row(&p.gradient)));
    for (title, m) in [
        ("hessian  raw d2Psi/df2", &p.hessian),
        (
            "hessian_projected  negative eigenvalues clamped to 0",
            &p.hessian_projected,
        ),
    ] {
        line(title.into());
        for r in m {
            line(format!("  {}", fmt_row(r)));
        }
    }
    line("eigenvalues (raw, ascending)".into());
    line(format!("  {}", fmt_row(&p.eigenvalues)));
    if !p.all_finite() {
        line(
            "note: some values are not finite (a genuine singularity of the energy at this F)"
                .into(),
        );
    }
    s
}
