//! The generated struct and its `Energy<D>` impls.

use ecc_dsl::{DimIr, Id, Module, PairIr, PairKind, ScaleIr, Sym};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use crate::domain;
use crate::error::CodegenError;
use crate::options::{GenOptions, Visibility};
use crate::plan::{Plan, Region, Root, is_keyword, unique};
use crate::render::Ex;
use crate::roots::{hints, psi_roots};
use crate::summary::{dim_facts, pair_label, pairs, params_line};

/// Local names the generated functions use for their own purposes.
const RESERVED: &[&str] = &["s1", "s2", "s3", "i1", "i2", "i3", "sigma", "value", "name"];

/// Names parameters' locals must also avoid (`psi` is the root's name).
const PARAM_RESERVED: &[&str] = &["psi"];

/// Everything needed to emit the code of one module.
struct Ctx<'a> {
    module: &'a Module,
    rt: TokenStream,
    ty: Ident,
    /// Struct field of each parameter.
    fields: Vec<Ident>,
    /// Local variable of each parameter inside the functions.
    locals: Vec<String>,
}

/// The struct, its inherent impl, `Default` and one `Energy<D>` impl per dimension.
pub(crate) fn generate_items(
    module: &Module,
    opts: &GenOptions,
) -> Result<TokenStream, CodegenError> {
    let ty = type_ident(&opts.type_name)?;
    let rt: syn::Path =
        syn::parse_str(&opts.runtime_path).map_err(|_| CodegenError::InvalidRuntimePath {
            path: opts.runtime_path.clone(),
        })?;
    if module.dims.is_empty() {
        return Err(CodegenError::NoDimensions {
            skipped: module.skipped.clone(),
        });
    }
    for d in &module.dims {
        validate(d, module.params.len())?;
    }
    let mut taken: std::collections::HashSet<String> = RESERVED
        .iter()
        .chain(PARAM_RESERVED)
        .chain(crate::fibre::RESERVED)
        .map(|s| s.to_string())
        .collect();
    let locals = module
        .params
        .iter()
        .map(|p| unique(&snake(&p.name), &mut taken))
        .collect();
    let ctx = Ctx {
        module,
        rt: quote!(#rt),
        ty,
        fields: module.params.iter().map(|p| field_ident(&p.name)).collect(),
        locals,
    };
    let mut out = struct_items(&ctx, opts);
    let name = opts
        .energy_name
        .clone()
        .unwrap_or_else(|| module.name.clone());
    for d in &module.dims {
        out.extend(energy_impl(&ctx, d, &name));
        if let Some(f) = &d.fibre {
            out.extend(crate::fibre::fibre_impl(&fibre_ctx(&ctx), d.dim, f, &name));
        }
    }
    Ok(out)
}

/// The fibre back end's view of the context ([`crate::fibre`]).
fn fibre_ctx<'a>(ctx: &'a Ctx<'_>) -> crate::fibre::FibreCtx<'a> {
    crate::fibre::FibreCtx {
        rt: &ctx.rt,
        ty: &ctx.ty,
        names: ctx.module.params.iter().map(|p| p.name.as_str()).collect(),
        fields: &ctx.fields,
        locals: &ctx.locals,
    }
}

fn type_ident(name: &str) -> Result<Ident, CodegenError> {
    let bad = || CodegenError::InvalidTypeName {
        name: name.to_string(),
    };
    if is_keyword(name) {
        return Err(bad());
    }
    syn::parse_str::<Ident>(name).map_err(|_| bad())
}

/// The struct field for a parameter: its own name, raw if it is a keyword,
/// with a trailing `_` if it cannot even be raw (`self`, `Self`, `super`, `crate`, `_`).
fn field_ident(name: &str) -> Ident {
    match name {
        "self" | "Self" | "super" | "crate" | "_" => format_ident!("{}_", name),
        n if is_keyword(n) => Ident::new_raw(n, Span::call_site()),
        n => Ident::new(n, Span::call_site()),
    }
}

/// A snake-case local name for a parameter (`E` → `e`, `lambda` → `lambda`).
fn snake(name: &str) -> String {
    let mut s = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 && !s.ends_with('_') {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        } else {
            s.push(c);
        }
    }
    let s = s.trim_start_matches('_').to_string();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        format!("p_{s}")
    } else {
        s
    }
}

/// Check the IR's shape so that emission can index it freely.
fn validate(d: &DimIr, n_params: usize) -> Result<(), CodegenError> {
    let bad = |what: String| CodegenError::MalformedIr { dim: d.dim, what };
    if d.dim != 2 && d.dim != 3 {
        return Err(bad(format!("dimension {} is not 2 or 3", d.dim)));
    }
    let n = d.dim as usize;
    let len = d.graph.len();
    let check = |id: Id, what: &str| {
        if id.index() < len {
            Ok(())
        } else {
            Err(bad(format!("{what} refers to node {} of {len}", id.0)))
        }
    };
    check(d.psi, "psi")?;
    if d.spectral.grad.len() != n {
        return Err(bad(format!("{} gradient entries", d.spectral.grad.len())));
    }
    for &g in &d.spectral.grad {
        check(g, "gradient")?;
    }
    match &d.spectral.scale {
        ScaleIr::Diagonal(a) => {
            if a.len() != n {
                return Err(bad(format!("{} diagonal scaling entries", a.len())));
            }
            for &x in a {
                check(x, "scaling block")?;
            }
        }
        ScaleIr::Full(a) => {
            if a.len() != n || a.iter().any(|r| r.len() != n) {
                return Err(bad("scaling block is not d×d".into()));
            }
            for &x in a.iter().flatten() {
                check(x, "scaling block")?;
            }
        }
    }
    let p = pairs(d.dim);
    if d.spectral.twist.len() != p || d.spectral.flip.len() != p {
        return Err(bad(format!(
            "{} twist and {} flip slots, expected {p}",
            d.spectral.twist.len(),
            d.spectral.flip.len()
        )));
    }
    let kinds = (d.spectral.twist_kind.len(), d.spectral.flip_kind.len());
    if kinds != (p, p) {
        return Err(bad(format!(
            "{} twist and {} flip kinds, expected {p}",
            kinds.0, kinds.1
        )));
    }
    for pr in d.spectral.twist.iter().chain(&d.spectral.flip) {
        match *pr {
            PairIr::Exact(x) => check(x, "pair")?,
            PairIr::Guarded { direct, limit, den } => {
                check(direct, "pair")?;
                check(limit, "pair")?;
                check(den, "pair")?;
            }
        }
    }
    for node in d.graph.nodes() {
        if let ecc_dsl::Node::Sym(Sym::Param(k)) = node
            && *k as usize >= n_params
        {
            return Err(bad(format!("parameter {k} is not declared")));
        }
        if let ecc_dsl::Node::Sym(Sym::Sigma(k)) = node
            && *k >= d.dim
        {
            return Err(bad(format!("s{} does not exist", k + 1)));
        }
    }
    Ok(())
}

fn doc_lines(ctx: &Ctx, opts: &GenOptions) -> Vec<String> {
    let m = ctx.module;
    let mut lines: Vec<String> = Vec::new();
    if let Some(doc) = &opts.doc {
        lines.extend(doc.lines().map(|l| format!(" {l}")));
        lines.push(String::new());
    }
    lines.push(format!(
        " Energy `{}`, generated by ecc-codegen from:",
        m.name
    ));
    lines.push(String::new());
    lines.push(" ```text".into());
    lines.extend(m.source.trim_end().lines().map(|l| format!(" {l}")));
    lines.push(" ```".into());
    lines.push(String::new());
    lines.push(format!(" Parameters: {}.", params_line(m)));
    for d in &m.dims {
        lines.push(String::new());
        lines.push(format!(" {}D:", d.dim));
        for f in dim_facts(d) {
            lines.push(format!(" - {f}"));
        }
    }
    lines
}

fn struct_items(ctx: &Ctx, opts: &GenOptions) -> TokenStream {
    let ty = &ctx.ty;
    let vis = match opts.vis {
        Visibility::Public => quote!(pub),
        Visibility::Crate => quote!(pub(crate)),
        Visibility::Private => quote!(),
    };
    let dead = if opts.vis == Visibility::Private {
        quote!(#[allow(dead_code)])
    } else {
        quote!()
    };
    let docs = doc_lines(ctx, opts);
    let source = ctx.module.source.as_str();
    let params = &ctx.module.params;
    if params.is_empty() {
        return quote! {
            #(#[doc = #docs])*
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
            #dead
            #vis struct #ty;

            #dead
            impl #ty {
                /// The energy's source text.
                pub const SOURCE: &'static str = #source;

                /// The energy (it has no parameters).
                pub const fn new() -> Self {
                    #ty
                }
            }
        };
    }
    let fields = &ctx.fields;
    let field_docs: Vec<String> = params
        .iter()
        .map(|p| format!(" Parameter `{}` (default {}).", p.name, p.default))
        .collect();
    let defaults: Vec<TokenStream> = params.iter().map(|p| Ex::Lit(p.default).tokens()).collect();
    let non_snake = if params
        .iter()
        .any(|p| p.name.chars().any(|c| c.is_ascii_uppercase()))
    {
        quote!(#[allow(non_snake_case)])
    } else {
        quote!()
    };
    quote! {
        #(#[doc = #docs])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        #non_snake
        #dead
        #vis struct #ty {
            #(#[doc = #field_docs] pub #fields: f64,)*
        }

        #dead
        impl #ty {
            /// The energy's source text.
            pub const SOURCE: &'static str = #source;

            /// The energy with the parameter defaults of its source.
            pub const fn new() -> Self {
                #ty { #(#fields: #defaults),* }
            }
        }

        impl ::core::default::Default for #ty {
            fn default() -> Self {
                Self::new()
            }
        }
    }
}

/// Lints that generated arithmetic may trip and that are not worth fighting.
fn allows() -> TokenStream {
    quote! {
        #[allow(
            clippy::approx_constant,
            clippy::excessive_precision,
            clippy::unreadable_literal,
            clippy::too_many_lines,
            clippy::many_single_char_names,
            clippy::similar_names,
            clippy::suboptimal_flops,
            clippy::float_cmp,
            non_snake_case
        )]
    }
}

fn leaf_namer<'c>(ctx: &'c Ctx<'_>) -> impl Fn(Sym) -> String + 'c {
    move |s| match s {
        Sym::Sigma(k) => format!("s{}", k + 1),
        Sym::I1 => "i1".into(),
        Sym::I2 => "i2".into(),
        Sym::I3 => "i3".into(),
        Sym::Param(k) => ctx.locals[k as usize].clone(),
        Sym::I4 => "i4".into(),
        Sym::I5 => "i5".into(),
        Sym::SignI4 => "sign_i4".into(),
    }
}

/// `let s1 = sigma[0]; …`, parameters and invariants, as the plan needs them.
fn prelude(ctx: &Ctx, dim: u8, plan: &Plan, extra_sigma: &[usize]) -> TokenStream {
    let leaves = plan.leaves();
    let n = dim as usize;
    let uses_inv = leaves
        .iter()
        .any(|s| matches!(s, Sym::I1 | Sym::I2 | Sym::I3));
    let mut out = TokenStream::new();
    for k in 0..n {
        if uses_inv || leaves.contains(&Sym::Sigma(k as u8)) || extra_sigma.contains(&k) {
            let s = format_ident!("s{}", k + 1);
            let k = int(k);
            out.extend(quote!(let #s = sigma[#k];));
        }
    }
    let s: Vec<Ident> = (1..=n).map(|k| format_ident!("s{}", k)).collect();
    for sym in leaves {
        match sym {
            Sym::Param(k) => {
                let local = format_ident!("{}", ctx.locals[*k as usize]);
                let field = &ctx.fields[*k as usize];
                out.extend(quote!(let #local = self.#field;));
            }
            Sym::I1 => out.extend(quote!(let i1 = #(#s)+*;)),
            Sym::I2 => out.extend(quote!(let i2 = #(#s * #s)+*;)),
            Sym::I3 => {
                let (first, rest) = (&s[0], &s[1..]);
                out.extend(quote!(let i3 = #first #(* #rest)*;));
            }
            // Only in a fibre part, whose prelude is `fibre::prelude`.
            Sym::Sigma(_) | Sym::I4 | Sym::I5 | Sym::SignI4 => {}
        }
    }
    out
}

/// `sigma`, or `_sigma` when the prelude reads no σ (Ψ_iso = 0 of a pure
/// fibre energy, or Ψ depending on parameters only).
fn sigma_arg(plan: &Plan, extra_sigma: &[usize]) -> TokenStream {
    let reads = !extra_sigma.is_empty()
        || plan
            .leaves()
            .iter()
            .any(|s| matches!(s, Sym::Sigma(_) | Sym::I1 | Sym::I2 | Sym::I3));
    if reads { quote!(sigma) } else { quote!(_sigma) }
}

/// The value of Ψ as a name that can take method calls.
fn psi_binding(plan: &Plan, psi: Id) -> (TokenStream, TokenStream) {
    if plan.is_bound(psi) {
        (TokenStream::new(), plan.value(psi))
    } else {
        let v = plan.value(psi);
        (quote!(let psi: f64 = #v;), quote!(psi))
    }
}

/// An unsuffixed integer literal (`2`, not `2usize`).
fn int(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

fn energy_impl(ctx: &Ctx, d: &DimIr, name: &str) -> TokenStream {
    let rt = &ctx.rt;
    let ty = &ctx.ty;
    let dim = int(d.dim as usize);
    let psi_fn = psi_fn(ctx, d);
    let spectral_fn = spectral_fn(ctx, d);
    let (i2i3_fn, svd_free) = psi_i2_i3_fn(ctx, d);
    let barrier = d.barrier;
    let param_fns = param_fns(ctx);
    let allows = allows();
    quote! {
        #allows
        impl #rt::Energy<#dim> for #ty {
            fn name(&self) -> &str {
                #name
            }

            #psi_fn

            #spectral_fn

            fn info(&self) -> #rt::EnergyInfo {
                #rt::EnergyInfo {
                    barrier: #barrier,
                    svd_free_psi: #svd_free,
                }
            }

            #i2i3_fn

            #param_fns
        }
    }
}

/// `psi.is_finite()`, and every active domain condition (`&& i3 > 0.0`).
fn inside(d: &DimIr, plan: &Plan, psi: &TokenStream) -> TokenStream {
    let mut out = quote!(#psi.is_finite());
    for (arg, rel) in domain::tests(d, plan) {
        let arg = arg.tokens();
        out.extend(match rel {
            ">" => quote!(&& #arg > 0.0),
            _ => quote!(&& #arg >= 0.0),
        });
    }
    out
}

fn psi_fn(ctx: &Ctx, d: &DimIr) -> TokenStream {
    let dim = int(d.dim as usize);
    let roots = psi_roots(d);
    let namer = leaf_namer(ctx);
    let plan = Plan::new(&d.graph, d.dim, &roots, &hints(d), &namer, RESERVED);
    let prelude = prelude(ctx, d.dim, &plan, &[]);
    let lets = plan.lets(Region::Psi);
    let (bind, psi) = psi_binding(&plan, d.psi);
    let inside = inside(d, &plan, &psi);
    let sigma = sigma_arg(&plan, &[]);
    quote! {
        fn psi(&self, #sigma: &[f64; #dim]) -> f64 {
            #prelude
            #lets
            #bind
            if #inside { #psi } else { f64::INFINITY }
        }
    }
}

/// `psi_i2_i3` when Ψ is SVD-free and written in I2, I3 (and parameters) only.
fn psi_i2_i3_fn(ctx: &Ctx, d: &DimIr) -> (TokenStream, bool) {
    if !d.svd_free {
        return (TokenStream::new(), false);
    }
    let roots = psi_roots(d);
    let namer = leaf_namer(ctx);
    let plan = Plan::new(&d.graph, d.dim, &roots, &hints(d), &namer, RESERVED);
    let leaves = plan.leaves();
    if leaves
        .iter()
        .any(|s| !matches!(s, Sym::I2 | Sym::I3 | Sym::Param(_)))
    {
        return (TokenStream::new(), false);
    }
    let i2 = if leaves.contains(&Sym::I2) {
        quote!(i2)
    } else {
        quote!(_i2)
    };
    let i3 = if leaves.contains(&Sym::I3) {
        quote!(i3)
    } else {
        quote!(_i3)
    };
    let params: TokenStream = leaves
        .iter()
        .filter_map(|s| match s {
            Sym::Param(k) => {
                let local = format_ident!("{}", ctx.locals[*k as usize]);
                let field = &ctx.fields[*k as usize];
                Some(quote!(let #local = self.#field;))
            }
            _ => None,
        })
        .collect();
    let lets = plan.lets(Region::Psi);
    let (bind, psi) = psi_binding(&plan, d.psi);
    let inside = inside(d, &plan, &psi);
    let f = quote! {
        fn psi_i2_i3(&self, #i2: f64, #i3: f64) -> Option<f64> {
            #params
            #lets
            #bind
            Some(if #inside { #psi } else { f64::INFINITY })
        }
    };
    (f, true)
}

fn pair_name(kind: &str, dim: u8, slot: usize) -> String {
    let (i, j) = pair_label(dim, slot);
    format!("{kind}_{i}{j}")
}

/// A guarded pair: its slot, local name, the IR ids and its two branch regions.
struct Guard {
    slot: usize,
    name: String,
    direct: Id,
    limit: Id,
    den: Id,
    branches: (u32, u32),
}

/// The roots of the spectral function (Ψ, gradient, scaling block, pairs) and
/// the guarded pairs among them.
fn spectral_roots(d: &DimIr) -> (Vec<Root>, Vec<Guard>) {
    let sp = &d.spectral;
    let main = |id: Id, name: String| Root {
        id,
        region: Region::Main,
        name,
        bind: true,
    };
    let mut roots = psi_roots(d);
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
            let name = pair_name(kind, d.dim, slot);
            match *pr {
                PairIr::Exact(x) => roots.push(main(x, name)),
                PairIr::Guarded { direct, limit, den } => {
                    let (bl, bd) = (branch, branch + 1);
                    branch += 2;
                    roots.push(Root {
                        id: den,
                        region: Region::Main,
                        name: format!("{kind}_den_{}", &name[name.len() - 2..]),
                        bind: false,
                    });
                    for (id, b, suffix) in [(limit, bl, "limit"), (direct, bd, "direct")] {
                        roots.push(Root {
                            id,
                            region: Region::Branch(b),
                            name: format!("{name}_{suffix}"),
                            bind: false,
                        });
                    }
                    guards.push(Guard {
                        slot,
                        name,
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

/// `let twist_12 = if |den| <= τ·max(|s1|, |s2|) { limit } else { direct };`
/// per guarded pair (the branches' bindings live inside their arm).
fn guard_lets(rt: &TokenStream, d: &DimIr, plan: &Plan, guards: &[Guard]) -> TokenStream {
    let mut out = TokenStream::new();
    for g in guards {
        let (i, j) = pair_label(d.dim, g.slot);
        let (si, sj) = (format_ident!("s{}", i), format_ident!("s{}", j));
        let abs_den = Ex::Method(Box::new(plan.value_ex(g.den)), "abs", vec![]).tokens();
        let (bl, bd) = g.branches;
        let lim_lets = plan.lets(Region::Branch(bl));
        let lim_v = plan.value(g.limit);
        let dir_lets = plan.lets(Region::Branch(bd));
        let dir_v = plan.value(g.direct);
        let var = format_ident!("{}", g.name);
        out.extend(quote! {
            let #var = if #abs_den <= #rt::divided::LIMIT_TOL * #si.abs().max(#sj.abs()) {
                #lim_lets
                #lim_v
            } else {
                #dir_lets
                #dir_v
            };
        });
    }
    out
}

/// The stretches a pair's guard or pole test reads (0-based).
fn pair_sigmas(d: &DimIr, guards: &[Guard]) -> Vec<usize> {
    let mut out = Vec::new();
    for g in guards {
        let (i, j) = pair_label(d.dim, g.slot);
        out.extend([i - 1, j - 1]);
    }
    for (slot, kind) in d.spectral.twist_kind.iter().enumerate() {
        if *kind == PairKind::Pole {
            let (i, j) = pair_label(d.dim, slot);
            out.extend([i - 1, j - 1]);
        }
    }
    out
}

/// The `ScaleBlock` expression.
fn scale_tokens(rt: &TokenStream, d: &DimIr, plan: &Plan) -> TokenStream {
    match &d.spectral.scale {
        ScaleIr::Diagonal(a) => {
            let v: Vec<TokenStream> = a.iter().map(|&x| plan.value(x)).collect();
            quote!(#rt::ScaleBlock::Diagonal([#(#v),*]))
        }
        ScaleIr::Full(a) => {
            let n = d.dim as usize;
            let rows: Vec<TokenStream> = (0..n)
                .map(|i| {
                    let v: Vec<TokenStream> =
                        (0..n).map(|j| plan.value(a[i.min(j)][i.max(j)])).collect();
                    quote!([#(#v),*])
                })
                .collect();
            quote!(#rt::ScaleBlock::Full([#(#rows),*]))
        }
    }
}

/// The three slot values of `twist` or `flip`: a closed form, the guarded
/// local, or for a pole `+∞` exactly on σi + σj = 0 (never NaN) and the
/// quotient elsewhere; unused 2D slots are 0.
fn slot_values(
    d: &DimIr,
    plan: &Plan,
    kind: &str,
    list: &[PairIr],
    kinds: &[PairKind],
) -> Vec<TokenStream> {
    let mut v: Vec<TokenStream> = list
        .iter()
        .enumerate()
        .map(|(slot, pr)| match *pr {
            PairIr::Exact(x) if kinds.get(slot) == Some(&PairKind::Pole) => {
                let (i, j) = pair_label(d.dim, slot);
                let (si, sj) = (format_ident!("s{}", i), format_ident!("s{}", j));
                let val = plan.value(x);
                quote!(if #si + #sj == 0.0 { f64::INFINITY } else { #val })
            }
            PairIr::Exact(x) => plan.value(x),
            PairIr::Guarded { .. } => {
                let var = format_ident!("{}", pair_name(kind, d.dim, slot));
                quote!(#var)
            }
        })
        .collect();
    while v.len() < 3 {
        v.push(quote!(0.0));
    }
    v
}

/// The spectral function: Ψ, the domain check, gradient, scaling block and
/// the twist/flip pairs (guarded ones as a lazy `if`, poles +∞ on their plane).
fn spectral_fn(ctx: &Ctx, d: &DimIr) -> TokenStream {
    let rt = &ctx.rt;
    let dim_lit = int(d.dim as usize);
    let sp = &d.spectral;
    let (roots, guards) = spectral_roots(d);
    let namer = leaf_namer(ctx);
    let mut taken: Vec<&str> = RESERVED.to_vec();
    taken.extend(guards.iter().map(|g| g.name.as_str()));
    let plan = Plan::new(&d.graph, d.dim, &roots, &hints(d), &namer, &taken);
    let extra = pair_sigmas(d, &guards);
    let prelude = prelude(ctx, d.dim, &plan, &extra);
    let sigma = sigma_arg(&plan, &extra);
    let psi_lets = plan.lets(Region::Psi);
    let (bind, psi) = psi_binding(&plan, d.psi);
    let main_lets = plan.lets(Region::Main);
    let guard_lets = guard_lets(rt, d, &plan, &guards);
    let outside = if d.active_guards().next().is_none() {
        quote!(!#psi.is_finite())
    } else {
        let inside = inside(d, &plan, &psi);
        quote!(!(#inside))
    };
    let psi_field = if psi.to_string() == "psi" {
        quote!(psi)
    } else {
        quote!(psi: #psi)
    };
    let grad: Vec<TokenStream> = sp.grad.iter().map(|&g| plan.value(g)).collect();
    let scale = scale_tokens(rt, d, &plan);
    let twist = slot_values(d, &plan, "twist", &sp.twist, &sp.twist_kind);
    let flip = slot_values(d, &plan, "flip", &sp.flip, &sp.flip_kind);
    quote! {
        fn spectral(&self, #sigma: &[f64; #dim_lit]) -> #rt::Spectral<#dim_lit> {
            #prelude
            #psi_lets
            #bind
            if #outside {
                return #rt::Spectral::infinite();
            }
            #main_lets
            #guard_lets
            #rt::Spectral {
                #psi_field,
                grad: [#(#grad),*],
                scale: #scale,
                twist: [#(#twist),*],
                flip: [#(#flip),*],
            }
        }
    }
}

/// `params()` and `set_param()` (only when the energy has parameters).
fn param_fns(ctx: &Ctx) -> TokenStream {
    let names: Vec<&str> = ctx.module.params.iter().map(|p| p.name.as_str()).collect();
    let (get, set) = (format_ident!("params"), format_ident!("set_param"));
    param_methods(&ctx.rt, &names, &ctx.fields, &get, &set)
}

/// The getter `get()` (name, value) pairs and the setter `set(name, value)`
/// over the struct fields `fields` of the parameters `names` (nothing when
/// there are none): shared by `Energy` and `FibreEnergy` impls.
pub(crate) fn param_methods(
    rt: &TokenStream,
    names: &[&str],
    fields: &[Ident],
    get: &Ident,
    set: &Ident,
) -> TokenStream {
    if names.is_empty() {
        return TokenStream::new();
    }
    quote! {
        fn #get(&self) -> Vec<(String, f64)> {
            vec![#((#names.to_string(), self.#fields)),*]
        }

        fn #set(&mut self, name: &str, value: f64) -> Result<(), #rt::ParamError> {
            if !value.is_finite() {
                return Err(#rt::ParamError::NotFinite { name: name.to_string(), value });
            }
            match name {
                #(#names => self.#fields = value,)*
                _ => {
                    return Err(#rt::ParamError::Unknown {
                        name: name.to_string(),
                        known: vec![#(#names.to_string()),*],
                    });
                }
            }
            Ok(())
        }
    }
}
