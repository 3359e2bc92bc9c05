//! The Markdown report (`ecc energy.psi --emit report`): derivatives, every
//! eigenvalue expression in canonical form, which modes are closed-form,
//! guarded or need an eigensolve, the decoupling proof and the singularities.

use std::fmt::Write;

use ecc_dsl::{DimIr, Module, PairIr, PairKind, Path, ScaleIr};

use crate::summary::{pair_label, params_line};

/// The report of a compiled module, as Markdown.
///
/// Expressions are printed with the CAS's canonical printer (`s1` is σ₁,
/// `I1 = s1 + s2 (+ s3)`, `I2 = s1² + s2² (+ s3²)`, `I3 = s1·s2 (·s3)`), so
/// the text is deterministic.
pub fn report_markdown(module: &Module, name: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Energy `{name}`\n");
    let _ = writeln!(out, "```text\n{}\n```\n", module.source.trim_end());
    let _ = writeln!(out, "Parameters: {}.\n", params_line(module));
    if module.dims.is_empty() {
        let _ = writeln!(out, "The energy compiled for no dimension.\n");
    }
    for (d, why) in &module.skipped {
        let _ = writeln!(out, "- {d}D not compiled: {why}");
    }
    if !module.skipped.is_empty() {
        out.push('\n');
    }
    for d in &module.dims {
        dim_section(&mut out, d);
    }
    out
}

fn code(d: &DimIr, id: ecc_dsl::Id) -> String {
    format!("`{}`", d.graph.to_text(id))
}

/// The written domain of Ψ in maths (`I3 > 0`): the conditions evaluators
/// test, then those Ψ enforces by itself, or `all F`.
fn domain_text(d: &DimIr) -> String {
    if d.domain.is_empty() {
        return "all F".to_string();
    }
    let list = |enforced: bool| {
        d.domain
            .iter()
            .filter(|g| g.enforced_by_psi == enforced)
            .map(|g| format!("`{} {} 0`", d.graph.to_text(g.arg), g.cond.relation()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (tested, own) = (list(false), list(true));
    match (tested.is_empty(), own.is_empty()) {
        (_, true) => tested,
        (true, false) => format!("{own} (Ψ itself is +∞ or NaN outside)"),
        (false, false) => format!("{tested}; {own} (Ψ itself is +∞ or NaN outside)"),
    }
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// One dimension's section: the property table, then one subsection per
/// table or list, in the order a reader follows the derivation.
fn dim_section(out: &mut String, d: &DimIr) {
    let _ = writeln!(out, "## {}D\n", d.dim);
    property_table(out, d);
    let _ = writeln!(out, "### Energy\n\nΨ = {}\n", code(d, d.psi));
    invariant_derivatives(out, d);
    gradient_list(out, d);
    scaling_modes(out, d);
    pair_modes(out, d);
    divided_differences(out, d);
    singularities(out, d);
    crate::report_fibre::fibre_section(out, d.dim, d.fibre.as_ref());
}

/// The property table: path, domain, barrier, SVD-freedom, sign symmetry,
/// decoupling (and the isotropy caveat when it was only checked numerically).
fn property_table(out: &mut String, d: &DimIr) {
    let path = match d.path {
        Path::Invariant => "invariant (Smith et al. 2019, §4 and App. D: Ψ(I1, I2, I3))",
        Path::Stretch => "stretch (Zhu 2020: Ψ(σ), twist/flip as divided differences)",
    };
    let _ = writeln!(out, "| property | value |\n|---|---|");
    let _ = writeln!(out, "| path | {path} |");
    let _ = writeln!(out, "| domain (Ψ = +∞ elsewhere) | {} |", domain_text(d));
    let _ = writeln!(out, "| barrier (keep det F > 0) | {} |", yes(d.barrier));
    let _ = writeln!(out, "| SVD-free Ψ (I2, I3 only) | {} |", yes(d.svd_free));
    let _ = writeln!(
        out,
        "| sign-symmetric ((σi, σj) → (−σj, −σi)) | {} |",
        yes(d.sign_symmetric)
    );
    let _ = writeln!(out, "| scaling modes decoupled | {} |", yes(d.decoupled));
    if d.isotropy_numeric_only {
        let _ = writeln!(out, "| isotropy | checked numerically only (not proved) |");
    }
    out.push('\n');
}

/// The table of ∂Ψ/∂Ik and ∂²Ψ/∂Ik∂Il (invariant path only).
fn invariant_derivatives(out: &mut String, d: &DimIr) {
    let Some(inv) = &d.d_inv else { return };
    let _ = writeln!(out, "### Invariant derivatives\n");
    let _ = writeln!(out, "| derivative | expression |\n|---|---|");
    for (k, &id) in inv.d1.iter().enumerate() {
        let _ = writeln!(out, "| ∂Ψ/∂I{} | {} |", k + 1, code(d, id));
    }
    let labels = ["I1 I1", "I2 I2", "I3 I3", "I1 I2", "I1 I3", "I2 I3"];
    for (l, &id) in labels.iter().zip(&inv.d2) {
        let _ = writeln!(out, "| ∂²Ψ/∂{l} | {} |", code(d, id));
    }
    out.push('\n');
}

/// The list of ∂Ψ/∂σi.
fn gradient_list(out: &mut String, d: &DimIr) {
    let _ = writeln!(out, "### Gradient\n");
    for (i, &g) in d.spectral.grad.iter().enumerate() {
        let _ = writeln!(out, "- ∂Ψ/∂s{} = {}", i + 1, code(d, g));
    }
    out.push('\n');
}

/// The scaling modes: closed-form diagonal eigenvalues when A = ∂²Ψ/∂σ² was
/// proved diagonal, else the upper triangle of A the runtime eigensolves.
fn scaling_modes(out: &mut String, d: &DimIr) {
    let n = d.dim as usize;
    let _ = writeln!(out, "### Scaling modes\n");
    match &d.spectral.scale {
        ScaleIr::Diagonal(a) => {
            let _ = writeln!(
                out,
                "Every off-diagonal of A = ∂²Ψ/∂σ² was proved identically zero, so the \
                 scaling modes are eigenvectors and their eigenvalues are closed-form \
                 (no eigensolve):\n"
            );
            for (i, &x) in a.iter().enumerate() {
                let _ = writeln!(
                    out,
                    "- λ_scale{} = A{}{} = {}",
                    i + 1,
                    i + 1,
                    i + 1,
                    code(d, x)
                );
            }
        }
        ScaleIr::Full(a) => {
            let _ = writeln!(
                out,
                "A = ∂²Ψ/∂σ² is coupled: the runtime solves this {n}×{n} symmetric \
                 eigenproblem for the scaling eigenvalues.\n"
            );
            for (i, row) in a.iter().enumerate() {
                for (j, &x) in row.iter().enumerate().skip(i) {
                    let _ = writeln!(out, "- A{}{} = {}", i + 1, j + 1, code(d, x));
                }
            }
        }
    }
    out.push('\n');
}

/// The twist and flip table: per pair, its closed form, or the guarded
/// direct quotient and the limit used within τ of the singular set.
fn pair_modes(out: &mut String, d: &DimIr) {
    let _ = writeln!(out, "### Twist and flip modes\n");
    let _ = writeln!(
        out,
        "| mode | pair | form | eigenvalue |\n|---|---|---|---|"
    );
    for (kind, list) in [("twist", &d.spectral.twist), ("flip", &d.spectral.flip)] {
        for (slot, pr) in list.iter().enumerate() {
            let (i, j) = pair_label(d.dim, slot);
            let pair = format!("(s{i}, s{j})");
            match *pr {
                PairIr::Exact(x) => {
                    let _ = writeln!(out, "| {kind} | {pair} | closed form | {} |", code(d, x));
                }
                PairIr::Guarded { direct, limit, den } => {
                    let _ = writeln!(
                        out,
                        "| {kind} | {pair} | guarded: direct | {} |",
                        code(d, direct)
                    );
                    let _ = writeln!(
                        out,
                        "| {kind} | {pair} | guarded: limit when \\|{}\\| ≤ τ·max(\\|s{i}\\|, \\|s{j}\\|) | {} |",
                        d.graph.to_text(den),
                        code(d, limit)
                    );
                }
            }
        }
    }
    out.push('\n');
    let _ = writeln!(
        out,
        "τ = ecc_runtime::divided::LIMIT_TOL ≈ 6.1e-6 (ε^(1/3)): the same switch as the runtime.\n"
    );
}

/// The denominators and logarithm arguments of the spectral expressions,
/// each marked removable when a guarded divided difference covers it.
fn singularities(out: &mut String, d: &DimIr) {
    let _ = writeln!(out, "### Singularities\n");
    if d.singularities.is_empty() {
        let _ = writeln!(
            out,
            "None: no denominator or logarithm in the spectral expressions.\n"
        );
    } else {
        let _ = writeln!(
            out,
            "Denominators and logarithm arguments found in the spectral expressions \
             (the energy or its eigenvalues are singular where they vanish):\n"
        );
        let guarded: Vec<ecc_dsl::Id> = d
            .spectral
            .twist
            .iter()
            .chain(&d.spectral.flip)
            .filter_map(|p| match p {
                PairIr::Guarded { den, .. } => Some(*den),
                PairIr::Exact(_) => None,
            })
            .collect();
        for &s in &d.singularities {
            let note = if guarded.contains(&s) {
                " (removable: a guarded divided difference switches to its limit here)"
            } else {
                ""
            };
            let _ = writeln!(out, "- {}{note}", code(d, s));
        }
        out.push('\n');
    }
}

/// Per divided difference, what it does on its singular set, as the CAS
/// decided it: no division, removable (with the limit used there), or a pole.
fn divided_differences(out: &mut String, d: &DimIr) {
    let _ = writeln!(
        out,
        "### Divided differences on σi = ±σj
"
    );
    let _ = writeln!(
        out,
        "| divided difference | on its singular set |\n|---|---|"
    );
    let lists = [
        ("twist", "+", &d.spectral.twist, &d.spectral.twist_kind),
        ("flip", "−", &d.spectral.flip, &d.spectral.flip_kind),
    ];
    for (kind, sign, list, kinds) in lists {
        for (slot, pr) in list.iter().enumerate() {
            let (i, j) = pair_label(d.dim, slot);
            let what = format!("{kind} (Ψ{i} {sign} Ψ{j})/(s{i} {sign} s{j})");
            let plane = if sign == "+" {
                format!("s{i} = −s{j}")
            } else {
                format!("s{i} = s{j}")
            };
            let verdict = match (kinds.get(slot), pr) {
                (Some(PairKind::Regular), _) => "no division (closed form)".to_string(),
                (Some(PairKind::Removable), PairIr::Guarded { limit, .. }) => {
                    format!("removable on {plane} (limit {})", code(d, *limit))
                }
                (Some(PairKind::Removable), PairIr::Exact(x)) => {
                    format!("removable on {plane} (exact quotient {})", code(d, *x))
                }
                (Some(PairKind::Pole), _) => {
                    format!("pole on {plane} (genuine singularity: +∞ there)")
                }
                (None, _) => "not classified".to_string(),
            };
            let _ = writeln!(out, "| {what} | {verdict} |");
        }
    }
    out.push('\n');
}
