//! `BENCHMARKS.md`: tables, figure links and the method notes.

use std::fmt::Write;

use super::figures::{mean_ratio, slug, worst_err};
use super::{Results, Size};
use crate::cases::CLASSES;
use crate::element::Method;
use crate::solve::{SolveMethod, THRESHOLDS, Trace};

fn e(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.is_finite() {
        format!("{x:.1e}")
    } else {
        "∞".into()
    }
}

fn secs(x: Option<f64>) -> String {
    match x {
        Some(s) if s < 10.0 => format!("{s:.2} s"),
        Some(s) => format!("{s:.1} s"),
        None => "—".into(),
    }
}

fn header(out: &mut String, cols: &[String]) {
    let _ = writeln!(out, "| {} |", cols.join(" | "));
    let _ = writeln!(out, "|{}", "---|".repeat(cols.len()));
}

fn trace<'a>(r: &'a Results, problem: &str, m: SolveMethod) -> Option<&'a Trace> {
    r.traces
        .iter()
        .find(|t| t.problem == problem && t.method == m)
}

/// The interleaved rounds of `problem` ([`super::rounds`]), if it has them.
fn rounds_of<'a>(r: &'a Results, problem: &str) -> Option<&'a super::rounds::Rounds> {
    r.rounds.iter().find(|t| t.problem == problem)
}

/// Ratio of time-to-tol of method `a` over method `b` on `problem`, if both reached it.
fn solve_ratio(
    r: &Results,
    problem: &str,
    a: SolveMethod,
    b: SolveMethod,
    tol: f64,
) -> Option<f64> {
    Some(trace(r, problem, a)?.time_to(tol)? / trace(r, problem, b)?.time_to(tol)?)
}

/// Method `m`'s time over the defaults' on `problem`: the median of the
/// interleaved rounds' ratios ([`super::rounds`]), or the kept traces'
/// ratio for results without rounds.
fn paired_ratio(r: &Results, problem: &str, m: SolveMethod) -> Option<f64> {
    rounds_of(r, problem)
        .and_then(|t| t.median_ratio(m))
        .or_else(|| solve_ratio(r, problem, m, SolveMethod::Defaults, 1e-4))
}

/// [`paired_ratio`] as a cell: `1.45× (1.21, 1.68, 1.45)`, every round's
/// ratio in brackets; `—` without one.
fn paired_cell(r: &Results, problem: &str, m: SolveMethod) -> String {
    let Some(x) = paired_ratio(r, problem, m) else {
        return "—".into();
    };
    let each: Vec<String> = rounds_of(r, problem)
        .map(|t| t.ratios(m).iter().map(|x| format!("{x:.2}")).collect())
        .unwrap_or_default();
    if each.is_empty() {
        format!("{x:.2}×")
    } else {
        format!("{x:.2}× ({})", each.join(", "))
    }
}

/// Rounds per problem of [`paired_ratio`] (1 for results without rounds).
fn n_rounds(r: &Results) -> usize {
    r.rounds.first().map_or(1, |t| t.len())
}

/// The headline bullets: per-element speed-ups, accuracy, the
/// parameterisation solves and the largest scaling runs.
fn headline(r: &Results, out: &mut String) {
    let _ = writeln!(out, "## Headline numbers\n");
    per_element_headline(r, out);
    accuracy_headline(r, out);
    solve_headline(r, out);
    scaling_headline(r, out);
    let _ = writeln!(out);
}

/// Per dimension: geometric-mean speed-up of the analytic projected Hessian
/// over the numeric projections, and the interpreted energy's cost.
fn per_element_headline(r: &Results, out: &mut String) {
    for d in [3, 2] {
        let (ne, nf) = (d * (d + 1), d * d);
        let range = |m: Method| {
            let v: Vec<f64> = r
                .timing
                .rows
                .iter()
                .filter(|x| x.dim == d && x.method == m)
                .map(|x| x.ratio)
                .collect();
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(0.0, f64::max);
            (lo, hi)
        };
        if let (Some(r12), Some(r9), Some(ri)) = (
            mean_ratio(r, Method::NumericElement, d),
            mean_ratio(r, Method::NumericF, d),
            mean_ratio(r, Method::Interpreted, d),
        ) {
            let (lo, hi) = range(Method::NumericElement);
            let _ = writeln!(
                out,
                "* **{d}D, per element:** the analytic projected Hessian (generated code) is **{r12:.1}×** faster than numeric {ne}×{ne} element projection \
                 (geometric mean over the energies, {lo:.1}–{hi:.1}×) and **{r9:.1}×** faster than numeric {nf}×{nf} F-projection; \
                 the run-time interpreted energy (`ecc eval` path) costs {ri:.2}× the generated one."
            );
        }
    }
}

/// The worst relative Hessian error of each method over 2D and 3D.
fn accuracy_headline(r: &Results, out: &mut String) {
    let errs: Vec<String> = [
        Method::Analytic,
        Method::NumericF,
        Method::NumericElement,
        Method::GenericF32,
    ]
    .iter()
    .filter_map(|&m| {
        let w = [2, 3]
            .iter()
            .filter_map(|&d| worst_err(r, m, d))
            .reduce(f64::max)?;
        Some(format!(
            "{} {}",
            m.label(3).replace("9×9 ", "").replace("12×12 ", ""),
            e(w)
        ))
    })
    .collect();
    if !errs.is_empty() {
        let _ = writeln!(
            out,
            "* **Accuracy** (worst relative Hessian error over every energy and every random/hard case, 2D and 3D): {}.",
            errs.join(", ")
        );
    }
}

/// Time to ‖∇E‖∞ ≤ 1e-4 of every method on each parameterisation problem,
/// then the two-thread and autodiff ratios of the defaults on every problem.
fn solve_headline(r: &Results, out: &mut String) {
    for p in r.problems.iter().filter(|p| p.name.contains("(SD)")) {
        let t = |m| trace(r, &p.name, m).and_then(|t| t.time_to(1e-4));
        let _ = writeln!(
            out,
            "* **Parameterisation, {} ({} triangles), time to ‖∇E‖∞ ≤ 1e-4:** ecc defaults {}, analytic clamp {}, abs {}, adaptive {}, numeric element projection {}, Laplacian proxy {}, autodiff baseline {}.{}",
            p.name,
            p.elements,
            secs(t(SolveMethod::Defaults)),
            secs(t(SolveMethod::Clamp)),
            secs(t(SolveMethod::Abs)),
            secs(t(SolveMethod::Adaptive)),
            secs(t(SolveMethod::NumericProjection)),
            secs(t(SolveMethod::LaplacianProxy)),
            secs(t(SolveMethod::Autodiff)),
            paired_ratio(r, &p.name, SolveMethod::Autodiff).map_or(String::new(), |x| format!(
                " Autodiff/defaults: {x:.2}× (median of {} rounds).",
                n_rounds(r)
            ))
        );
    }
    let range = |m: SolveMethod| {
        let v: Vec<(f64, &str)> = r
            .problems
            .iter()
            .filter_map(|p| Some((paired_ratio(r, &p.name, m)?, p.name.as_str())))
            .collect();
        let lo = v.iter().min_by(|x, y| x.0.total_cmp(&y.0))?;
        let hi = v.iter().max_by(|x, y| x.0.total_cmp(&y.0))?;
        Some(format!(
            "{:.2}× ({}) to {:.2}× ({})",
            lo.0, lo.1, hi.0, hi.1
        ))
    };
    if let Some(x) = range(SolveMethod::DefaultsOneThread) {
        let _ = writeln!(
            out,
            "* **Two threads against one, per solve** (ecc defaults, time to 1e-4, median of {} interleaved rounds): {x}.",
            n_rounds(r)
        );
    }
    if let Some(x) = range(SolveMethod::Autodiff) {
        let _ = writeln!(
            out,
            "* **Autodiff baseline against ecc's defaults, per solve** (time to 1e-4, median of {} interleaved rounds): {x}.",
            n_rounds(r)
        );
    }
}

/// Issue #11's per-solve criteria, read off the traces of section 2.
fn targets_table(r: &Results, out: &mut String) {
    let _ = writeln!(
        out,
        "### Summary: defaults, threads, autodiff\n\nPer problem, from the rows below: iterations to 1e-4 of the ecc defaults and of \
         numeric per-element projection (the criterion: defaults ≤ 1.05 × numeric); time to 1e-4 of the defaults on one and on two threads, and of \
         the autodiff baseline (forward-mode second derivatives + numeric element projection + Cholesky, what TinyAD does). These three run in {} \
         interleaved rounds, the order rotating so each runs first in turn: times are each method's fastest round, ratios the median of the \
         per-round ratios, every round's ratio in brackets. — : not reached, or no autodiff form for that energy.\n",
        n_rounds(r)
    );
    header(
        out,
        &[
            "problem".into(),
            "elements".into(),
            "iterations: defaults / numeric proj.".into(),
            "time: 1 thread / 2 threads".into(),
            "1 thread ÷ 2 threads".into(),
            "autodiff time".into(),
            "autodiff ÷ defaults".into(),
        ],
    );
    for p in &r.problems {
        let it = |m| trace(r, &p.name, m).and_then(|t| t.iters_to(1e-4));
        let tt = |m| trace(r, &p.name, m).and_then(|t| t.time_to(1e-4));
        let iters = |m| it(m).map_or("—".into(), |i: usize| i.to_string());
        let _ = writeln!(
            out,
            "| {} | {} | {} / {} | {} / {} | {} | {} | {} |",
            p.name,
            p.elements,
            iters(SolveMethod::Defaults),
            iters(SolveMethod::NumericProjection),
            secs(tt(SolveMethod::DefaultsOneThread)),
            secs(tt(SolveMethod::Defaults)),
            paired_cell(r, &p.name, SolveMethod::DefaultsOneThread),
            secs(tt(SolveMethod::Autodiff)),
            paired_cell(r, &p.name, SolveMethod::Autodiff),
        );
    }
    let _ = writeln!(out);
}

/// Seconds per iteration at the largest size of each (mesh, solver).
fn scaling_headline(r: &Results, out: &mut String) {
    let big = |mesh: &str, solver: &str| {
        r.scaling
            .iter()
            .filter(|x| x.mesh == mesh && x.solver == solver)
            .max_by_key(|x| x.elements)
    };
    let mut parts = Vec::new();
    for mesh in ["tri (SD)", "tet (SNH)"] {
        for solver in ["Cholesky", "Pcg"] {
            if let Some(x) = big(mesh, solver) {
                parts.push(format!(
                    "{} {} {}: {:.2} s/iteration",
                    x.elements, mesh, solver, x.per_iter_s
                ));
            }
        }
    }
    if !parts.is_empty() {
        let _ = writeln!(out, "* **Scaling** (largest sizes): {}.", parts.join("; "));
    }
}

/// Section 1: per-element time and accuracy tables, the reference's own
/// error, and the trade-off figures.
fn element_section(r: &Results, out: &mut String) {
    let _ = writeln!(
        out,
        "## 1. Per element\n\nEnergy, gradient and projected Hessian of one element (triangle: 6×6, tet: 12×12), \
         {} random elements × {} interleaved rounds. Cells: fastest round in ns per element, and in parentheses the median over rounds of the ratio \
         to the analytic kernel measured in the same round. The generic-kernel rows are this crate's precision-generic copy of the kernel (dense, \
         allocating): compare f32 with f64 *within* it, not with the runtime.\n",
        r.timing.batch, r.timing.rounds
    );
    for d in [2, 3] {
        timing_table(r, out, d);
    }
    let _ = writeln!(
        out,
        "### Accuracy\n\nWorst relative Hessian error max|H − H_ref|/max|H_ref| against the double-double reference, {} sample(s) per class \
         (random rotations), element rest shape fixed. Each method is compared with the exact version of what it computes: \
         F-space projection m·Bᵀ P(∇²Ψ) B for the analytic, interpreted, numeric F-projection and generic kernels; element projection \
         P(m·Bᵀ ∇²Ψ B) for the numeric element projection; the raw m·Bᵀ ∇²Ψ B for the unprojected Hessian. \
         — : class not in the energy's domain (barrier energies and det F ≤ 0).\n",
        r.accuracy.samples_per_class
    );
    for d in [2, 3] {
        if !r.accuracy.rows.iter().any(|x| x.dim == d) {
            continue;
        }
        let cols = accuracy_by_class(r, out, d);
        accuracy_by_energy(r, out, d, &cols);
    }
    reference_error(r, out);
    let _ = writeln!(
        out,
        "![2D trade-off](element_tradeoff_2d.png)\n\n![3D trade-off](element_tradeoff_3d.png)\n"
    );
}

/// The time-per-element table of dimension `d` (nothing when it has no rows).
fn timing_table(r: &Results, out: &mut String, d: usize) {
    let energies: Vec<&str> = {
        let mut v: Vec<&str> = r
            .timing
            .rows
            .iter()
            .filter(|x| x.dim == d)
            .map(|x| x.energy.as_str())
            .collect();
        v.dedup();
        v
    };
    if energies.is_empty() {
        return;
    }
    let _ = writeln!(out, "### {d}D time per element\n");
    let mut cols = vec!["energy".to_string()];
    cols.extend(Method::ALL.iter().map(|m| m.label(d)));
    header(out, &cols);
    for en in energies {
        let mut row = vec![en.to_string()];
        for m in Method::ALL {
            let cell = r
                .timing
                .rows
                .iter()
                .find(|x| x.dim == d && x.energy == en && x.method == m)
                .map_or("—".into(), |x| {
                    format!("{:.0} ns ({:.2}×)", x.ns, x.ratio)
                });
            row.push(cell);
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    let _ = writeln!(out);
}

/// The worst Hessian error over energies, by case class, in dimension `d`;
/// returns the table's columns.
fn accuracy_by_class(r: &Results, out: &mut String, d: usize) -> Vec<String> {
    let _ = writeln!(out, "#### {d}D, worst over energies, by case class\n");
    let mut cols = vec!["case".to_string()];
    cols.extend(Method::ALL.iter().map(|m| m.label(d)));
    header(out, &cols);
    for c in CLASSES {
        let rows: Vec<_> = r
            .accuracy
            .rows
            .iter()
            .filter(|x| x.dim == d && x.class == c.name && x.samples > 0)
            .collect();
        if rows.is_empty() {
            continue;
        }
        let mut row = vec![c.name.to_string()];
        for m in Method::ALL {
            let w = rows
                .iter()
                .filter(|x| x.method == m)
                .map(|x| x.hess_err)
                .reduce(f64::max);
            row.push(w.map_or("—".into(), e));
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    cols
}

/// The worst Hessian / gradient error over case classes, by energy, in
/// dimension `d` (`cols` as in the by-class table).
fn accuracy_by_energy(r: &Results, out: &mut String, d: usize, cols: &[String]) {
    let _ = writeln!(
        out,
        "\n#### {d}D, worst over case classes, by energy (Hessian / gradient)\n"
    );
    header(
        out,
        &cols
            .iter()
            .enumerate()
            .map(|(i, c)| if i == 0 { "energy".into() } else { c.clone() })
            .collect::<Vec<_>>(),
    );
    let mut energies: Vec<&str> = r
        .accuracy
        .rows
        .iter()
        .filter(|x| x.dim == d)
        .map(|x| x.energy.as_str())
        .collect();
    energies.dedup();
    for en in energies {
        let mut row = vec![en.to_string()];
        for m in Method::ALL {
            let rows = r
                .accuracy
                .rows
                .iter()
                .filter(|x| x.dim == d && x.energy == en && x.method == m && x.samples > 0);
            let (h, g) = rows.fold((0.0f64, 0.0f64), |a, x| {
                (a.0.max(x.hess_err), a.1.max(x.grad_err))
            });
            row.push(format!("{} / {}", e(h), e(g)));
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    let _ = writeln!(out);
}

/// The reference's own error estimate (worst over the accuracy study).
fn reference_error(r: &Results, out: &mut String) {
    let worst_ref = r
        .accuracy
        .refs
        .iter()
        .map(|x| x.hess_self_err)
        .fold(0.0, f64::max);
    let worst_gref = r
        .accuracy
        .refs
        .iter()
        .map(|x| x.grad_self_err)
        .fold(0.0, f64::max);
    let worst_ref_row = r
        .accuracy
        .refs
        .iter()
        .max_by(|a, b| a.hess_self_err.total_cmp(&b.hess_self_err));
    let _ = writeln!(
        out,
        "The reference's own error estimate (disagreement of neighbouring Richardson estimates, relative): Hessian ≤ {}, gradient ≤ {}{}.\n",
        e(worst_ref),
        e(worst_gref),
        worst_ref_row.map_or(String::new(), |x| format!(
            " (worst: {}D {} at {})",
            x.dim, x.energy, x.class
        ))
    );
}

fn autodiff_section(r: &Results, out: &mut String) {
    let a = &r.autodiff;
    if a.rows.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "### Autodiff baseline\n\nWhat TinyAD does, written in Rust: the element energy |q| ψ(Ds Dm⁻¹) as a function of the node coordinates \
         (6 in 2D, 12 in 3D) evaluated in forward-mode second-order dual numbers with static size (`num-dual` `Dual2SVec64`), then the \
         numeric projection of the dense element Hessian (nalgebra `SymmetricEigen`, eigenvalues clamped). Energies without an SVD-free \
         form (3D ARAP; ARAP 2D uses the closed-form 2×2 polar factor) have no row. Same batches and interleaved timing as above \
         ({} elements, {} rounds; fastest round, median per-round ratio). *raw Hessian agreement*: worst max|H_ad − H_ecc| / max|H_ecc| of \
         the unprojected element Hessians over the batch (the two compute the same derivative).\n",
        a.batch, a.rounds
    );
    header(
        out,
        &[
            "dim".into(),
            "energy".into(),
            "analytic (ns)".into(),
            "analytic raw + numeric proj. (ns)".into(),
            "autodiff + numeric proj. (ns)".into(),
            "autodiff raw (ns)".into(),
            "autodiff / analytic".into(),
            "raw Hessian agreement".into(),
        ],
    );
    for x in &a.rows {
        let _ = writeln!(
            out,
            "| {}D | {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.1}× | {} |",
            x.dim,
            x.energy,
            x.analytic_ns,
            x.numeric_ns,
            x.autodiff_ns,
            x.autodiff_raw_ns,
            x.ratio,
            e(x.max_rel_diff)
        );
    }
    let _ = writeln!(out);
}

fn solve_section(r: &Results, out: &mut String) {
    let (limit, newton, proxy) = r.solve_limits;
    let _ = writeln!(
        out,
        "## 2. Per solve\n\nProjected Newton (Armijo backtracking, inversion-free for barrier energies) from the same start with \
         each way of building the system. *ecc defaults* is what `ecc sim` runs: the default projection `auto` (F-space on parameterisations, \
         whose trust-region Newton policy ends in raw-Hessian steps, and on tets), `linear = \"auto\"` (Cholesky on all of these meshes), \
         the split two-thread Cholesky with the `auto` ordering (block AMD at these sizes), the default factor reuse (the step after a \
         factorisation tries CG preconditioned by it where a factorisation is dear: hand.mesh here), and on parameterisations trust-region \
         Newton; *ecc defaults, 1 thread* is the same in a one-thread pool. Every other row uses faer Cholesky on two threads (split), \
         a factorisation at every Newton step (as TinyAD), the fixed filter and F-space projection. Each run stops at ‖∇E‖∞ ≤ 1e-8, after {newton} iterations ({proxy} for the proxy) or after {limit:.0} s. \
         Times are the solver's own per-iteration records (assembly + factorisation + solve + line search; setup excluded). \
         The proxy's constant Hessian is counted as factorised once. — : threshold not reached.\n"
    );
    targets_table(r, out);
    for p in &r.problems {
        let _ = writeln!(
            out,
            "### {}\n\n`{}`, {} elements, {} vertices, {}.\n",
            p.name, p.file, p.elements, p.vertices, p.energy
        );
        let mut cols: Vec<String> = vec![
            "method".into(),
            "iterations".into(),
            "final ‖∇E‖∞".into(),
            "stop".into(),
        ];
        cols.extend(THRESHOLDS.iter().map(|t| format!("time to {}", e(*t))));
        cols.push("iterations to 1e-4".into());
        header(out, &cols);
        for m in SolveMethod::ALL {
            let Some(t) = trace(r, &p.name, m) else {
                continue;
            };
            let last = t.points.last();
            let mut row = vec![
                m.label().to_string(),
                format!("{}", last.map_or(0, |p| p.iter)),
                last.map_or("—".into(), |p| e(p.grad_inf)),
                t.status.clone(),
            ];
            row.extend(THRESHOLDS.iter().map(|&tol| secs(t.time_to(tol))));
            row.push(t.iters_to(1e-4).map_or("—".into(), |i| i.to_string()));
            let _ = writeln!(out, "| {} |", row.join(" | "));
        }
        let s = slug(&p.name);
        let _ = writeln!(
            out,
            "\n![{} by iteration](solve_{s}_iter.png)\n\n![{} by time](solve_{s}_time.png)\n",
            p.name, p.name
        );
    }
}

fn scaling_section(r: &Results, out: &mut String) {
    if r.scaling.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "## 3. Scaling\n\nMean time per projected Newton iteration over {} iteration(s) (tolerance 0), analytic clamp. Triangles: unit-square grid, \
         symmetric Dirichlet, edges x = 0 and x = 1 fixed, x = 1 pulled to 1.5. Tets: unit cube, stable Neo-Hookean, faces x = 0 and x = 1 fixed, \
         x = 1 twisted 30°. PCG is Jacobi-preconditioned with an inexact-Newton forcing term.\n",
        r.scaling_iters
    );
    header(
        out,
        &[
            "mesh",
            "elements",
            "unknowns",
            "solver",
            "s / iteration",
            "assembly",
            "factor",
            "solve",
            "line search",
            "CG its / iteration",
            "factor MB",
            "setup s",
            "status",
        ]
        .map(String::from),
    );
    for x in &r.scaling {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} | {:.0} | {:.2} | {} |",
            x.mesh,
            x.elements,
            x.unknowns,
            x.solver,
            x.per_iter_s,
            x.assembly_s,
            x.factor_s,
            x.solve_s,
            x.line_search_s,
            x.cg_per_iter,
            x.factor_mb,
            x.setup_s,
            x.status
        );
    }
    let _ = writeln!(out, "\n![scaling](scaling.png)\n");
}

const METHODS: &str = "## How it is measured

* **Per-element methods.** *analytic*: `tri_eval`/`tet_eval` with the generated energy (ecc-energies) and `Filter::Clamp` — signed SVD, \
closed-form eigenvalues, modal Hessian. *interpreted*: the same kernel with the energy compiled from its `.psi` text at run time (ecc-interp, what `ecc eval` runs). \
*numeric F-projection*: raw d²×d² F-space Hessian (analytic) → nalgebra `SymmetricEigen` → clamp → dense m·Bᵀ P B with a precomputed B. \
*numeric element projection*: raw element Hessian (`Filter::None`) → nalgebra `SymmetricEigen` of the 6×6/12×12 → clamp. *unprojected*: `Filter::None`. \
*generic kernel f64/f32*: a precision-generic re-implementation in this crate (Jacobi SVD, stretch derivatives from the CAS graph, divided differences with a \
u^{1/3} switch to the symmetric limit, dense chain rule), run in f32 (inputs rounded to f32) and f64 — the runtime is f64-only, so this is how f32 is measured. \
All energies are called through `dyn Energy`.
* **Reference.** Central differences of Ψ(F) in double-double arithmetic (≈ 32 digits): Ψ from the energy's CAS graph of Ψ alone (no derivative the DSL derived), \
σ from a double-double Jacobi SVD (σ_last = det F/Π others), steps 0.05·s·2⁻ᵏ (s = smallest of ‖F‖, |σᵢ|, |σᵢ+σⱼ|), two Richardson levels, the estimate whose neighbours \
agree best; element quantities by the exact chain rule and projections by a double-double Jacobi eigensolver. The projection onto the PSD cone is 1-Lipschitz, so the \
projected references are as accurate as the raw one.
* **Hard cases.** rest (F = I exactly), uniform scale, repeated σ, σ differing by 1e-9, σᵢ+σⱼ ≈ 0 (1e-7 off; ARAP has a genuine pole there), σ = 1e-6, inverted, \
σ = 1e3, each under random rotations; random F = I + U(−½, ½), ⅛ inverted. Barrier energies skip det F ≤ 0.
* **Timing.** Ratios are measured interleaved in one run (every round runs each method once over the same batch); absolute times depend on the machine's load. \
Per solve, the defaults on two threads, on one thread and the autodiff baseline run in interleaved rounds (the order rotating, so each runs first in turn, \
as a cold first solve is slower than later ones): their times are each one's fastest round, their ratios the median of the per-round ratios. \
Every other method is one solve.
* **Solve methods.** *analytic clamp / abs*: fixed filter max(λ, 0) / |λ|. *adaptive*: `FilterPolicy::TrustRegion` (Chen et al. 2024): clamp when the previous \
step's ρ = actual/predicted decrease satisfies |ρ − 1| < 0.01, abs otherwise. *numeric element projection*: the same solver with each element's raw Hessian projected by \
nalgebra `SymmetricEigen` (a term wrapper). *Laplacian proxy*: constant per-element H = 2|q|BᵀB (F-Hessian 2I: the rest-mesh Laplacian per coordinate, as in AQP and the \
ARAP global step) with the real energy and gradient and the same line search.
";

/// The whole document.
pub fn render(r: &Results) -> String {
    let mut out = String::new();
    let m = &r.machine;
    let _ = writeln!(out, "# ecc benchmarks: what accuracy costs in time\n");
    let size = match r.size {
        Size::Full => "full",
        Size::Quick => "quick",
        Size::Tiny => "tiny (smoke test)",
    };
    let _ = writeln!(
        out,
        "Generated by `{}` (size: {size}) in {:.1} min. Every number below comes from that one run; raw data in [`results.json`](results.json).\n",
        r.command,
        r.seconds / 60.0
    );
    header(&mut out, &["machine".to_string(), String::new()]);
    for (k, v) in [
        ("CPU", m.cpu.clone()),
        ("cores (threads used)", m.cores.to_string()),
        ("memory", m.memory.clone()),
        ("rustc", m.rustc.clone()),
        ("date", m.date_utc.clone()),
        ("git commit", m.commit.clone()),
        (
            "load average 1/5/15 min, before → after",
            format!("{} → {}", m.load_before, m.load_after),
        ),
    ] {
        let _ = writeln!(out, "| {k} | {v} |");
    }
    let busy = m
        .load_before
        .split_whitespace()
        .next()
        .and_then(|x| x.parse::<f64>().ok())
        .unwrap_or(0.0);
    if busy > 0.5 * m.cores as f64 {
        let _ = writeln!(
            out,
            "\n**Note:** the machine was not idle when the run started (1-minute load {busy:.2} on {} cores: other work was running). Absolute times are \
             inflated and noisy; the ratios, measured interleaved within the same run, are the numbers to read.",
            m.cores
        );
    }
    let _ = writeln!(out);
    headline(r, &mut out);
    element_section(r, &mut out);
    autodiff_section(r, &mut out);
    solve_section(r, &mut out);
    scaling_section(r, &mut out);
    out.push_str(METHODS);
    if !r.notes.is_empty() {
        let _ = writeln!(out, "\n## Problems during the run\n");
        for n in &r.notes {
            let _ = writeln!(out, "* {n}");
        }
    }
    out
}
