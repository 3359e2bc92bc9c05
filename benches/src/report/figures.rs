//! The report's PNG figures (see [`crate::plot`]).

use super::Results;
use crate::element::Method;
use crate::plot::{Chart, Series};
use crate::solve::{SolveMethod, THRESHOLDS};

/// File-name slug of a problem name.
pub fn slug(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    while s.contains("__") {
        s = s.replace("__", "_");
    }
    s.trim_matches('_').to_string()
}

/// ASCII label of a solve method (the plot font is ASCII only).
fn ascii(m: SolveMethod) -> &'static str {
    match m {
        SolveMethod::Clamp => "analytic clamp",
        SolveMethod::Abs => "analytic abs",
        SolveMethod::Adaptive => "adaptive (rho)",
        SolveMethod::NumericProjection => "numeric elem. proj.",
        SolveMethod::LaplacianProxy => "Laplacian proxy",
    }
}

fn method_ascii(m: Method, d: usize) -> String {
    m.label(d).replace('×', "x")
}

/// Geometric mean of the per-energy time ratios of `m` in dimension `d`.
pub fn mean_ratio(r: &Results, m: Method, d: usize) -> Option<f64> {
    let v: Vec<f64> = r
        .timing
        .rows
        .iter()
        .filter(|x| x.dim == d && x.method == m)
        .map(|x| x.ratio.ln())
        .collect();
    (!v.is_empty()).then(|| (v.iter().sum::<f64>() / v.len() as f64).exp())
}

/// Worst Hessian error of `m` in dimension `d` over all energies and classes.
pub fn worst_err(r: &Results, m: Method, d: usize) -> Option<f64> {
    r.accuracy
        .rows
        .iter()
        .filter(|x| x.dim == d && x.method == m && x.samples > 0)
        .map(|x| x.hess_err)
        .reduce(f64::max)
}

fn tradeoff(r: &Results, d: usize) -> Chart {
    let series = Method::ALL
        .iter()
        .filter_map(|&m| {
            Some(Series {
                label: method_ascii(m, d),
                points: vec![(mean_ratio(r, m, d)?, worst_err(r, m, d)?.max(1e-17))],
                dots: true,
            })
        })
        .collect();
    Chart {
        title: format!("{d}D element: time vs worst Hessian error"),
        xlabel: "time per element / analytic (geometric mean over energies)".into(),
        ylabel: "worst relative Hessian error (all energies, all cases)".into(),
        log_x: true,
        log_y: true,
        series,
        hlines: vec![],
    }
}

fn convergence(r: &Results, problem: &str, by_time: bool) -> Chart {
    let series = SolveMethod::ALL
        .iter()
        .filter_map(|&m| {
            let t = r
                .traces
                .iter()
                .find(|t| t.problem == problem && t.method == m)?;
            Some(Series {
                label: ascii(m).into(),
                points: t
                    .points
                    .iter()
                    .map(|p| {
                        (
                            if by_time { p.seconds } else { p.iter as f64 },
                            p.grad_inf.max(1e-16),
                        )
                    })
                    .collect(),
                dots: t.points.len() <= 60,
            })
        })
        .collect();
    let ascii_problem: String = problem.chars().filter(|c| c.is_ascii()).collect();
    Chart {
        title: format!("{ascii_problem}: convergence"),
        xlabel: if by_time {
            "wall time (s)".into()
        } else {
            "iteration".into()
        },
        ylabel: "max |grad E|".into(),
        log_x: false,
        log_y: true,
        series,
        hlines: THRESHOLDS.to_vec(),
    }
}

fn scaling(r: &Results) -> Chart {
    let mut series = Vec::new();
    for mesh in ["tri (SD)", "tet (SNH)"] {
        for solver in ["Cholesky", "Pcg"] {
            let pts: Vec<(f64, f64)> = r
                .scaling
                .iter()
                .filter(|x| x.mesh == mesh && x.solver == solver)
                .map(|x| (x.elements as f64, x.per_iter_s))
                .collect();
            if !pts.is_empty() {
                series.push(Series {
                    label: format!("{mesh} {solver}"),
                    points: pts,
                    dots: true,
                });
            }
        }
    }
    Chart {
        title: "Time per Newton iteration".into(),
        xlabel: "elements".into(),
        ylabel: "seconds per iteration".into(),
        log_x: true,
        log_y: true,
        series,
        hlines: vec![],
    }
}

/// Every figure as (file name, PNG bytes).
pub fn all(r: &Results) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    for d in [2, 3] {
        out.push((
            format!("element_tradeoff_{d}d.png"),
            tradeoff(r, d).png(900, 480),
        ));
    }
    for p in &r.problems {
        for (by_time, suffix) in [(false, "iter"), (true, "time")] {
            out.push((
                format!("solve_{}_{suffix}.png", slug(&p.name)),
                convergence(r, &p.name, by_time).png(900, 460),
            ));
        }
    }
    if !r.scaling.is_empty() {
        out.push(("scaling.png".into(), scaling(r).png(900, 480)));
    }
    out
}
