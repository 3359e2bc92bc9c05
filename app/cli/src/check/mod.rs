//! `ecc check FILE.psi [--dim D] [--samples N] [--seed S] [--param NAME=VALUE]...`
//!
//! Verifies the interpreted eigensystem of any `.psi` energy at hard and
//! random deformation gradients (see [`cases`]) against central differences
//! and a numeric eigensolve (see [`compare`]), prints the worst error per
//! case and per check, and fails (exit status 1) if any exceeds its tolerance.
//! A file with `fiber a` is checked in two sections: its isotropic part
//! Ψ_iso as above, and its fibre part ψ(I4, I5) at every hard case × fibre
//! direction (see [`fibre_cases`], [`fibre`]); both count towards the verdict.

mod cases;
mod compare;
mod fibre;
mod fibre_cases;

use std::fmt::Write as _;
use std::path::PathBuf;

use ecc_dsl::Path as IrPath;
use nalgebra::SMatrix;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::error::CliError;
use crate::input::parse_params;
use crate::output::print_stdout;
use crate::source::{Loaded, load};
use compare::Errors;
use ecc_runtime::Space;
use ecc_runtime::fibre::FibreDim;

/// Tolerances (relative, see [`compare`]) for gradient, Hessian, eigenvalues, projection.
///
/// Central differences (with Richardson extrapolation) are accurate to
/// ≈1e-11 (gradient) and ≈1e-7 (Hessian) on the library energies, worst
/// ≈2e-6 at σ = 1e3, so the first two leave room for hard points; the eigen
/// checks compare two exact computations in floating point.
pub const TOLERANCES: [f64; 4] = [1e-6, 1e-5, 1e-8, 1e-8];
const CHECK_NAMES: [&str; 4] = ["gradient", "hessian", "eigenvalues", "projected"];

/// Arguments of `ecc check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The energy: a `.psi` file.
    pub file: PathBuf,
    /// Check only this dimension (default: every dimension the energy compiles for).
    #[arg(long, value_name = "D", value_parser = clap::value_parser!(u8).range(2..=3))]
    pub dim: Option<u8>,
    /// Number of random deformation gradients (in addition to the hard cases).
    #[arg(long, value_name = "N", default_value_t = 32)]
    pub samples: usize,
    /// Seed of the random deformation gradients and rotations.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Override a parameter (repeatable), e.g. --param mu=2.5.
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
}

/// Worst errors of one report row.
#[derive(Default)]
struct Row {
    name: String,
    points: usize,
    worst: [Option<f64>; 4],
    /// Each distinct note with the number of points it applied to.
    notes: Vec<(&'static str, usize)>,
}

impl Row {
    fn add(&mut self, e: &Errors) {
        self.points += 1;
        let v = [e.gradient, e.hessian, e.eigenvalues, e.projected];
        for (w, x) in self.worst.iter_mut().zip(v) {
            if let Some(x) = x {
                *w = Some(w.map_or(
                    x,
                    |m: f64| if x.is_nan() { f64::INFINITY } else { m.max(x) },
                ));
            }
        }
        if let Some(n) = e.note {
            match self.notes.iter_mut().find(|(m, _)| *m == n) {
                Some((_, c)) => *c += 1,
                None => self.notes.push((n, 1)),
            }
        }
    }
}

/// Run `ecc check`.
pub fn run(args: &CheckArgs) -> Result<(), CliError> {
    let params = parse_params(&args.params)?;
    let loaded = load(&args.file)?;
    let dims: Vec<u8> = match args.dim {
        Some(d) => vec![d],
        None => loaded.module.dims.iter().map(|d| d.dim).collect(),
    };
    let mut failures = 0;
    let mut report = String::new();
    for dim in dims {
        let (text, failed) = match dim {
            2 => check_dim::<2>(&loaded, &params, args)?,
            _ => check_dim::<3>(&loaded, &params, args)?,
        };
        report.push_str(&text);
        failures += failed;
    }
    print_stdout(&report)?;
    if failures > 0 {
        return Err(CliError::CheckFailed { failures });
    }
    Ok(())
}

fn check_dim<const D: usize>(
    loaded: &Loaded,
    params: &[(String, f64)],
    args: &CheckArgs,
) -> Result<(String, usize), CliError>
where
    Space<D>: FibreDim<D>,
{
    let module = &loaded.module;
    let fibre = ecc_interp::fibre_from_module::<D>(module, &loaded.shown, params)?;
    let energy = ecc_interp::iso_part_from_module::<D>(module, &loaded.shown, params)?;
    let mut rng = ChaCha8Rng::seed_from_u64(args.seed ^ D as u64);
    let (mut text, mut failed) = (String::new(), 0);
    if fibre.is_none() || !ecc_interp::iso_part_is_zero(module, D) {
        let rows = iso_rows::<D>(loaded, &energy, &mut rng, args.samples);
        let path = match energy.path() {
            IrPath::Invariant => "invariant",
            IrPath::Stretch => "stretch",
        };
        let points: usize = rows.iter().map(|r| r.points).sum();
        let title = format!(
            "ecc check {} ({}D, {} path, {} points; relative errors, `-` = skipped, `!` = above tolerance)",
            loaded.shown, D, path, points
        );
        let (t, f) = render(&title, 22, &rows);
        text.push_str(&t);
        failed += f;
    }
    if let Some(fib) = &fibre {
        let mut rows: Vec<Row> = Vec::new();
        for case in fibre_cases::fibre_cases::<D>(&mut rng, args.samples) {
            let errors = fibre::compare_fibre::<D>(fib, &case.f, &case.a);
            add_to(&mut rows, case.name, &errors);
        }
        let points: usize = rows.iter().map(|r| r.points).sum();
        let zero_iso = if ecc_interp::iso_part_is_zero(module, D) {
            "; isotropic part identically 0"
        } else {
            ""
        };
        let title = format!(
            "ecc check {} ({}D) fibre part psi(I4, I5) ({} points{zero_iso}; relative errors, `-` = skipped, `!` = above tolerance)",
            loaded.shown, D, points
        );
        let (t, f) = render(&title, 30, &rows);
        text.push_str(&t);
        failed += f;
    }
    Ok((text, failed))
}

/// Add one point's errors to the row called `name` (created on first use).
fn add_to(rows: &mut Vec<Row>, name: String, errors: &Errors) {
    match rows.iter_mut().find(|r| r.name == name) {
        Some(r) => r.add(errors),
        None => {
            let mut r = Row {
                name,
                ..Row::default()
            };
            r.add(errors);
            rows.push(r);
        }
    }
}

/// The isotropic rows: hard, random and plane cases.
fn iso_rows<const D: usize>(
    loaded: &Loaded,
    energy: &ecc_interp::InterpEnergy<D>,
    rng: &mut ChaCha8Rng,
    samples: usize,
) -> Vec<Row>
where
    Space<D>: FibreDim<D>,
{
    let mut twists = [compare::Twist::Smooth; 3];
    if let Some(ir) = loaded.module.dim(D as u8) {
        for (k, kind) in ir.spectral.twist_kind.iter().enumerate().take(3) {
            twists[k] = match kind {
                ecc_dsl::PairKind::Pole => compare::Twist::Pole,
                ecc_dsl::PairKind::Removable if !ir.sign_symmetric => compare::Twist::Kinked,
                _ => compare::Twist::Smooth,
            };
        }
    }
    let mut rows: Vec<Row> = Vec::new();
    let mut all = cases::cases::<D>(rng, samples);
    all.extend(plane_cases::<D>(rng));
    for case in all {
        let errors = compare::compare::<D>(energy, &case.f, twists);
        add_to(&mut rows, case.name.to_string(), &errors);
    }
    rows
}

/// Row names of [`plane_cases`] by offset: exactly on the plane, then 1e-3…1e-12 off it.
const TWIST_ROWS: [&str; 5] = [
    "si = -sj",
    "si = -sj + 1e-3",
    "si = -sj + 1e-6",
    "si = -sj + 1e-9",
    "si = -sj + 1e-12",
];
const FLIP_ROWS: [&str; 5] = [
    "si = sj",
    "si = sj + 1e-3",
    "si = sj + 1e-6",
    "si = sj + 1e-9",
    "si = sj + 1e-12",
];

/// Points on and near the singular sets of every pair's divided
/// differences, F = U diag(σ) Vᵀ with random rotations: σi = −σj (twist) and
/// σi = σj (flip) exactly and 1e-3, 1e-6, 1e-9, 1e-12 (relative) away. In the
/// signed SVD only pairs with the last (possibly negative) σ can meet
/// σi = −σj, so 3D visits (1.2, a, −a) (slot 0) and (a, a, −a) (slots 0 and 1);
/// flips visit (c, a, a) with c below and above a, and (a, a, a); the last σ
/// is the one moved off the plane.
fn plane_cases<const D: usize>(rng: &mut ChaCha8Rng) -> Vec<cases::Case<D>> {
    let a = 0.7;
    let twists: Vec<Vec<f64>> = if D == 2 {
        vec![vec![a, -a]]
    } else {
        vec![vec![1.2, a, -a], vec![a, a, -a]]
    };
    let flips: Vec<Vec<f64>> = if D == 2 {
        vec![vec![a, a]]
    } else {
        vec![vec![0.4, a, a], vec![1.2, a, a], vec![a, a, a]]
    };
    let offsets = [0.0, 1e-3, 1e-6, 1e-9, 1e-12];
    let mut out = Vec::new();
    for (sets, names) in [(twists, TWIST_ROWS), (flips, FLIP_ROWS)] {
        for s in sets {
            for (delta, name) in offsets.iter().zip(names) {
                let mut sigma = s.clone();
                sigma[D - 1] += delta * a;
                let u = cases::random_rotation::<D>(rng);
                let v = cases::random_rotation::<D>(rng);
                let d = SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { sigma[i] } else { 0.0 });
                out.push(cases::Case {
                    name,
                    f: u * d * v.transpose(),
                });
            }
        }
    }
    out
}

fn cell(x: Option<f64>, tol: f64) -> String {
    match x {
        None => format!("{:>12}", "-"),
        Some(v) if v.is_finite() && v <= tol => format!("{v:>12.2e}"),
        Some(v) => format!("{:>12}", format!("{v:.2e}!")),
    }
}

/// The table under `title` with a `width`-wide case column; returns the
/// text and the number of checks whose worst error fails.
fn render(title: &str, width: usize, rows: &[Row]) -> (String, usize) {
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let _ = writeln!(
        s,
        "{:<width$}{:>12}{:>12}{:>12}{:>12}  note",
        "case", CHECK_NAMES[0], CHECK_NAMES[1], CHECK_NAMES[2], CHECK_NAMES[3]
    );
    let mut worst = [None::<f64>; 4];
    for r in rows {
        let label = if r.points > 1 {
            format!("{} ({})", r.name, r.points)
        } else {
            r.name.clone()
        };
        let _ = write!(s, "{label:<width$}");
        for k in 0..4 {
            let _ = write!(s, "{}", cell(r.worst[k], TOLERANCES[k]));
            if let Some(v) = r.worst[k] {
                let v = if v.is_nan() { f64::INFINITY } else { v };
                worst[k] = Some(worst[k].map_or(v, |m: f64| m.max(v)));
            }
        }
        let notes: Vec<String> = r
            .notes
            .iter()
            .map(|(n, c)| {
                if r.points > 1 {
                    format!("{n} ({c} of {})", r.points)
                } else {
                    n.to_string()
                }
            })
            .collect();
        let _ = writeln!(s, "  {}", notes.join("; "));
    }
    let _ = write!(s, "{:<width$}", "worst");
    let mut failed = 0;
    for k in 0..4 {
        let _ = write!(s, "{}", cell(worst[k], TOLERANCES[k]));
        if worst[k].is_some_and(|v| !v.is_finite() || v > TOLERANCES[k]) {
            failed += 1;
        }
    }
    let _ = writeln!(s);
    let _ = write!(s, "{:<width$}", "tolerance");
    for t in TOLERANCES {
        let _ = write!(s, "{t:>12.0e}");
    }
    let _ = writeln!(s);
    let verdict = if failed == 0 { "PASS" } else { "FAIL" };
    let _ = writeln!(s, "result: {verdict}\n");
    (s, failed)
}
