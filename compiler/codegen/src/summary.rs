//! One-line descriptions of what was specialised, shared by the generated
//! docs, the file header and the report.

use ecc_dsl::{DimIr, Module, PairIr, Path, ScaleIr};

/// Pair slot labels with 1-based stretch names: 3D slot 0 is (s2, s3).
pub(crate) fn pair_label(dim: u8, slot: usize) -> (usize, usize) {
    let (i, j) = if dim == 2 {
        (0, 1)
    } else {
        [(1, 2), (2, 0), (0, 1)][slot]
    };
    (i + 1, j + 1)
}

/// Number of twist/flip pair slots.
pub(crate) fn pairs(dim: u8) -> usize {
    if dim == 2 { 1 } else { 3 }
}

/// Short facts about one compiled dimension, one per line.
pub(crate) fn dim_facts(d: &DimIr) -> Vec<String> {
    let n = d.dim as usize;
    let mut out = Vec::new();
    out.push(match d.path {
        Path::Invariant => "invariant path (Smith et al. 2019: Ψ(I1, I2, I3))".to_string(),
        Path::Stretch => "stretch path (Zhu 2020: Ψ(σ), divided differences)".to_string(),
    });
    out.push(match &d.spectral.scale {
        ScaleIr::Diagonal(_) => format!(
            "scaling block diagonal (off-diagonals proved ≡ 0): {n} closed-form eigenvalues, no eigensolve"
        ),
        ScaleIr::Full(_) => format!("scaling block coupled: the runtime solves a {n}×{n} symmetric eigenproblem"),
    });
    let all = d.spectral.twist.iter().chain(&d.spectral.flip);
    let guarded = all
        .clone()
        .filter(|p| matches!(p, PairIr::Guarded { .. }))
        .count();
    let total = all.count();
    out.push(format!(
        "twist/flip: {} exact closed forms, {guarded} guarded (limit form near σi = ±σj)",
        total - guarded
    ));
    out.push(format!(
        "barrier: {}; SVD-free Ψ: {}; sign-symmetric: {}",
        yes(d.barrier),
        yes(d.svd_free),
        yes(d.sign_symmetric)
    ));
    let tested: Vec<String> = d
        .active_guards()
        .map(|g| format!("{} {} 0", d.graph.to_text(g.arg), g.cond.relation()))
        .collect();
    if !tested.is_empty() {
        out.push(format!(
            "domain as written (tested, Ψ = +∞ elsewhere): {}",
            tested.join(", ")
        ));
    }
    out
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// `mu = 1, lambda = 10`, or `none`.
pub(crate) fn params_line(m: &Module) -> String {
    if m.params.is_empty() {
        return "none".to_string();
    }
    m.params
        .iter()
        .map(|p| format!("{} = {}", p.name, p.default))
        .collect::<Vec<_>>()
        .join(", ")
}
