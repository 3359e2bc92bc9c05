//! The report's PNG figures, drawn with ecc-scene's plotters-based
//! [`Chart`] (one plotting module for the scenes and the report).

use ecc_scene::pictures::{Chart, Series};

use super::Results;
use crate::element::Method;
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
                label: m.label(d),
                points: vec![(mean_ratio(r, m, d)?, worst_err(r, m, d)?.max(1e-17))],
                dots: true,
                colour: None,
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
        ..Chart::default()
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
                label: m.label().into(),
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
                colour: None,
            })
        })
        .collect();
    Chart {
        title: format!("{problem}: convergence"),
        xlabel: if by_time {
            "wall time (s)".into()
        } else {
            "iteration".into()
        },
        ylabel: "‖∇E‖∞".into(),
        log_y: true,
        integer_x: !by_time,
        series,
        hlines: THRESHOLDS.to_vec(),
        hline_label: "thresholds".into(),
        ..Chart::default()
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
                    colour: None,
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
        ..Chart::default()
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

#[cfg(test)]
mod tests {
    //! The figures of the committed full run (`docs/benchmarks/results.json`),
    //! rebuilt from its JSON: every figure renders at its size with ink in
    //! the plot. `ECC_FIGURES_OUT=DIR` also writes them there (to look at,
    //! or to refresh docs/benchmarks/*.png without re-running the report).

    use serde_json::Value;

    use super::*;
    use crate::element::accuracy::{AccuracyResult, AccuracyRow};
    use crate::element::timing::{TimingResult, TimingRow};
    use crate::report::{ProblemInfo, Size};
    use crate::scaling::ScalingRow;
    use crate::solve::{Point, Trace};

    fn f(v: &Value, k: &str) -> f64 {
        v[k].as_f64().unwrap_or(f64::NAN)
    }
    fn u(v: &Value, k: &str) -> usize {
        v[k].as_u64().unwrap_or(0) as usize
    }
    fn s(v: &Value, k: &str) -> String {
        v[k].as_str().unwrap_or_default().to_string()
    }
    fn rows(v: &Value) -> &[Value] {
        v.as_array().map(Vec::as_slice).unwrap_or(&[])
    }
    fn method(v: &Value) -> Method {
        let name = v["method"].as_str().unwrap_or_default();
        *Method::ALL
            .iter()
            .find(|m| format!("{m:?}") == name)
            .unwrap_or_else(|| panic!("unknown method {name}"))
    }
    fn solve_method(v: &Value) -> SolveMethod {
        let name = v["method"].as_str().unwrap_or_default();
        *SolveMethod::ALL
            .iter()
            .find(|m| format!("{m:?}") == name)
            .unwrap_or_else(|| panic!("unknown solve method {name}"))
    }

    /// The parts of `results.json` the figures read.
    fn results(v: &Value) -> Results {
        let timing = rows(&v["timing"]["rows"])
            .iter()
            .map(|r| TimingRow {
                dim: u(r, "dim"),
                energy: s(r, "energy"),
                method: method(r),
                ns: f(r, "ns"),
                ratio: f(r, "ratio"),
            })
            .collect();
        let accuracy = rows(&v["accuracy"]["rows"])
            .iter()
            .map(|r| AccuracyRow {
                dim: u(r, "dim"),
                energy: s(r, "energy"),
                class: s(r, "class"),
                method: method(r),
                hess_err: f(r, "hess_err"),
                grad_err: f(r, "grad_err"),
                samples: u(r, "samples"),
            })
            .collect();
        let problems = rows(&v["problems"])
            .iter()
            .map(|p| ProblemInfo {
                name: s(p, "name"),
                file: s(p, "file"),
                energy: s(p, "energy"),
                elements: u(p, "elements"),
                vertices: u(p, "vertices"),
            })
            .collect();
        let traces = rows(&v["traces"])
            .iter()
            .map(|t| Trace {
                problem: s(t, "problem"),
                method: solve_method(t),
                elements: u(t, "elements"),
                unknowns: u(t, "unknowns"),
                points: rows(&t["points"])
                    .iter()
                    .map(|p| Point {
                        iter: u(p, "iter"),
                        seconds: f(p, "seconds"),
                        grad_inf: f(p, "grad_inf"),
                        energy: f(p, "energy"),
                    })
                    .collect(),
                status: s(t, "status"),
                seconds_measured: f(t, "seconds_measured"),
            })
            .collect();
        let scaling = rows(&v["scaling"])
            .iter()
            .map(|r| ScalingRow {
                mesh: s(r, "mesh"),
                elements: u(r, "elements"),
                unknowns: u(r, "unknowns"),
                solver: s(r, "solver"),
                setup_s: f(r, "setup_s"),
                iterations: u(r, "iterations"),
                per_iter_s: f(r, "per_iter_s"),
                assembly_s: f(r, "assembly_s"),
                factor_s: f(r, "factor_s"),
                solve_s: f(r, "solve_s"),
                line_search_s: f(r, "line_search_s"),
                cg_per_iter: f(r, "cg_per_iter"),
                factor_mb: f(r, "factor_mb"),
                status: s(r, "status"),
            })
            .collect();
        Results {
            size: Size::Full,
            command: s(v, "command"),
            machine: Default::default(),
            timing: TimingResult {
                rows: timing,
                ..Default::default()
            },
            accuracy: AccuracyResult {
                rows: accuracy,
                ..Default::default()
            },
            autodiff: Default::default(),
            problems,
            traces,
            rounds: Vec::new(),
            solve_limits: (0.0, 0, 0),
            scaling,
            scaling_iters: 0,
            notes: vec![],
            seconds: 0.0,
        }
    }

    #[test]
    fn figures_of_the_committed_run_render() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../docs/benchmarks/results.json"
        );
        let text = std::fs::read_to_string(path).expect("docs/benchmarks/results.json");
        let v: Value = serde_json::from_str(&text).expect("valid JSON");
        let r = results(&v);
        let figs = all(&r);
        // 2 trade-off plots, 2 per problem, the scaling plot
        assert_eq!(figs.len(), 2 + 2 * r.problems.len() + 1);
        for (name, png) in &figs {
            let dec = png::Decoder::new(std::io::Cursor::new(png.as_slice()));
            let mut rd = dec.read_info().expect("a PNG");
            let mut buf = vec![0; rd.output_buffer_size().expect("size")];
            let info = rd.next_frame(&mut buf).expect("decodes");
            assert_eq!(info.width, 900, "{name}");
            // coloured curve pixels (not grey ink or white)
            let coloured = buf
                .chunks(3)
                .filter(|c| c.iter().max().unwrap_or(&0) - c.iter().min().unwrap_or(&0) > 60)
                .count();
            assert!(coloured > 300, "{name}: {coloured} coloured pixels");
            if let Some(dir) = std::env::var_os("ECC_FIGURES_OUT") {
                let out = std::path::Path::new(&dir).join(name);
                std::fs::write(&out, png).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
            }
        }
    }
}
