//! The fibre section of the Markdown report: ψ(I4, I5) of an energy with
//! `fiber a`, its partials, its domain, and which eigensystem the runtime
//! uses for it (`ecc_runtime::fibre::point`): the closed form of I5
//! (eqs. P3–P5 there: λ_along = 2ψ5 + 4ψ55 I5 on vec(n aᵀ), λ_across = 2ψ5
//! on the d − 1 other vec(q aᵀ), 0 on the d² − d vec(q cᵀ) with c ⊥ a)
//! when ψ4 ≡ ψ44 ≡ ψ45 ≡ 0, else the analytic raw Hessian projected by a
//! d² × d² (ψ(I4) alone: d² − d + 1) numeric eigensolve.
//!
//! **Citation** ([`CLOSED_FORM_SOURCE`], checked against text). P3–P5 are
//! the eigensystem of I5 of Kim, de Goes & Iben 2019, *Anisotropic
//! Elasticity for Inversion-Safety and Element Rehabilitation*, §4.1
//! "The Eigensystem of I5" — eq. 5 I5 = tr(C A), eq. 6 ∂I5/∂F = 2 F A,
//! eq. 7 ∂²I5/∂f² = 2 [A_ij I], whose non-zero eigenvalues are 2‖a‖² on
//! Q_i = e_i aᵀ — carried through the chain rule. Checked in the I❤LA
//! transcription of §4.1 (iheartla.github.io, `heartdown/CaseStudies/
//! static/gallery_res/Anisotropic/Anisotropic.txt`; its front matter sets
//! section base 4 and equation base 5, and its text calls the Hessian
//! "Eqn. 7"). The eigenvalues of the three library energies were checked
//! against HOBAK's `ANISOTROPIC_{STVK,FUNG,ARAP}` sources
//! (theodorekim/HOBAKv1, whose comments cite no equation numbers). Not
//! cited, because no text was available to check them: the numbers of
//! the paper's later sections and equations, and section or equation
//! numbers of Kim & Eberle's *Dynamic Deformables* (a reader's transcribed
//! table of contents places the anisotropic material in the chapter
//! "A Better Way for Anisotropic Solids", numbered 8 there).

use std::fmt::Write;

use ecc_dsl::{FibreIr, FibreUses, Sym};

/// Where the closed-form eigensystem comes from, as the report cites it.
pub(crate) const CLOSED_FORM_SOURCE: &str = "the eigensystem of I5, Kim, de Goes & Iben 2019 \
     §4.1 eq. 7, through the chain rule";

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
            "Eigensystem: closed form (ψ4 ≡ ψ44 ≡ ψ45 ≡ 0; {CLOSED_FORM_SOURCE}): \
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
