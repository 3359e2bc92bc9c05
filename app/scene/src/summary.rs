//! The run summary (`summary.json`): what was simulated, which terms were
//! evaluated and what they cost, per-frame Newton statistics and physical
//! quantities, and the time split.

use std::collections::BTreeMap;

use ecc_fem::{NewtonResult, TimeSplit};
use serde::{Deserialize, Serialize};

use crate::counters::CounterValues;

/// Non-finite numbers (NaN before the first solve, ∞ outside a barrier's
/// domain) are written as JSON `null` and read back as NaN.
mod finite_or_null {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_finite() {
            s.serialize_f64(*v)
        } else {
            s.serialize_none()
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// One Newton iteration for the convergence plot.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolvePoint {
    /// ‖∇E‖∞ (scaled objective, free DOFs) at the start of the iteration
    /// (the last point of a solve: at its returned positions).
    #[serde(with = "finite_or_null")]
    pub grad_inf: f64,
    /// Scaled objective.
    #[serde(with = "finite_or_null")]
    pub energy: f64,
    /// Seconds inside Newton solves since the run's first solve started
    /// (time between solves, e.g. writing frames, is not counted).
    pub seconds: f64,
}

/// Linear-solver work (`linear` of a solve and of the run): what the
/// Newton systems cost in factorisations and CG iterations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct LinearWork {
    /// Symbolic analyses (orderings + elimination trees) of the Cholesky
    /// factor, including one `auto` ran and discarded for PCG. Run total
    /// only (0 in a solve's entry: the analysis belongs to the solver).
    pub symbolic_analyses: usize,
    /// Numeric Cholesky factorisations, shift retries included (≤ Newton
    /// iterations × `shift_attempts` plus one per failed PCG attempt of
    /// `auto`; 0 for `pcg`).
    pub numeric_factorizations: usize,
    /// CG iterations (PCG steps, `auto`'s PCG attempts, stale-factor CG).
    pub cg_iterations: usize,
    /// Newton steps solved with CG preconditioned by a stale factor.
    pub reused_factor_steps: usize,
    /// The Cholesky factor's thread policy (`[solver] threads`); run total
    /// only, absent without a Cholesky factor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub threads: Option<ecc_fem::linear::cholesky::ThreadPolicy>,
    /// The Cholesky factor's fill-reducing ordering (`[solver] ordering`);
    /// run total only, absent without a Cholesky factor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ordering: Option<ecc_fem::linear::ordering::FillOrdering>,
    /// Whether the policy split the factorisation over two threads (`split`
    /// on a two-thread pool, when the symbolic analysis estimates it pays);
    /// run total only, absent without a Cholesky factor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split: Option<bool>,
    /// The precision of the factor at the end of the run (`[solver]
    /// precision`): `mixed` for a split factor kept in single precision,
    /// `double` otherwise (not split, asked so, or fallen back to double);
    /// run total only, absent without a Cholesky factor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<ecc_fem::linear::cholesky::FactorPrecision>,
}

impl LinearWork {
    /// The factorisations, CG iterations and reused steps of one solve's
    /// accepted Newton steps (`symbolic_analyses` 0: see the field).
    pub fn of_solve(r: &NewtonResult) -> Self {
        LinearWork {
            symbolic_analyses: 0,
            numeric_factorizations: r.records.iter().map(|s| s.factorizations).sum(),
            cg_iterations: r.records.iter().map(|s| s.cg_iterations).sum(),
            reused_factor_steps: r.records.iter().filter(|s| s.reused_factor).count(),
            ..LinearWork::default()
        }
    }

    /// The run's totals: the solves' sums, and the symbolic analyses of
    /// the solver (`NewtonResult::symbolic_analyses` of the last solve).
    pub fn of_run(solves: &[SolveLog], symbolic_analyses: usize) -> Self {
        let mut w = LinearWork {
            symbolic_analyses,
            ..LinearWork::default()
        };
        for s in solves {
            w.numeric_factorizations += s.linear.numeric_factorizations;
            w.cg_iterations += s.linear.cg_iterations;
            w.reused_factor_steps += s.linear.reused_factor_steps;
        }
        w
    }

    /// With the thread policy, ordering and split of `system`'s Cholesky
    /// factor, if it has one.
    pub fn with_factor(mut self, system: &ecc_fem::linear::LinearSystem) -> Self {
        if let Some(f) = system.cholesky() {
            self.threads = Some(f.params().threads);
            self.ordering = Some(f.params().ordering);
            self.split = Some(f.split().is_some());
            self.precision = Some(f.precision());
        }
        self
    }
}

/// One Newton solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveLog {
    /// The frame it belongs to.
    pub frame: usize,
    /// Newton status name.
    pub status: String,
    /// Newton steps.
    pub iterations: usize,
    /// Iterates (iterations + 1 points).
    pub points: Vec<SolvePoint>,
    /// Assembly / factorisation / solve / line-search seconds.
    pub times: TimeSplit,
    /// Factorisations and CG iterations of this solve.
    #[serde(default)]
    pub linear: LinearWork,
}

/// One output frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameStats {
    /// Frame number (0 = initial state).
    pub frame: usize,
    /// Simulated time (dynamics).
    pub time: Option<f64>,
    /// Interpolation parameter t (interpolation).
    pub t: Option<f64>,
    /// Newton solves in this frame.
    pub solves: usize,
    /// Newton iterations summed over the frame's solves.
    pub iterations: usize,
    /// Distinct statuses of the frame's solves.
    pub statuses: Vec<String>,
    /// Every solve converged.
    pub converged: bool,
    /// ‖∇E‖∞ at the end of the last solve.
    #[serde(with = "finite_or_null")]
    pub grad_inf: f64,
    /// Σ|q|Ψ (the blended energy for interpolation; unscaled).
    #[serde(with = "finite_or_null")]
    pub elastic_energy: f64,
    /// −Σ m_v g·x_v.
    pub gravity_potential: Option<f64>,
    /// Ground barrier / penalty energy.
    pub contact_energy: Option<f64>,
    /// ½ vᵀMv.
    pub kinetic_energy: Option<f64>,
    /// Sum of the above.
    #[serde(with = "finite_or_null")]
    pub total_energy: f64,
    /// Smallest signed element measure (area / volume).
    #[serde(with = "finite_or_null")]
    pub min_measure: f64,
    /// Elements with signed measure ≤ 0.
    pub inverted: usize,
    /// Smallest vertex distance to the ground.
    pub min_ground_distance: Option<f64>,
    /// Largest distance between a handle vertex and its target.
    pub handle_error: Option<f64>,
    /// Wall seconds for the frame.
    pub seconds: f64,
}

/// Cost of one term over the whole run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TermStats {
    /// Term name.
    pub name: String,
    /// Stencils (elements, vertices, …).
    pub stencils: usize,
    /// Value-only passes (line search).
    pub value_passes: usize,
    /// Gradient + Hessian passes.
    pub assembly_passes: usize,
    /// Seconds in this term.
    pub seconds: f64,
}

/// The mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshStats {
    /// File path or generator.
    pub source: String,
    /// "planar triangle", "surface triangle" or "tetrahedral".
    pub kind: String,
    /// Vertices (after dropping unreferenced ones).
    pub vertices: usize,
    /// Elements.
    pub elements: usize,
    /// Σ|q| at rest.
    pub rest_measure: f64,
}

/// The energy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnergyStats {
    /// Its name.
    pub name: String,
    /// Parameter values in use.
    pub params: BTreeMap<String, f64>,
    /// Barrier energy (inversion-free line search).
    pub barrier: bool,
}

/// A handle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandleStats {
    /// Label.
    pub name: String,
    /// Number of vertices.
    pub vertices: usize,
    /// Keyframes (0 = pinned).
    pub keys: usize,
}

/// Everything about a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Scene name.
    pub scene: String,
    /// Scene file.
    pub scene_file: String,
    /// "quasi_static", "dynamic", "interpolation" or "parameterization".
    pub mode: String,
    /// The element Hessian projection (`[solver] projection`): "f-space",
    /// "element" or "hybrid".
    pub projection: String,
    /// The mesh.
    pub mesh: MeshStats,
    /// The energy.
    pub energy: EnergyStats,
    /// The fibre energy ψ(I4, I5) of the fibre term (`[fibers] energy`, or
    /// the fibre part of `[energy] psi`; `barrier` is false); absent without
    /// a fibre term (additive key).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fibre_energy: Option<EnergyStats>,
    /// Effects the scene names.
    pub effects: Vec<String>,
    /// Terms in the objective and their cost (exactly the assembled ones).
    pub terms: Vec<TermStats>,
    /// Proof of what ran: mass matrix builds, contact passes, …
    pub counters: CounterValues,
    /// Handles.
    pub handles: Vec<HandleStats>,
    /// Per-frame statistics (frame 0 = initial state).
    pub frames: Vec<FrameStats>,
    /// Every Newton solve (convergence history).
    pub solves: Vec<SolveLog>,
    /// Newton iterations over the run.
    pub newton_iterations: usize,
    /// Linear-solver work over the run (symbolic analyses, numeric
    /// factorisations, CG iterations, reused-factor steps).
    #[serde(default)]
    pub linear: LinearWork,
    /// Frames whose solves all converged.
    pub converged_frames: usize,
    /// Why the run stopped early, if it did.
    pub stopped: Option<String>,
    /// How the run ended: `converged` (every frame), `unconverged` (it
    /// reached the last frame, but some solve stopped at `max_iters` or
    /// another limit) or `stopped` (see `stopped`).
    pub status: RunStatus,
    /// Scaled objective at the end.
    #[serde(with = "finite_or_null")]
    pub final_energy: f64,
    /// Seconds: reading and building.
    pub setup_seconds: f64,
    /// Seconds: all Newton solves, split by phase.
    pub newton: TimeSplit,
    /// Seconds: writing frames, pictures and the summary.
    pub output_seconds: f64,
    /// Seconds: the whole run.
    pub wall_seconds: f64,
    /// Files written (relative to the output folder).
    pub outputs: Vec<String>,
    /// Warnings (mesh validation notes, non-converged frames).
    pub warnings: Vec<String>,
}

/// How a scene run ended (`status` in `summary.json`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// Every frame's solves converged.
    Converged,
    /// The run reached its last frame but some frames did not converge.
    Unconverged,
    /// The run stopped before its last frame.
    Stopped,
}

impl RunStatus {
    /// The status of a run with `converged` of `frames` frames converged.
    pub fn of(stopped: bool, converged: usize, frames: usize) -> Self {
        if stopped {
            RunStatus::Stopped
        } else if converged < frames {
            RunStatus::Unconverged
        } else {
            RunStatus::Converged
        }
    }
}

impl Summary {
    /// Sum the phase times of `solves`.
    pub fn newton_split(solves: &[SolveLog]) -> TimeSplit {
        let mut t = TimeSplit::default();
        for s in solves {
            t.assembly += s.times.assembly;
            t.factor += s.times.factor;
            t.solve += s.times.solve;
            t.line_search += s.times.line_search;
            t.total += s.times.total;
        }
        t
    }

    /// Human-readable `--stats` table: terms and their cost, counters, time split.
    pub fn stats_table(&self) -> String {
        let mut s = String::new();
        s.push_str("terms evaluated (exactly those the scene names):\n");
        s.push_str(&format!(
            "  {:<20} {:>9} {:>10} {:>10} {:>10}\n",
            "term", "stencils", "value", "assembly", "seconds"
        ));
        for t in &self.terms {
            s.push_str(&format!(
                "  {:<20} {:>9} {:>10} {:>10} {:>10.3}\n",
                t.name, t.stencils, t.value_passes, t.assembly_passes, t.seconds
            ));
        }
        let c = &self.counters;
        s.push_str(&format!(
            "mass matrix builds: {}   stiffness snapshots: {}   contact passes: {}\n",
            c.mass_matrix_builds, c.stiffness_snapshots, c.contact_passes
        ));
        let n = &self.newton;
        s.push_str(&format!(
            "newton: {} iterations, {:.3} s (assembly {:.3}, factor {:.3}, solve {:.3}, line search {:.3})\n",
            self.newton_iterations, n.total, n.assembly, n.factor, n.solve, n.line_search
        ));
        let l = &self.linear;
        s.push_str(&format!(
            "linear: {} symbolic analyses, {} numeric factorisations, {} CG iterations, {} reused-factor steps\n",
            l.symbolic_analyses, l.numeric_factorizations, l.cg_iterations, l.reused_factor_steps
        ));
        s.push_str(&format!(
            "setup {:.3} s, output {:.3} s, wall {:.3} s\n",
            self.setup_seconds, self.output_seconds, self.wall_seconds
        ));
        s
    }
}
