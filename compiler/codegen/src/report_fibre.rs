//! The fibre section of the Markdown report: ψ(I4, I5) of an energy with
//! `fiber a`, its partials, its domain, and which eigensystem the runtime
//! uses for it (`ecc_runtime::fibre::point`): the closed form of I5
//! (Kim & Eberle 2022 §7.3, eqs. P3–P5: λ_along = 2ψ5 + 4ψ55 I5 on
//! vec(n aᵀ), λ_across = 2ψ5 on the d − 1 other vec(q aᵀ), 0 on the
//! d² − d vec(q cᵀ) with c ⊥ a) when ψ4 ≡ ψ44 ≡ ψ45 ≡ 0, else the analytic
//! raw Hessian projected by a d² × d² (ψ(I4) alone: d² − d + 1) numeric
//! eigensolve.

use std::fmt::Write;

use ecc_dsl::{FibreIr, FibreUses, Sym};

/// Appends the fibre section of one dimension (nothing without a fibre).
pub(crate) fn fibre_section(out: &mut String, dim: u8, f: Option<&FibreIr>) {
    let Some(f) = f else { return };
    let t = |id| format!("`{}`", f.graph.to_text(id));
    let _ = writeln!(
        out,
        "### Fibre part\n\nΨ above is the isotropic part; the fibre direction `{}` adds ψ(I4, I5) \
         (I4 = aᵀ S a, I5 = ‖F a‖²), projected separately.\n",
        f.direction
    );
    let _ = writeln!(out, "ψ = {}\n", t(f.psi));
    let _ = writeln!(out, "| partial | expression |\n|---|---|");
    for (name, id) in [
        ("∂ψ/∂I4", f.d4),
        ("∂ψ/∂I5", f.d5),
        ("∂²ψ/∂I4²", f.d44),
        ("∂²ψ/∂I4∂I5", f.d45),
        ("∂²ψ/∂I5²", f.d55),
    ] {
        let _ = writeln!(out, "| {name} | {} |", t(id));
    }
    let _ = writeln!(
        out,
        "\nψ reads: {}. Domain: {}.\n",
        reads(f.uses),
        domain(f)
    );
    let n = usize::from(dim) * usize::from(dim);
    if f.closed_form {
        let _ = writeln!(
            out,
            "Eigensystem: closed form (ψ4 ≡ ψ44 ≡ ψ45 ≡ 0; Kim & Eberle 2022 §7.3): \
             λ_along = 2ψ5 + 4ψ55·I5 = {} (1 mode), λ_across = 2ψ5 = {} ({} modes), \
             0 ({} modes).\n",
            t_along(f),
            t_across(f),
            dim - 1,
            n - usize::from(dim)
        );
    } else {
        let k = if f.uses == FibreUses::I4 {
            n - usize::from(dim) + 1
        } else {
            n
        };
        let _ = writeln!(
            out,
            "Eigensystem: ψ has I4 terms, no closed form is established: the analytic raw \
             Hessian is projected by a {k} × {k} numeric eigensolve.\n"
        );
    }
}

fn reads(u: FibreUses) -> &'static str {
    match u {
        FibreUses::None => "neither I4 nor I5 (constant)",
        FibreUses::I4 => "I4 only",
        FibreUses::I5 => "I5 only",
        FibreUses::Both => "I4 (or sign(I4)) and I5",
    }
}

fn domain(f: &FibreIr) -> String {
    if f.domain.is_empty() {
        return "all F".into();
    }
    f.domain
        .iter()
        .map(|g| format!("`{} {} 0`", f.graph.to_text(g.arg), g.cond.relation()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// λ_along = 2ψ5 + 4ψ55·I5, simplified by the CAS (eq. P3).
fn t_along(f: &FibreIr) -> String {
    let mut g = f.graph.clone();
    let (two, four, i5) = (g.int(2), g.int(4), g.sym(Sym::I5));
    let a = g.mul2(two, f.d5);
    let b = g.product(&[four, f.d55, i5]);
    let along = g.add2(a, b);
    format!("`{}`", g.to_text(along))
}

/// λ_across = 2ψ5 (eq. P4).
fn t_across(f: &FibreIr) -> String {
    let mut g = f.graph.clone();
    let two = g.int(2);
    let across = g.mul2(two, f.d5);
    format!("`{}`", g.to_text(across))
}
