//! The generated `FibreEnergy<D>` impl of an energy with `fiber a`
//! ([`ecc_dsl::FibreIr`]): the same struct (the parameters are shared with
//! its `Energy<D>` impl, which is the isotropic part Ψ_iso) evaluates
//! ψ(I4, I5) and its partials [ψ4, ψ5, ψ44, ψ45, ψ55] straight from the
//! CAS's expressions, with ψ's domain conditions tested first (ψ = +∞ and
//! zero derivatives outside, as for Ψ). `uses()` is what the CAS decided
//! (which invariants ψ reads), so the runtime picks the closed-form I5
//! eigensystem or the numeric block (`ecc_runtime::fibre::point`).

use std::collections::HashMap;

use ecc_dsl::{DomainCond, FibreIr, FibreUses, Sym};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::plan::{Plan, Region, Root};

/// Local names of the generated `fibre` function (parameters' locals avoid them).
pub(crate) const RESERVED: &[&str] = &["i4", "i5", "sign_i4", "name", "value"];

/// What the fibre impl needs of the energy's context.
pub(crate) struct FibreCtx<'a> {
    /// The runtime crate path.
    pub rt: &'a TokenStream,
    /// The struct.
    pub ty: &'a Ident,
    /// Parameter names as declared.
    pub names: Vec<&'a str>,
    /// Struct field of each parameter.
    pub fields: &'a [Ident],
    /// Local variable of each parameter.
    pub locals: &'a [String],
}

/// `impl FibreEnergy<dim> for Ty { … }`.
pub(crate) fn fibre_impl(c: &FibreCtx, dim: u8, f: &FibreIr, name: &str) -> TokenStream {
    let rt = c.rt;
    let ty = c.ty;
    let dim = Literal::usize_unsuffixed(usize::from(dim));
    let body = fibre_body(c, f);
    let uses = match f.uses {
        FibreUses::None => quote!(None),
        FibreUses::I4 => quote!(I4),
        FibreUses::I5 => quote!(I5),
        FibreUses::Both => quote!(Both),
    };
    let params = param_fns(c);
    quote! {
        #[allow(
            clippy::approx_constant,
            clippy::excessive_precision,
            clippy::unreadable_literal,
            clippy::suboptimal_flops,
            clippy::float_cmp,
            non_snake_case
        )]
        impl #rt::FibreEnergy<#dim> for #ty {
            fn name(&self) -> &str {
                #name
            }

            #body

            fn uses(&self) -> #rt::FibreUse {
                #rt::FibreUse::#uses
            }

            #params
        }
    }
}

fn root(id: ecc_dsl::Id, region: Region, name: &str, bind: bool) -> Root {
    Root {
        id,
        region,
        name: name.into(),
        bind,
    }
}

/// `fn fibre(&self, i4, i5) -> FibreDerivs`.
fn fibre_body(c: &FibreCtx, f: &FibreIr) -> TokenStream {
    let rt = c.rt;
    let mut roots = vec![root(f.psi, Region::Psi, "psi", true)];
    for g in f.active_guards() {
        roots.push(root(g.arg, Region::Psi, "domain_arg", false));
    }
    let names = ["d4", "d5", "d44", "d45", "d55"];
    let ids = [f.d4, f.d5, f.d44, f.d45, f.d55];
    for (id, n) in ids.iter().zip(names) {
        roots.push(root(*id, Region::Main, n, false));
    }
    let namer = |s: Sym| match s {
        Sym::I4 => "i4".to_string(),
        Sym::I5 => "i5".to_string(),
        Sym::SignI4 => "sign_i4".to_string(),
        Sym::Param(k) => c.locals[usize::from(k)].clone(),
        // A fibre graph has no other leaves (`ecc_dsl::FibreIr`).
        _ => "f64::NAN".to_string(),
    };
    let mut taken: Vec<&str> = RESERVED.to_vec();
    taken.extend(names);
    let plan = Plan::new(&f.graph, 3, &roots, &HashMap::new(), &namer, &taken);
    let prelude = prelude(c, &plan);
    let psi_lets = plan.lets(Region::Psi);
    let psi = plan.value(f.psi);
    let bind = if plan.is_bound(f.psi) {
        TokenStream::new()
    } else {
        quote!(let psi: f64 = #psi;)
    };
    let inside = inside(f, &plan);
    let main_lets = plan.lets(Region::Main);
    let d: Vec<TokenStream> = ids.iter().map(|&id| plan.value(id)).collect();
    let [d4, d5, d44, d45, d55] = [&d[0], &d[1], &d[2], &d[3], &d[4]];
    let leaves = plan.leaves();
    let i4 = arg(
        leaves.contains(&Sym::I4) || leaves.contains(&Sym::SignI4),
        "i4",
    );
    let i5 = arg(leaves.contains(&Sym::I5), "i5");
    quote! {
        fn fibre(&self, #i4: f64, #i5: f64) -> #rt::FibreDerivs {
            #prelude
            #psi_lets
            #bind
            if !(psi.is_finite() #inside) {
                return #rt::FibreDerivs { psi: f64::INFINITY, ..#rt::FibreDerivs::default() };
            }
            #main_lets
            #rt::FibreDerivs { psi, d4: #d4, d5: #d5, d44: #d44, d45: #d45, d55: #d55 }
        }
    }
}

/// `name`, or `_name` when the body does not read it.
fn arg(used: bool, name: &str) -> Ident {
    if used {
        format_ident!("{}", name)
    } else {
        format_ident!("_{}", name)
    }
}

/// `let sign_i4 = …;` and the parameters' locals, as the plan reads them.
fn prelude(c: &FibreCtx, plan: &Plan) -> TokenStream {
    let mut out = TokenStream::new();
    for sym in plan.leaves() {
        match sym {
            Sym::SignI4 => out.extend(quote! {
                // sign(I4): +1 for I4 > 0, −1 otherwise (HOBAK's convention).
                let sign_i4: f64 = if i4 > 0.0 { 1.0 } else if i4.is_nan() { f64::NAN } else { -1.0 };
            }),
            Sym::Param(k) => {
                let local = format_ident!("{}", c.locals[usize::from(*k)]);
                let field = &c.fields[usize::from(*k)];
                out.extend(quote!(let #local = self.#field;));
            }
            _ => {}
        }
    }
    out
}

/// `&& arg > 0.0` … for each active domain condition of ψ.
fn inside(f: &FibreIr, plan: &Plan) -> TokenStream {
    let mut out = TokenStream::new();
    for g in f.active_guards() {
        let v = plan.value(g.arg);
        out.extend(match g.cond {
            DomainCond::Positive => quote!(&& #v > 0.0),
            DomainCond::NonNegative => quote!(&& #v >= 0.0),
            DomainCond::NonZero => quote!(&& (#v).abs() > 0.0),
        });
    }
    out
}

/// `fibre_params()` and `set_fibre_param()` over the shared parameters.
fn param_fns(c: &FibreCtx) -> TokenStream {
    let (get, set) = (
        format_ident!("fibre_params"),
        format_ident!("set_fibre_param"),
    );
    crate::energy::param_methods(c.rt, &c.names, c.fields, &get, &set)
}
