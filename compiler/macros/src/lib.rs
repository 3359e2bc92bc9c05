//! # ecc-macros: the `energy!` macro
//!
//! Write an isotropic energy as a formula and get a type implementing
//! `ecc_runtime::Energy<2>` and/or `Energy<3>`, with exact derivatives,
//! closed-form eigenvalues where the CAS proves them, and filtered Hessians
//! through the runtime — all generated at compile time by `ecc-codegen`.
//!
//! Depend on both `ecc-runtime` (the generated code refers to
//! `::ecc_runtime`) and `ecc-macros`.
//!
//! ## Expression form
//!
//! ```
//! use ecc_runtime::{Energy, ScaleBlock};
//! let arap = ecc_macros::energy!(I2 - 2*I1 + d);      // a value of a generated type
//! let s = Energy::<3>::spectral(&arap, &[1.2, 1.0, 0.9]);
//! assert_eq!(s.scale, ScaleBlock::Diagonal([2.0; 3])); // proved decoupled
//! ```
//!
//! The input may also hold statements separated by `;`
//! (`energy!(param k = 2; psi = k*(I2 - 2*I1 + d))`). It expands to a block
//! that defines a private struct and returns `Struct::new()`.
//!
//! ## Item form
//!
//! ```
//! ecc_macros::energy! {
//!     /// Stable Neo-Hookean.
//!     pub struct Snh;
//!     param mu = 1.0;
//!     param lambda = 10.0;
//!     let alpha = 1 + mu/lambda - mu/((d + 1)*lambda);
//!     psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1);
//! }
//! let mut e = Snh::new();        // or Snh::default(); fields `mu`, `lambda`
//! e.lambda = 100.0;
//! use ecc_runtime::Energy;
//! assert!(Energy::<3>::psi(&e, &[1.0, 1.0, 1.0]).is_finite());
//! ```
//!
//! Doc comments are kept; the visibility is `pub`, `pub(crate)` or private;
//! `dim 2;` or `dim 3;` restricts the dimensions (otherwise every dimension
//! the formula makes sense in is generated). Statements are the energy
//! language's (`param`, `let`, `psi =`, `dim`), separated by `;`.
//!
//! ## Errors
//!
//! Errors of the formula become `compile_error!`s at the offending tokens:
//! a syntax error at the token where parsing stopped, an unknown identifier
//! at that identifier, a non-isotropic stretch energy at its `psi`
//! expression. The macro never panics.
//!
//! Comments are Rust's `//` and `/* */` (Rust removes them before the macro
//! sees its input). A `#` — a comment in `.psi` files — is an error at the
//! `#` here: the input has no lines, so a `.psi` comment would silently drop
//! everything after it. A literal that does not fit an f64 (`1e400`) is an
//! error at the literal, as in `.psi` files.
//!
//! ## Why not `energy!<…>`?
//!
//! A macro invocation is `path!` followed by a delimited token tree — `( )`,
//! `[ ]` or `{ }`. Angle brackets are not delimiters in Rust's token model
//! (`<` and `>` are ordinary punctuation that may be unbalanced), so
//! `energy!<I2 - 2*I1 + d>` cannot be parsed by the compiler and no macro
//! can accept it. Use `energy!(…)` or `energy! { … }`.

mod item;
mod text;

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use ecc_codegen::{GenOptions, Visibility};
use ecc_dsl::Error as DslError;

use crate::text::Text;

/// Generate an energy type from a formula. See the crate docs.
#[proc_macro]
pub fn energy(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand(input.into()).into()
}

fn expand(input: TokenStream) -> TokenStream {
    let (header, body) = match item::split(input) {
        Ok(x) => x,
        Err(e) => return e.to_compile_error(),
    };
    let text = Text::from_tokens(body);
    if let Some(e) = text.hash_errors() {
        return e.to_compile_error();
    }
    let (type_name, energy_name) = match &header {
        Some(h) => (h.name.to_string(), item::snake(&h.name.to_string())),
        None => ("GeneratedEnergy".to_string(), "energy".to_string()),
    };
    let module = match ecc_dsl::compile(&text.text, &energy_name) {
        Ok(m) => m,
        Err(diags) => {
            let errors = diags.errors.iter().map(|e| error_tokens(&text, e));
            return quote!(#(#errors)*);
        }
    };
    let opts = GenOptions {
        type_name: type_name.clone(),
        vis: header.as_ref().map_or(Visibility::Private, |h| h.vis),
        runtime_path: "::ecc_runtime".to_string(),
        doc: header.as_ref().filter(|h| !h.docs.is_empty()).map(|h| {
            h.docs
                .iter()
                .map(|d| d.strip_prefix(' ').unwrap_or(d))
                .collect::<Vec<_>>()
                .join("\n")
        }),
        energy_name: Some(energy_name),
    };
    let items = match ecc_codegen::generate(&module, &opts) {
        Ok(t) => t,
        Err(e) => {
            let span = header
                .as_ref()
                .map_or_else(Span::call_site, |h| h.name.span());
            return syn::Error::new(span, format!("energy!: {e}")).to_compile_error();
        }
    };
    match header {
        Some(_) => items,
        None => {
            let ty = Ident::new(&type_name, Span::call_site());
            quote!({
                #items
                #ty::new()
            })
        }
    }
}

/// A `compile_error!` for one energy-language error, spanning the Rust
/// tokens its byte range came from.
fn error_tokens(text: &Text, e: &DslError) -> TokenStream {
    let span = e.span();
    let (first, last) = text
        .spans_of(span.range())
        .unwrap_or((Span::call_site(), Span::call_site()));
    let ends = quote::quote_spanned!(first=> __first)
        .into_iter()
        .chain(quote::quote_spanned!(last=> __last));
    let ends: TokenStream = ends.collect();
    syn::Error::new_spanned(ends, message(e)).to_compile_error()
}

/// The error's message with its most useful note.
fn message(e: &DslError) -> String {
    let mut m = e.to_string();
    match e {
        DslError::UnknownIdent {
            suggestion: Some(s),
            ..
        }
        | DslError::UnknownFunction {
            suggestion: Some(s),
            ..
        } => {
            m.push_str(&format!("; did you mean `{s}`?"));
        }
        DslError::UnknownIdent {
            defined_later: Some(_),
            ..
        } => {
            m.push_str(" (it is defined later: move the definition up)");
        }
        DslError::NotIsotropic {
            no_s3: true,
            dim: 3,
            ..
        } => {
            m.push_str("; an energy in the stretches must be symmetric in them (if it is a 2D energy, add `dim 2;`)");
        }
        DslError::NotIsotropic { .. } => {
            m.push_str(
                "; an energy in the stretches must be symmetric under every permutation of them",
            );
        }
        _ => {}
    }
    m
}
