//! The report: runs the three studies at a chosen size and writes
//! `BENCHMARKS.md`, PNG plots and `results.json` into a folder.
//!
//! | size | per element | per solve | scaling |
//! |---|---|---|---|
//! | full (default) | 4 samples/class, 256 elements × 41 rounds | 5 problems × 8 methods, ≤ 30 s each; defaults on 1 and 2 threads and autodiff × 5 interleaved rounds | tris 10k…1M, tets 10k…300k (Cholesky ≤ 100k), 3 steps |
//! | `--quick` | 2 samples/class, 128 × 11 | same problems, ≤ 8 s each; × 3 rounds | tris 10k, 100k; tets 10k, 30k; 2 steps |
//! | tiny (tests) | 1 sample, 2 energies, 3 classes | hand_1_i_f5000, 2 s; × 2 rounds | 2k tris, 1k tets, 1 step |
//!
//! Run with `cargo run --release -p ecc-benches --bin report -- [--quick] [--out DIR]`.

pub mod cholmod;
pub mod figures;
pub mod machine;
pub mod markdown;
pub mod rounds;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::Serialize;

use crate::element::{accuracy, autodiff, timing};
use crate::scaling::{self, ScalingPlan, ScalingRow};
use crate::solve::{self, SolveError, SolveLimits, SolveMethod, Trace};
use machine::Machine;
use rounds::Rounds;

/// Size of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Size {
    Full,
    Quick,
    /// Seconds, for the CI smoke test.
    Tiny,
}

/// Everything the report needs to know.
#[derive(Clone, Debug)]
pub struct Config {
    pub size: Size,
    pub out: PathBuf,
    /// Folder with the meshes (`ecc_mesh::data_dir()`).
    pub data: PathBuf,
    /// The command line shown in the report.
    pub command: String,
}

/// A problem in the solve study.
#[derive(Clone, Debug, Serialize)]
pub struct ProblemInfo {
    pub name: String,
    pub file: String,
    pub energy: String,
    pub elements: usize,
    pub vertices: usize,
}

/// Everything measured (also written as `results.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Results {
    pub size: Size,
    pub command: String,
    pub machine: Machine,
    pub timing: timing::TimingResult,
    pub accuracy: accuracy::AccuracyResult,
    /// The autodiff baseline per element.
    pub autodiff: autodiff::AutodiffTiming,
    pub problems: Vec<ProblemInfo>,
    /// Each method's fastest trace (one per problem and method).
    pub traces: Vec<Trace>,
    /// The headline ratios' methods, round by round ([`rounds`]).
    pub rounds: Vec<Rounds>,
    pub solve_limits: (f64, usize, usize),
    pub scaling: Vec<ScalingRow>,
    pub scaling_iters: usize,
    /// Failures that did not stop the report (unreadable mesh, …).
    pub notes: Vec<String>,
    pub seconds: f64,
}

/// Why a report could not be written.
#[derive(Debug)]
pub enum ReportError {
    /// An energy failed to build.
    Energies(String),
    /// Writing the output folder failed.
    Io { path: String, message: String },
}

impl std::fmt::Display for ReportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReportError::Energies(m) => write!(f, "{m}"),
            ReportError::Io { path, message } => write!(f, "cannot write {path}: {message}"),
        }
    }
}

impl std::error::Error for ReportError {}

fn io(path: &Path, e: std::io::Error) -> ReportError {
    ReportError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

fn solve_limits(size: Size) -> SolveLimits {
    match size {
        Size::Full => SolveLimits {
            seconds: 30.0,
            newton_iters: 300,
            proxy_iters: 5000,
        },
        Size::Quick => SolveLimits {
            seconds: 8.0,
            newton_iters: 300,
            proxy_iters: 5000,
        },
        Size::Tiny => SolveLimits {
            seconds: 2.0,
            newton_iters: 30,
            proxy_iters: 60,
        },
    }
}

fn scaling_plan(size: Size) -> ScalingPlan {
    match size {
        Size::Full => ScalingPlan {
            tris: vec![10_000, 100_000, 300_000, 1_000_000],
            tets: vec![10_000, 30_000, 100_000, 300_000],
            direct_max_tets: 100_000,
            iters: 3,
        },
        Size::Quick => ScalingPlan {
            tris: vec![10_000, 100_000],
            tets: vec![10_000, 30_000],
            direct_max_tets: 30_000,
            iters: 2,
        },
        Size::Tiny => ScalingPlan {
            tris: vec![2_000],
            tets: vec![1_000],
            direct_max_tets: 1_000,
            iters: 1,
        },
    }
}

/// What the solve study has gathered so far.
#[derive(Default)]
struct SolveStudy {
    problems: Vec<ProblemInfo>,
    traces: Vec<Trace>,
    rounds: Vec<Rounds>,
}

impl SolveStudy {
    /// Log and keep a finished solve, or note why it failed.
    fn record<E: std::fmt::Display>(
        &mut self,
        name: &str,
        m: SolveMethod,
        result: Result<Trace, E>,
        log: &mut dyn FnMut(&str),
        notes: &mut Vec<String>,
    ) {
        match result {
            Ok(t) => {
                log(&format!(
                    "  {name} / {}: {} its, |g| {:.1e}, {:.2} s, {}",
                    m.label(),
                    t.points.len() - 1,
                    t.points.last().map_or(f64::NAN, |p| p.grad_inf),
                    t.seconds_measured,
                    t.status
                ));
                self.traces.push(t);
            }
            Err(e) => notes.push(format!("{name} / {}: {e}", m.label())),
        }
    }

    /// Every method on problem `name` (`run` solves it with a method):
    /// first `rounds` interleaved rounds of [`rounds::PAIRED`] keeping each
    /// method's fastest trace, then the others once each.
    fn run_problem(
        &mut self,
        name: &str,
        rounds: usize,
        log: &mut dyn FnMut(&str),
        notes: &mut Vec<String>,
        mut run: impl FnMut(SolveMethod) -> Result<Trace, SolveError>,
    ) {
        let mut record = Rounds::new(name);
        let mut best: Vec<(SolveMethod, Trace)> = Vec::new();
        let mut failed: Vec<SolveMethod> = Vec::new();
        for k in 0..rounds {
            for m in rounds::round_order(k) {
                if failed.contains(&m) {
                    record.push(m, None);
                    continue;
                }
                let result = run(m);
                record.push(m, result.as_ref().ok());
                match result {
                    Ok(t) => match best.iter_mut().find(|(b, _)| *b == m) {
                        Some((_, kept)) if rounds::faster(&t, kept) => *kept = t,
                        Some(_) => {}
                        None => best.push((m, t)),
                    },
                    Err(e) => {
                        failed.push(m);
                        notes.push(format!("{name} / {}: {e}", m.label()));
                    }
                }
            }
        }
        for m in [SolveMethod::DefaultsOneThread, SolveMethod::Autodiff] {
            log(&format!(
                "  {name}: {} / defaults per round {:.2?}",
                m.label(),
                record.ratios(m)
            ));
        }
        for m in rounds::PAIRED {
            if let Some(i) = best.iter().position(|(b, _)| *b == m) {
                let (_, t) = best.swap_remove(i);
                self.record::<SolveError>(name, m, Ok(t), log, notes);
            }
        }
        self.rounds.push(record);
        for m in SolveMethod::ALL {
            if !rounds::PAIRED.contains(&m) {
                let result = run(m);
                self.record(name, m, result, log, notes);
            }
        }
    }
}

/// Interleaved rounds of [`rounds::PAIRED`] per problem.
fn paired_rounds(size: Size) -> usize {
    match size {
        Size::Full => 5,
        Size::Quick => 3,
        Size::Tiny => 2,
    }
}

/// Run the solve study; failures become notes.
fn solves(cfg: &Config, log: &mut dyn FnMut(&str), notes: &mut Vec<String>) -> SolveStudy {
    let limits = solve_limits(cfg.size);
    let mut study = SolveStudy::default();
    param_solves(cfg, &limits, &mut study, log, notes);
    deform_solves(cfg, &limits, &mut study, log, notes);
    study
}

/// Symmetric Dirichlet parameterisations of the surface meshes, every method.
fn param_solves(
    cfg: &Config,
    limits: &SolveLimits,
    study: &mut SolveStudy,
    log: &mut dyn FnMut(&str),
    notes: &mut Vec<String>,
) {
    let params: &[(&str, &str)] = if cfg.size == Size::Tiny {
        &[("hand_1_i_f5000 (SD)", "hand_1_i_f5000.obj")]
    } else {
        &[
            ("camelhead (SD)", "camelhead.off"),
            ("armadillo_cut_low (SD)", "armadillo_cut_low.obj"),
            ("hand_1_i_f5000 (SD)", "hand_1_i_f5000.obj"),
        ]
    };
    for &(name, file) in params {
        let mesh = match ecc_mesh::read_tri_mesh(cfg.data.join(file)) {
            Ok(m) => m,
            Err(e) => {
                notes.push(format!("{name}: {e}"));
                continue;
            }
        };
        study.problems.push(ProblemInfo {
            name: name.into(),
            file: file.into(),
            energy: "symmetric Dirichlet (sd2.psi)".into(),
            elements: mesh.triangles.len(),
            vertices: mesh.positions.len(),
        });
        study.run_problem(name, paired_rounds(cfg.size), log, notes, |m| {
            let e: Arc<dyn ecc_runtime::Energy<2>> =
                Arc::new(ecc_energies::SymmetricDirichlet2::new());
            solve::parameterization(name, &mesh, e, m, limits)
        });
    }
}

/// ARAP and stable Neo-Hookean deformations of the hand, every method.
fn deform_solves(
    cfg: &Config,
    limits: &SolveLimits,
    study: &mut SolveStudy,
    log: &mut dyn FnMut(&str),
    notes: &mut Vec<String>,
) {
    let deform: &[(&str, &str)] = if cfg.size == Size::Tiny {
        &[]
    } else {
        &[("hand (ARAP)", "arap"), ("hand (SNH)", "snh")]
    };
    if !deform.is_empty() {
        match ecc_mesh::read_tet_mesh(cfg.data.join("hand.mesh")) {
            Err(e) => notes.push(format!("hand.mesh: {e}")),
            Ok(mesh) => {
                for &(name, which) in deform {
                    study.problems.push(ProblemInfo {
                        name: name.into(),
                        file: "hand.mesh".into(),
                        energy: if which == "arap" {
                            "ARAP (arap.psi)".into()
                        } else {
                            "stable Neo-Hookean μ=1, λ=10 (snh.psi)".into()
                        },
                        elements: mesh.tets.len(),
                        vertices: mesh.positions.len(),
                    });
                    let rounds = paired_rounds(cfg.size);
                    study.run_problem(name, rounds, log, notes, |m| {
                        let e: Arc<dyn ecc_runtime::Energy<3>> = if which == "arap" {
                            Arc::new(ecc_energies::Arap::new())
                        } else {
                            Arc::new(ecc_energies::StableNeoHookean::new())
                        };
                        solve::deformation(name, &mesh, e, m, limits)
                    });
                }
            }
        }
    }
}

/// Run every study at `cfg.size`, then write the folder. `log` receives progress lines.
pub fn run(cfg: &Config, log: &mut dyn FnMut(&str)) -> Result<Results, ReportError> {
    let t0 = std::time::Instant::now();
    let mut machine = Machine::collect();
    let mut notes = Vec::new();
    log(&format!(
        "machine: {} ({} cores), load {}",
        machine.cpu, machine.cores, machine.load_before
    ));
    let en = |e: crate::energies::EnergySetError| ReportError::Energies(e.to_string());
    log("1/3 per element: timing");
    let timing = match cfg.size {
        Size::Full => timing::run(256, 41),
        Size::Quick => timing::run(128, 11),
        Size::Tiny => timing::run_limited(8, 2, 2),
    }
    .map_err(en)?;
    log(&format!("    {:.1} s", timing.seconds));
    log("1/3 per element: accuracy (double-double reference)");
    let accuracy = match cfg.size {
        Size::Full => accuracy::run(4),
        Size::Quick => accuracy::run(2),
        Size::Tiny => accuracy::run_limited(1, 2, 3),
    }
    .map_err(en)?;
    log(&format!("    {:.1} s", accuracy.seconds));
    log("1/3 per element: autodiff baseline");
    let autodiff = match cfg.size {
        Size::Full => autodiff::run(256, 41),
        Size::Quick => autodiff::run(128, 11),
        Size::Tiny => autodiff::run(8, 2),
    }
    .map_err(en)?;
    log(&format!("    {:.1} s", autodiff.seconds));
    log("2/3 per solve");
    let study = solves(cfg, log, &mut notes);
    log("3/3 scaling");
    let plan = scaling_plan(cfg.size);
    let scaling = scaling::run(&plan, |r| {
        log(&format!(
            "  {} {} {}: {:.4} s/iter ({})",
            r.mesh, r.elements, r.solver, r.per_iter_s, r.status
        ))
    });
    machine.load_after = machine::load_average();
    let limits = solve_limits(cfg.size);
    let results = Results {
        size: cfg.size,
        command: cfg.command.clone(),
        machine,
        timing,
        accuracy,
        autodiff,
        problems: study.problems,
        traces: study.traces,
        rounds: study.rounds,
        solve_limits: (limits.seconds, limits.newton_iters, limits.proxy_iters),
        scaling,
        scaling_iters: plan.iters,
        notes,
        seconds: t0.elapsed().as_secs_f64(),
    };
    write(&results, &cfg.out)?;
    Ok(results)
}

/// Write `BENCHMARKS.md`, the PNGs and `results.json` into `out`.
pub fn write(results: &Results, out: &Path) -> Result<(), ReportError> {
    std::fs::create_dir_all(out).map_err(|e| io(out, e))?;
    for (name, png) in figures::all(results) {
        let p = out.join(&name);
        std::fs::write(&p, png).map_err(|e| io(&p, e))?;
    }
    let p = out.join("results.json");
    let json = serde_json::to_string_pretty(results).map_err(|e| ReportError::Io {
        path: p.display().to_string(),
        message: e.to_string(),
    })?;
    std::fs::write(&p, json).map_err(|e| io(&p, e))?;
    let p = out.join("BENCHMARKS.md");
    let md = markdown::render(results) + &cholmod::section(out);
    std::fs::write(&p, md).map_err(|e| io(&p, e))?;
    Ok(())
}
