//! The emitted C++ header: file comment, include guard, runtime, and the
//! energy struct with `psi`, `spectral` and the `eval*` entry points per
//! dimension. Function bodies come from the same [`Plan`] as the Rust code.

use std::fmt::Write as _;

use ecc_dsl::{DimIr, Id, Module, PairIr, PairKind, ScaleIr, Sym};

use super::expr::{cpp, lit};
use super::{CPP_RUNTIME, CppOptions, CppRuntime};
use crate::error::CodegenError;
use crate::options::GenOptions;
use crate::plan::{Plan, Region, Root};
use crate::roots::{hints, psi_roots};
use crate::summary::{dim_facts, pair_label, params_line};

/// Locals of the generated functions (and namespaces they name): no
/// binding or parameter takes them.
const RESERVED: &[&str] = &[
    "s1", "s2", "s3", "i1", "i2", "i3", "i4", "i5", "sign_i4", "sigma", "out", "std", "ecc",
];

/// Members of the generated struct and parameters of its entry points: no
/// parameter takes them (bindings may: a local hides a member harmlessly).
const MEMBERS: &[&str] = &[
    "psi",
    "spectral",
    "eval",
    "eval_tri",
    "eval_tet",
    "psi_f",
    "name",
    "source",
    "barrier",
    "has_dim",
    "F",
    "x",
    "dm_inv",
    "area",
    "volume",
    "filter",
    "want_hessian",
    "has_fibre",
    "fibre_uses",
    "fibre",
    "fibre_psi_f",
    "fibre_eval",
    "fibre_eval_tri",
    "fibre_eval_tet",
    "a",
    "D",
];

/// C++ keywords and alternative tokens (C++17, plus C++20 ones for safety).
const CPP_KEYWORDS: &[&str] = &[
    "alignas",
    "alignof",
    "and",
    "and_eq",
    "asm",
    "auto",
    "bitand",
    "bitor",
    "bool",
    "break",
    "case",
    "catch",
    "char",
    "char8_t",
    "char16_t",
    "char32_t",
    "class",
    "compl",
    "concept",
    "const",
    "consteval",
    "constexpr",
    "constinit",
    "const_cast",
    "continue",
    "co_await",
    "co_return",
    "co_yield",
    "decltype",
    "default",
    "delete",
    "do",
    "double",
    "dynamic_cast",
    "else",
    "enum",
    "explicit",
    "export",
    "extern",
    "false",
    "float",
    "for",
    "friend",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "mutable",
    "namespace",
    "new",
    "noexcept",
    "not",
    "not_eq",
    "nullptr",
    "operator",
    "or",
    "or_eq",
    "private",
    "protected",
    "public",
    "register",
    "reinterpret_cast",
    "requires",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "static_cast",
    "struct",
    "switch",
    "template",
    "this",
    "thread_local",
    "throw",
    "true",
    "try",
    "typedef",
    "typeid",
    "typename",
    "union",
    "unsigned",
    "using",
    "virtual",
    "void",
    "volatile",
    "wchar_t",
    "while",
    "xor",
    "xor_eq",
    "final",
    "override",
    "main",
    "NULL",
    "assert",
];

fn is_cpp_reserved(s: &str) -> bool {
    CPP_KEYWORDS.contains(&s)
        || RESERVED.contains(&s)
        || MEMBERS.contains(&s)
        || s.contains("__")
        || s.starts_with('_')
}

/// A C++ member name for a parameter: its own name when possible, else
/// sanitised and suffixed with `_` (unique among the parameters).
fn field_names(module: &Module) -> Vec<String> {
    let mut used: Vec<String> = Vec::new();
    for p in &module.params {
        let mut n: String = p
            .name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        while n.contains("__") {
            n = n.replace("__", "_");
        }
        if n.is_empty() || n.starts_with(|c: char| c.is_ascii_digit()) {
            n = format!("p{n}");
        }
        while is_cpp_reserved(&n) || used.contains(&n) {
            n = format!("{}_", n.trim_start_matches('_'));
            if n == "_" {
                n = "p_".into();
            }
        }
        used.push(n);
    }
    used
}

fn valid_type_name(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && !is_cpp_reserved(name)
}

/// A C++ string literal of `s` (escaped).
fn string_lit(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\x{:02x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Everything needed to print one module.
pub(super) struct Ctx<'a> {
    module: &'a Module,
    fields: Vec<String>,
}

impl Ctx<'_> {
    pub(super) fn leaf_name(&self, s: Sym) -> String {
        match s {
            Sym::Sigma(k) => format!("s{}", k + 1),
            Sym::I1 => "i1".into(),
            Sym::I2 => "i2".into(),
            Sym::I3 => "i3".into(),
            Sym::Param(k) => self.fields[k as usize].clone(),
            // The fibre leaves (`fibre` function parameters and local).
            Sym::I4 => "i4".into(),
            Sym::I5 => "i5".into(),
            Sym::SignI4 => "sign_i4".into(),
        }
    }

    /// Names bindings must avoid: ours, the parameters', C++ keywords.
    pub(super) fn taken(&self) -> Vec<&str> {
        let mut t: Vec<&str> = RESERVED.iter().chain(CPP_KEYWORDS).copied().collect();
        t.extend(self.fields.iter().map(String::as_str));
        t
    }
}

/// The whole header.
pub(super) fn header(module: &Module, opts: &CppOptions) -> Result<String, CodegenError> {
    if !valid_type_name(&opts.type_name) {
        return Err(CodegenError::InvalidCppTypeName {
            name: opts.type_name.clone(),
        });
    }
    // The Rust back end validates the IR's shape (and fails the same way).
    crate::generate(module, &GenOptions::default())?;
    let ctx = Ctx {
        module,
        fields: field_names(module),
    };
    let ty = &opts.type_name;
    let mut h = file_comment(module, ty);
    let guard = format!("ECC_ENERGY_{}_HPP", ty.to_ascii_uppercase());
    let _ = writeln!(h, "#ifndef {guard}\n#define {guard}\n");
    match &opts.runtime {
        CppRuntime::Inline => {
            h.push_str("// ---- ecc runtime (shared by every emitted header) ----\n");
            h.push_str(CPP_RUNTIME);
            h.push_str("// ---- end of the ecc runtime ----\n\n");
        }
        CppRuntime::Include(path) => {
            let _ = writeln!(h, "#include {}\n", string_lit(path));
        }
    }
    h.push_str("namespace ecc {\nnamespace energies {\n\n");
    let name = opts
        .energy_name
        .clone()
        .unwrap_or_else(|| module.name.clone());
    h.push_str(&struct_text(&ctx, ty, &name));
    h.push_str("\n}  // namespace energies\n}  // namespace ecc\n\n");
    let _ = writeln!(h, "#endif  // {guard}");
    Ok(h)
}

fn file_comment(module: &Module, ty: &str) -> String {
    let mut h = format!(
        "// @generated by ecc-codegen from `{}` (type `ecc::energies::{ty}`). Do not edit by hand.\n//\n// Source:\n",
        module.name
    );
    for line in module.source.trim_end().lines() {
        let _ = writeln!(h, "//     {line}");
    }
    let _ = writeln!(h, "//\n// Parameters: {}.", params_line(module));
    for d in &module.dims {
        let _ = writeln!(h, "// {}D:", d.dim);
        for f in dim_facts(d) {
            let _ = writeln!(h, "//   - {f}");
        }
    }
    for d in &module.dims {
        if let Some(f) = &d.fibre {
            let _ = writeln!(
                h,
                "// {}D fibre part (direction `{}`): {}.",
                d.dim,
                f.direction,
                fibre_fact(f)
            );
        }
    }
    for (d, why) in &module.skipped {
        let _ = writeln!(h, "// {d}D not generated: {why}");
    }
    h.push_str(
        "//\n// C++17, standard library only, no allocation, no exceptions. For CUDA/HIP\n\
         // `#define ECC_HOST_DEVICE __host__ __device__` before including this file.\n\n",
    );
    h
}

/// What the file comment says of a fibre part: which eigensystem applies.
fn fibre_fact(f: &ecc_dsl::FibreIr) -> &'static str {
    if f.closed_form {
        "ψ has no I4 derivative, closed-form eigensystem (fibre_eval: no eigensolve)"
    } else {
        "ψ has I4 terms, fibre_eval filters the Hessian by a d²×d² eigensolve"
    }
}

fn struct_text(ctx: &Ctx, ty: &str, name: &str) -> String {
    let m = ctx.module;
    let mut s = format!(
        "/// Energy `{name}`: Ψ, its stretch-space eigensystem and the filtered\n\
         /// F-space / element derivatives. Parameters are public members.\n\
         struct {ty} {{\n"
    );
    for (p, f) in m.params.iter().zip(&ctx.fields) {
        let _ = writeln!(
            s,
            "    /// Parameter `{}` (default {}).\n    double {f} = {};",
            p.name,
            p.default,
            lit(p.default)
        );
    }
    if !m.params.is_empty() {
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "    /// The energy's name.\n    static constexpr const char* name = {};",
        string_lit(name)
    );
    let _ = writeln!(
        s,
        "    /// The energy's source text.\n    static constexpr const char* source = {};",
        string_lit(&m.source)
    );
    let dims: Vec<String> = m.dims.iter().map(|d| format!("d == {}", d.dim)).collect();
    let _ = writeln!(
        s,
        "    /// Whether dimension `d` was generated.\n    ECC_HOST_DEVICE static constexpr bool has_dim({}",
        predicate(&dims)
    );
    let barrier: Vec<String> = m
        .dims
        .iter()
        .filter(|d| d.barrier)
        .map(|d| format!("d == {}", d.dim))
        .collect();
    let _ = writeln!(
        s,
        "    /// Whether Ψ → +∞ as an element degenerates in dimension `d` (keep elements uninverted).\n    ECC_HOST_DEVICE static constexpr bool barrier({}",
        predicate(&barrier)
    );
    for d in &m.dims {
        s.push('\n');
        s.push_str(&psi_fn(ctx, d));
        s.push('\n');
        s.push_str(&spectral_fn(ctx, d));
        s.push('\n');
        s.push_str(&entry_points(d.dim));
    }
    s.push_str(&super::fibre::members(ctx, &m.dims));
    s.push_str("};\n");
    s
}

/// The rest of `f(int d) { return <any of the conditions>; }` (the parameter
/// unnamed when there is none, so that `-Wunused-parameter` stays quiet).
fn predicate(conds: &[String]) -> String {
    if conds.is_empty() {
        "int /*d*/) { return false; }".into()
    } else {
        format!("int d) {{ return {}; }}", conds.join(" || "))
    }
}

/// `const double s1 = sigma[0];` …, and the invariants, as the plan reads them.
fn prelude(dim: u8, plan: &Plan, extra_sigma: &[usize]) -> String {
    let leaves = plan.leaves();
    let uses_inv = leaves
        .iter()
        .any(|s| matches!(s, Sym::I1 | Sym::I2 | Sym::I3));
    let mut out = String::new();
    let n = dim as usize;
    for k in 0..n {
        if uses_inv || leaves.contains(&Sym::Sigma(k as u8)) || extra_sigma.contains(&k) {
            let _ = writeln!(out, "        const double s{} = sigma[{k}];", k + 1);
        }
    }
    let s: Vec<String> = (1..=n).map(|k| format!("s{k}")).collect();
    for sym in leaves {
        let (name, what, v) = match sym {
            Sym::I1 => ("i1", "I1 = Σ σi", s.join(" + ")),
            Sym::I2 => (
                "i2",
                "I2 = Σ σi² = ‖F‖²",
                s.iter()
                    .map(|x| format!("{x} * {x}"))
                    .collect::<Vec<_>>()
                    .join(" + "),
            ),
            Sym::I3 => ("i3", "I3 = Π σi = det F", s.join(" * ")),
            _ => continue,
        };
        let _ = writeln!(out, "        const double {name} = {v};  // {what}");
    }
    if out.is_empty() {
        out.push_str("        (void)sigma;\n");
    }
    out
}

fn lets(plan: &Plan, region: Region, indent: &str) -> String {
    let mut out = String::new();
    for (name, ex) in plan.bindings(region) {
        let _ = writeln!(out, "{indent}const double {name} = {};", cpp(&ex));
    }
    out
}

/// `if (!(a > 0.0 && …)) <then>` for the active domain conditions (empty
/// when there are none).
fn domain_test(d: &DimIr, plan: &Plan, then: &str) -> String {
    let tests: Vec<String> = crate::domain::tests(d, plan)
        .iter()
        .map(|(arg, rel)| format!("{} {rel} 0.0", cpp(arg)))
        .collect();
    if tests.is_empty() {
        return String::new();
    }
    format!(
        "        if (!({})) {then}  // outside the domain as written\n",
        tests.join(" && ")
    )
}

fn psi_fn(ctx: &Ctx, d: &DimIr) -> String {
    let namer = |s: Sym| ctx.leaf_name(s);
    let plan = Plan::new(
        &d.graph,
        d.dim,
        &psi_roots(d),
        &hints(d),
        &namer,
        &ctx.taken(),
    );
    let n = d.dim;
    format!(
        "    /// Ψ(σ) in {n}D (σ: signed singular values, |σ0| ≥ … , only the last may be < 0);\n\
         \x20   /// +∞ outside the domain, never NaN.\n\
         \x20   ECC_HOST_DEVICE double psi(const double (&sigma)[{n}]) const {{\n{}{}{}\
         \x20       return ::ecc::finite_or_inf({});\n    }}\n",
        prelude(n, &plan, &[]),
        lets(&plan, Region::Psi, "        "),
        domain_test(d, &plan, "return ::ecc::infinity();"),
        cpp(&plan.value_ex(d.psi)),
    )
}

/// A guarded pair: its slot, kind, variable and the plan ids.
struct Guard {
    slot: usize,
    kind: &'static str,
    var: String,
    direct: Id,
    limit: Id,
    den: Id,
    branches: (u32, u32),
}

/// The roots of `spectral`: Ψ, gradient, scaling block, pairs (guarded ones
/// as two lazily computed branches and their denominator).
fn spectral_roots(d: &DimIr) -> (Vec<Root>, Vec<Guard>) {
    let sp = &d.spectral;
    let mut roots = psi_roots(d);
    let main = |id: Id, name: String| Root {
        id,
        region: Region::Main,
        name,
        bind: true,
    };
    for (i, &g) in sp.grad.iter().enumerate() {
        roots.push(main(g, format!("psi_s{}", i + 1)));
    }
    match &sp.scale {
        ScaleIr::Diagonal(a) => {
            for (i, &x) in a.iter().enumerate() {
                roots.push(main(x, format!("a{}{}", i + 1, i + 1)));
            }
        }
        ScaleIr::Full(a) => {
            for (i, row) in a.iter().enumerate() {
                for (j, &x) in row.iter().enumerate().skip(i) {
                    roots.push(main(x, format!("a{}{}", i + 1, j + 1)));
                }
            }
        }
    }
    let mut guards = Vec::new();
    let mut branch = 0u32;
    for (kind, list) in [("twist", &sp.twist), ("flip", &sp.flip)] {
        for (slot, pr) in list.iter().enumerate() {
            let (i, j) = pair_label(d.dim, slot);
            let var = format!("{kind}_{i}{j}");
            match *pr {
                PairIr::Exact(x) => roots.push(main(x, var)),
                PairIr::Guarded { direct, limit, den } => {
                    let (bl, bd) = (branch, branch + 1);
                    branch += 2;
                    roots.push(Root {
                        id: den,
                        region: Region::Main,
                        name: format!("{kind}_den_{i}{j}"),
                        bind: false,
                    });
                    for (id, b, suffix) in [(limit, bl, "limit"), (direct, bd, "direct")] {
                        roots.push(Root {
                            id,
                            region: Region::Branch(b),
                            name: format!("{var}_{suffix}"),
                            bind: false,
                        });
                    }
                    guards.push(Guard {
                        slot,
                        kind,
                        var,
                        direct,
                        limit,
                        den,
                        branches: (bl, bd),
                    });
                }
            }
        }
    }
    (roots, guards)
}

fn guard_text(plan: &Plan, dim: u8, g: &Guard) -> String {
    let (i, j) = pair_label(dim, g.slot);
    let (op, lim) = if g.kind == "twist" {
        ("+", "+")
    } else {
        ("−", "−")
    };
    let mut s = format!(
        "        // λ_{kind} of (σ{i}, σ{j}) = (Ψ_{i} {op} Ψ_{j})/(σ{i} {op} σ{j}); within the switch band\n\
         \x20       // |σ{i} {op} σ{j}| ≤ τ·max(|σ{i}|, |σ{j}|), τ = ε^(1/3), its limit (A_{i}{i} + A_{j}{j})/2 {lim} A_{i}{j}.\n\
         \x20       double {var};\n\
         \x20       if (std::fabs({den}) <= ::ecc::LIMIT_TOL * std::fmax(std::fabs(s{i}), std::fabs(s{j}))) {{\n",
        kind = g.kind,
        var = g.var,
        den = cpp(&plan.value_ex(g.den)),
    );
    s.push_str(&lets(plan, Region::Branch(g.branches.0), "            "));
    let _ = writeln!(
        s,
        "            {} = {};\n        }} else {{",
        g.var,
        cpp(&plan.value_ex(g.limit))
    );
    s.push_str(&lets(plan, Region::Branch(g.branches.1), "            "));
    let _ = writeln!(
        s,
        "            {} = {};\n        }}",
        g.var,
        cpp(&plan.value_ex(g.direct))
    );
    s
}

fn spectral_fn(ctx: &Ctx, d: &DimIr) -> String {
    let n = d.dim;
    let (roots, guards) = spectral_roots(d);
    let mut taken = ctx.taken();
    taken.extend(guards.iter().map(|g| g.var.as_str()));
    let namer = |s: Sym| ctx.leaf_name(s);
    let plan = Plan::new(&d.graph, n, &roots, &hints(d), &namer, &taken);
    let extra = guarded_stretches(d, &guards);
    let mut s = format!(
        "    /// Ψ, ∂Ψ/∂σ, A = ∂²Ψ/∂σ² and the twist/flip eigenvalues of each pair slot\n\
         \x20   /// in {n}D (Smith et al. 2019 eqs. 22–23, Zhu 2020 eq. 28).\n\
         \x20   ECC_HOST_DEVICE ::ecc::Spectral<{n}> spectral(const double (&sigma)[{n}]) const {{\n"
    );
    s.push_str(&prelude(n, &plan, &extra));
    s.push_str(&lets(&plan, Region::Psi, "        "));
    let psi = cpp(&plan.value_ex(d.psi));
    let _ = writeln!(
        s,
        "        if (!std::isfinite({psi})) return ::ecc::Spectral<{n}>::infinite();  // outside the domain"
    );
    s.push_str(&domain_test(
        d,
        &plan,
        &format!("return ::ecc::Spectral<{n}>::infinite();"),
    ));
    s.push_str(&lets(&plan, Region::Main, "        "));
    for g in &guards {
        s.push_str(&guard_text(&plan, n, g));
    }
    let _ = writeln!(
        s,
        "        ::ecc::Spectral<{n}> out{{}};\n        out.psi = {psi};"
    );
    for (i, &g) in d.spectral.grad.iter().enumerate() {
        let _ = writeln!(
            s,
            "        out.grad[{i}] = {};  // ∂Ψ/∂σ{}",
            cpp(&plan.value_ex(g)),
            i + 1
        );
    }
    s.push_str(&scale_lines(&plan, d));
    s.push_str(&pair_lines(&plan, d));
    s.push_str("        return out;\n    }\n");
    s
}

/// The (0-based) stretches that the guards and the pole tests read, so the
/// prelude names them.
fn guarded_stretches(d: &DimIr, guards: &[Guard]) -> Vec<usize> {
    let sp = &d.spectral;
    let poles = sp
        .twist_kind
        .iter()
        .chain(&sp.flip_kind)
        .enumerate()
        .filter(|(_, k)| **k == PairKind::Pole)
        .map(|(slot, _)| slot % sp.twist.len().max(1));
    guards
        .iter()
        .map(|g| g.slot)
        .chain(poles)
        .flat_map(|slot| {
            let (i, j) = pair_label(d.dim, slot);
            [i - 1, j - 1]
        })
        .collect()
}

/// `out.diagonal` and the scaling block A = ∂²Ψ/∂σ² (Smith et al. 2019
/// Appendix D): its diagonal when A is proved diagonal, else every entry.
fn scale_lines(plan: &Plan, d: &DimIr) -> String {
    let dim = d.dim as usize;
    let mut s = String::new();
    match &d.spectral.scale {
        ScaleIr::Diagonal(a) => {
            s.push_str(
                "        out.diagonal = true;  // A_ij ≡ 0 for i ≠ j (proved): no eigensolve\n",
            );
            for (i, &x) in a.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "        out.scale[{i}][{i}] = {};",
                    cpp(&plan.value_ex(x))
                );
            }
        }
        ScaleIr::Full(a) => {
            s.push_str("        out.diagonal = false;  // coupled: the runtime filters A by its eigenpairs\n");
            for i in 0..dim {
                for j in 0..dim {
                    let id = a[i.min(j)][i.max(j)];
                    let _ = writeln!(
                        s,
                        "        out.scale[{i}][{j}] = {};",
                        cpp(&plan.value_ex(id))
                    );
                }
            }
        }
    }
    s
}

/// `out.twist[slot]` and `out.flip[slot]` (Smith et al. 2019 eqs. 22–23):
/// exact values, +∞ exactly on a genuine pole's plane, or the guarded
/// variable computed by `guard_text`.
fn pair_lines(plan: &Plan, d: &DimIr) -> String {
    let (n, sp) = (d.dim, &d.spectral);
    let mut s = String::new();
    for (kind, list, kinds) in [
        ("twist", &sp.twist, &sp.twist_kind),
        ("flip", &sp.flip, &sp.flip_kind),
    ] {
        for (slot, pr) in list.iter().enumerate() {
            let v = match *pr {
                // A genuine pole: +∞ exactly on its plane (never NaN).
                PairIr::Exact(x) if kinds.get(slot) == Some(&PairKind::Pole) => {
                    let (i, j) = pair_label(n, slot);
                    let on = if kind == "twist" {
                        format!("s{i} + s{j} == 0.0")
                    } else {
                        format!("s{i} == s{j}")
                    };
                    let val = cpp(&plan.value_ex(x));
                    format!("({on}) ? ::ecc::infinity() : {val}")
                }
                PairIr::Exact(x) => cpp(&plan.value_ex(x)),
                PairIr::Guarded { .. } => {
                    let (i, j) = pair_label(n, slot);
                    format!("{kind}_{i}{j}")
                }
            };
            let _ = writeln!(s, "        out.{kind}[{slot}] = {v};");
        }
    }
    s
}

/// `psi_f`, `eval` and the element entry point of one dimension.
fn entry_points(n: u8) -> String {
    let nn = n as usize * n as usize;
    let (elem, nodes, measure, size) = if n == 2 {
        ("eval_tri", 3, "area", 6)
    } else {
        ("eval_tet", 4, "volume", 12)
    };
    format!(
        "    /// Ψ(F) for a {n}×{n} F (row-major `F[row][col]`); NaN for a non-finite F.\n\
         \x20   ECC_HOST_DEVICE double psi_f(const double (&F)[{n}][{n}]) const {{\n\
         \x20       return ::ecc::psi_f<{n}>(*this, F);\n    }}\n\n\
         \x20   /// Ψ, vec(∂Ψ/∂F) (column-major) and the {nn}×{nn} Hessian ∂²Ψ/∂f² with its\n\
         \x20   /// eigenvalues mapped by `filter` (`ecc::Filter::none()` = raw, may be indefinite).\n\
         \x20   ECC_HOST_DEVICE ::ecc::PointEval<{n}> eval(const double (&F)[{n}][{n}],\n\
         \x20                                         ::ecc::Filter filter = ::ecc::Filter::clamp(),\n\
         \x20                                         bool want_hessian = true) const {{\n\
         \x20       return ::ecc::eval_f<{n}>(*this, F, filter, want_hessian);\n    }}\n\n\
         \x20   /// Energy, gradient and filtered {size}×{size} Hessian of a linear element with\n\
         \x20   /// node positions `x` ({nodes} × {n}), rest Dm⁻¹ and rest {measure}; all × {measure}.\n\
         \x20   ECC_HOST_DEVICE ::ecc::ElementEval<{size}> {elem}(const double (&x)[{nodes}][{n}],\n\
         \x20                                         const double (&dm_inv)[{n}][{n}], double {measure},\n\
         \x20                                         ::ecc::Filter filter = ::ecc::Filter::clamp(),\n\
         \x20                                         bool want_hessian = true) const {{\n\
         \x20       return ::ecc::{elem}(*this, x, dm_inv, {measure}, filter, want_hessian);\n    }}\n"
    )
}
