//! `ecc eval --fiber "ax ay [az]"`: the fibre part ψ(I4, I5) of an energy
//! with `fiber a` at F (issue 16). The isotropic part is what `psi`,
//! `gradient`, … report as before; the fibre part is the additive `fibre`
//! object of the JSON (see `CLI.md`): the direction (normalised), I4, I5,
//! ψ, ψ's partials, vec(∂ψ/∂F), the eigenvalues of the raw ∂²ψ/∂f²
//! (numeric, ascending) and the runtime's eigensystem path.

use ecc_runtime::fibre::{FibrePath, fibre_f, invariant4, invariant5, unit_fibre};
use ecc_runtime::{Dim, FibreEnergy, Space, filter::Filter};

use nalgebra::{SMatrix, SymmetricEigen};
use serde_json::{Value, json};

use crate::error::CliError;
use crate::source::Loaded;

/// The `fibre` JSON object, or `None` for an energy without `fiber` (then
/// `--fiber` must be absent). Errors: a fibre energy without `--fiber`, a
/// `--fiber` for an energy without one, a malformed or zero direction.
pub fn fibre_value<const D: usize>(
    loaded: &Loaded,
    params: &[(String, f64)],
    f: &SMatrix<f64, D, D>,
    dir: Option<&str>,
) -> Result<Option<Value>, CliError>
where
    Space<D>: Dim<D>,
{
    let fib = ecc_interp::fibre_from_module::<D>(&loaded.module, &loaded.shown, params)?;
    let (fib, dir) = match (fib, dir) {
        (None, None) => return Ok(None),
        (None, Some(_)) => {
            return Err(CliError::Usage(format!(
                "--fiber given, but {} has no `fiber` statement (no fibre part)",
                loaded.shown
            )));
        }
        (Some(_), None) => {
            return Err(CliError::Usage(format!(
                "{} has a fibre part (`fiber a`): give the direction with --fiber \"ax ay{}\"",
                loaded.shown,
                if D == 3 { " az" } else { "" }
            )));
        }
        (Some(e), Some(d)) => (e, d),
    };
    let a = parse_direction::<D>(dir)?;
    let p = fibre_point(&fib, f, &a);
    let (i4, i5) = (invariant4(f, &a), invariant5(f, &a));
    let d = fib.fibre(i4, i5);
    let num = |x: f64| x.is_finite().then_some(x);
    let (eig, grad) = (&p.eigenvalues, &p.gradient);
    let inside = p.psi.is_finite();
    let partials = [d.d4, d.d5, d.d44, d.d45, d.d55].map(num);
    Ok(Some(json!({
        "direction": a.iter().copied().collect::<Vec<f64>>(),
        "I4": num(i4),
        "I5": num(i5),
        "domain": if inside { "inside" } else { "outside" },
        "psi": num(p.psi),
        "partials": partials,
        "gradient": inside.then(|| grad.iter().map(|x| num(*x)).collect::<Vec<_>>()),
        "eigenvalues": inside.then(|| eig.iter().map(|x| num(*x)).collect::<Vec<_>>()),
        "eigensystem": match p.path {
            FibrePath::ClosedI5 => "closed-form",
            FibrePath::Numeric => "numeric",
            FibrePath::Reduced => "reduced",
            FibrePath::Degenerate => "degenerate",
        },
    })))
}

/// ψ, vec(∂ψ/∂F) and the ascending eigenvalues of the raw ∂²ψ/∂f² at F.
struct Point {
    psi: f64,
    gradient: Vec<f64>,
    eigenvalues: Vec<f64>,
    path: FibrePath,
}

/// [`Point`] in dimension D (the runtime's kernels are per `Space<D>`).
fn fibre_point<const D: usize>(
    e: &ecc_interp::InterpFibre<D>,
    f: &SMatrix<f64, D, D>,
    a: &nalgebra::SVector<f64, D>,
) -> Point {
    let any_f: &dyn std::any::Any = f;
    let any_a: &dyn std::any::Any = a;
    let any_e: &dyn std::any::Any = e;
    macro_rules! at {
        ($d:literal) => {
            if let (Some(f), Some(a), Some(e)) = (
                any_f.downcast_ref::<SMatrix<f64, $d, $d>>(),
                any_a.downcast_ref::<nalgebra::SVector<f64, $d>>(),
                any_e.downcast_ref::<ecc_interp::InterpFibre<$d>>(),
            ) {
                let p = fibre_f(e, f, a, Filter::None, true);
                let mut eig: Vec<f64> = SymmetricEigen::new(p.hess)
                    .eigenvalues
                    .iter()
                    .copied()
                    .collect();
                eig.sort_by(f64::total_cmp);
                return Point {
                    psi: p.psi,
                    gradient: p.grad.iter().copied().collect(),
                    eigenvalues: eig,
                    path: p.path,
                };
            }
        };
    }
    at!(2);
    at!(3);
    Point {
        psi: f64::NAN,
        gradient: Vec::new(),
        eigenvalues: Vec::new(),
        path: FibrePath::Degenerate,
    }
}

/// D numbers separated by spaces or commas, normalised; a zero or
/// non-finite direction is an error.
fn parse_direction<const D: usize>(text: &str) -> Result<nalgebra::SVector<f64, D>, CliError> {
    let bad = |why: &str| CliError::Usage(format!("--fiber \"{text}\": {why}"));
    let xs: Vec<f64> = text
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| bad(&format!("`{t}` is not a number")))
        })
        .collect::<Result<_, _>>()?;
    if xs.len() != D {
        return Err(bad(&format!("expected {D} numbers, found {}", xs.len())));
    }
    let arr: [f64; D] = std::array::from_fn(|i| xs[i]);
    unit_fibre(&arr).ok_or_else(|| bad("the direction must be finite and nonzero"))
}

/// `text` (a pretty-printed JSON object) with `"fibre": value` appended.
pub fn append_to_json(text: &str, value: &Value) -> Result<String, CliError> {
    let inner = serde_json::to_string_pretty(value)?.replace('\n', "\n  ");
    let body = text.trim_end().strip_suffix('}').unwrap_or(text).trim_end();
    Ok(format!("{body},\n  \"fibre\": {inner}\n}}"))
}
