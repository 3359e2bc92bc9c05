//! The emitted C++ of an energy's fibre part ψ(I4, I5) (`fiber a`,
//! [`ecc_dsl::FibreIr`]): the C++ twin of the Rust back end's
//! `FibreEnergy<D>` impl (`crate::fibre`), printed from the same [`Plan`].
//!
//! Members added to the energy's struct (only when the module has a fibre):
//!
//! * `has_fibre(d)`, `fibre_uses(d)` → `ecc::FibreUse` (what the CAS decided:
//!   the runtime takes a signed SVD for I4 only when ψ reads it);
//! * `fibre<D>(i4, i5)` → `ecc::FibreDerivs`: ψ and [ψ4, ψ5, ψ44, ψ45, ψ55],
//!   ψ's domain conditions tested first (ψ = +∞, partials 0 outside);
//! * per dimension, with a unit rest fibre `a`: `fibre_psi_f(F, a)`,
//!   `fibre_eval(F, a, filter)` → `ecc::FibreEval<D>` (ψ, I4, I5,
//!   vec(∂ψ/∂F), the filtered d²×d² Hessian) and `fibre_eval_tri` /
//!   `fibre_eval_tet`, which call the runtime's `ecc::fibre_*` templates
//!   (`compiler/codegen/cpp/ecc_runtime.hpp`, section "fibres").

use std::collections::HashMap;
use std::fmt::Write as _;

use ecc_dsl::{DimIr, DomainCond, FibreIr, FibreUses, Sym};

use super::energy::Ctx;
use super::expr::cpp;
use crate::plan::{Plan, Region, Root};

/// Names of the partials' roots in the plan.
const PARTIALS: [&str; 5] = ["d4", "d5", "d44", "d45", "d55"];

/// The fibre members of the struct (empty when no dimension has a fibre).
pub(super) fn members(ctx: &Ctx, dims: &[DimIr]) -> String {
    let fibres: Vec<(u8, &FibreIr)> = dims
        .iter()
        .filter_map(|d| d.fibre.as_ref().map(|f| (d.dim, f)))
        .collect();
    if fibres.is_empty() {
        return String::new();
    }
    let mut s = String::from("\n");
    s.push_str(&queries(&fibres));
    s.push('\n');
    s.push_str(&fibre_fn(ctx, &fibres));
    for (dim, _) in &fibres {
        s.push('\n');
        s.push_str(&entry_points(*dim));
    }
    s
}

/// `has_fibre(d)` and `fibre_uses(d)`.
fn queries(fibres: &[(u8, &FibreIr)]) -> String {
    let has: Vec<String> = fibres.iter().map(|(d, _)| format!("d == {d}")).collect();
    let mut uses = String::new();
    for (d, f) in fibres {
        let u = match f.uses {
            FibreUses::None => "None",
            FibreUses::I4 => "I4",
            FibreUses::I5 => "I5",
            FibreUses::Both => "Both",
        };
        let _ = write!(uses, "d == {d} ? ::ecc::FibreUse::{u} : ");
    }
    format!(
        "    /// Whether dimension `d` has a fibre part ψ(I4, I5) (`fiber` in the source).\n\
         \x20   ECC_HOST_DEVICE static constexpr bool has_fibre(int d) {{ return {}; }}\n\
         \x20   /// Which fibre invariants ψ reads in dimension `d` (decided by the CAS).\n\
         \x20   ECC_HOST_DEVICE static constexpr ::ecc::FibreUse fibre_uses(int d) {{\n\
         \x20       return {uses}::ecc::FibreUse::None;\n    }}\n",
        has.join(" || ")
    )
}

/// `template <int D> FibreDerivs fibre(i4, i5) const`, one branch per dimension.
fn fibre_fn(ctx: &Ctx, fibres: &[(u8, &FibreIr)]) -> String {
    let mut s = String::from(
        "    /// ψ(I4, I5) of the fibre part in D dimensions and its partials ∂ψ/∂I4,\n\
         \x20   /// ∂ψ/∂I5, ∂²ψ/∂I4², ∂²ψ/∂I4∂I5, ∂²ψ/∂I5²; ψ = +∞ (partials 0) outside\n\
         \x20   /// ψ's domain, never NaN. I4 = aᵀSa (signed polar F = RS), I5 = ‖Fa‖².\n\
         \x20   template <int D>\n\
         \x20   ECC_HOST_DEVICE ::ecc::FibreDerivs fibre(double i4, double i5) const {\n\
         \x20       static_assert(has_fibre(D), \"no fibre part in this dimension\");\n",
    );
    for (k, (dim, f)) in fibres.iter().enumerate() {
        let kw = if k == 0 { "if" } else { "} else if" };
        let _ = writeln!(s, "        {kw} constexpr (D == {dim}) {{");
        s.push_str(&body(ctx, *dim, f));
    }
    s.push_str("        }\n    }\n");
    s
}

/// The statements of one dimension's branch (indented twelve spaces).
fn body(ctx: &Ctx, dim: u8, f: &FibreIr) -> String {
    let root = |id, region, name: &str, bind| Root {
        id,
        region,
        name: name.into(),
        bind,
    };
    let mut roots = vec![root(f.psi, Region::Psi, "psi", true)];
    for g in f.active_guards() {
        roots.push(root(g.arg, Region::Psi, "domain_arg", false));
    }
    let ids = [f.d4, f.d5, f.d44, f.d45, f.d55];
    for (id, n) in ids.iter().zip(PARTIALS) {
        roots.push(root(*id, Region::Main, n, false));
    }
    let namer = |s: Sym| ctx.leaf_name(s);
    let mut taken = ctx.taken();
    taken.extend(PARTIALS);
    let plan = Plan::new(&f.graph, dim, &roots, &HashMap::new(), &namer, &taken);
    let ind = "            ";
    let leaves = plan.leaves();
    let mut s = String::new();
    if !(leaves.contains(&Sym::I4) || leaves.contains(&Sym::SignI4)) {
        let _ = writeln!(s, "{ind}(void)i4;");
    }
    if !leaves.contains(&Sym::I5) {
        let _ = writeln!(s, "{ind}(void)i5;");
    }
    if leaves.contains(&Sym::SignI4) {
        let _ = writeln!(
            s,
            "{ind}// sign(I4): +1 for I4 > 0, −1 otherwise (HOBAK's convention).\n\
             {ind}const double sign_i4 = i4 > 0.0 ? 1.0 : (std::isnan(i4) ? ::ecc::nan() : -1.0);"
        );
    }
    s.push_str(&lines(&plan, Region::Psi, ind));
    let psi = cpp(&plan.value_ex(f.psi));
    if !plan.is_bound(f.psi) {
        let _ = writeln!(s, "{ind}const double psi = {psi};");
    }
    let inside = format!("std::isfinite(psi){}", guards(f, &plan));
    let test = if inside.contains("&&") {
        format!("!({inside})")
    } else {
        format!("!{inside}")
    };
    let _ = writeln!(
        s,
        "{ind}if ({test}) return ::ecc::FibreDerivs::infinite();  // outside the domain"
    );
    s.push_str(&lines(&plan, Region::Main, ind));
    let d: Vec<String> = ids.iter().map(|&id| cpp(&plan.value_ex(id))).collect();
    let _ = writeln!(
        s,
        "{ind}::ecc::FibreDerivs out{{}};\n{ind}out.psi = psi;\n{ind}out.d4 = {};\n{ind}out.d5 = {};\n\
         {ind}out.d44 = {};\n{ind}out.d45 = {};\n{ind}out.d55 = {};\n{ind}return out;",
        d[0], d[1], d[2], d[3], d[4]
    );
    s
}

/// `const double name = …;` for the plan's bindings of `region`.
fn lines(plan: &Plan, region: Region, indent: &str) -> String {
    let mut out = String::new();
    for (name, ex) in plan.bindings(region) {
        let _ = writeln!(out, "{indent}const double {name} = {};", cpp(&ex));
    }
    out
}

/// ` && arg > 0.0` … for each active domain condition of ψ.
fn guards(f: &FibreIr, plan: &Plan) -> String {
    let mut out = String::new();
    for g in f.active_guards() {
        let v = cpp(&plan.value_ex(g.arg));
        let _ = match g.cond {
            DomainCond::Positive => write!(out, " && {v} > 0.0"),
            DomainCond::NonNegative => write!(out, " && {v} >= 0.0"),
            DomainCond::NonZero => write!(out, " && std::fabs({v}) > 0.0"),
        };
    }
    out
}

/// `fibre_psi_f`, `fibre_eval` and the element entry point of one dimension.
fn entry_points(n: u8) -> String {
    let nn = n as usize * n as usize;
    let (elem, nodes, measure, size) = if n == 2 {
        ("fibre_eval_tri", 3, "area", 6)
    } else {
        ("fibre_eval_tet", 4, "volume", 12)
    };
    format!(
        "    /// ψ(F) of the fibre part for a {n}×{n} F (row-major) and the unit rest fibre `a`\n\
         \x20   /// (`ecc::unit_fibre` normalises one); NaN for a non-finite F.\n\
         \x20   ECC_HOST_DEVICE double fibre_psi_f(const double (&F)[{n}][{n}], const double (&a)[{n}]) const {{\n\
         \x20       return ::ecc::fibre_psi_f<{n}>(*this, F, a);\n    }}\n\n\
         \x20   /// The fibre part at F for the unit rest fibre `a`: ψ, I4, I5, vec(∂ψ/∂F) (column-major)\n\
         \x20   /// and the {nn}×{nn} Hessian ∂²ψ/∂f² with its eigenvalues mapped by `filter` (closed form\n\
         \x20   /// when ψ has no I4 derivative, else a {nn}×{nn} eigensolve). Add it to `eval(F)`.\n\
         \x20   ECC_HOST_DEVICE ::ecc::FibreEval<{n}> fibre_eval(const double (&F)[{n}][{n}], const double (&a)[{n}],\n\
         \x20                                         ::ecc::Filter filter = ::ecc::Filter::clamp(),\n\
         \x20                                         bool want_hessian = true) const {{\n\
         \x20       return ::ecc::fibre_eval_f<{n}>(*this, F, a, filter, want_hessian);\n    }}\n\n\
         \x20   /// The fibre part's energy, gradient and filtered {size}×{size} Hessian of a linear element\n\
         \x20   /// ({nodes} × {n} node positions `x`, rest Dm⁻¹ and {measure}, unit rest fibre `a`); all × {measure}.\n\
         \x20   ECC_HOST_DEVICE ::ecc::ElementEval<{size}> {elem}(const double (&x)[{nodes}][{n}],\n\
         \x20                                         const double (&dm_inv)[{n}][{n}], double {measure},\n\
         \x20                                         const double (&a)[{n}],\n\
         \x20                                         ::ecc::Filter filter = ::ecc::Filter::clamp(),\n\
         \x20                                         bool want_hessian = true) const {{\n\
         \x20       return ::ecc::{elem}(*this, x, dm_inv, {measure}, a, filter, want_hessian);\n    }}\n"
    )
}
