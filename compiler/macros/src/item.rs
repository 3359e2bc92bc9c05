//! The item form's header: `#[doc]`s, visibility, `struct Name;`.

use proc_macro2::{Delimiter, Ident, Span, TokenStream, TokenTree};

use ecc_codegen::Visibility;

/// The parsed header of `energy! { pub struct Name; … }`.
pub(crate) struct Header {
    pub docs: Vec<String>,
    pub vis: Visibility,
    pub name: Ident,
}

/// Split the input into the item header (if the input starts with
/// attributes, `pub` or `struct`) and the energy statements after it.
pub(crate) fn split(input: TokenStream) -> Result<(Option<Header>, TokenStream), syn::Error> {
    let tts: Vec<TokenTree> = input.into_iter().collect();
    let mut i = 0;
    let mut docs = Vec::new();
    while let (Some(TokenTree::Punct(p)), Some(TokenTree::Group(g))) = (tts.get(i), tts.get(i + 1))
    {
        if p.as_char() != '#' || g.delimiter() != Delimiter::Bracket {
            break;
        }
        docs.push(doc_text(g.stream()).ok_or_else(|| {
            syn::Error::new(
                g.span(),
                "only doc comments may be attached to an energy struct",
            )
        })?);
        i += 2;
    }
    let is_item = !docs.is_empty()
        || matches!(tts.get(i), Some(TokenTree::Ident(id)) if id == "pub" || id == "struct");
    if !is_item {
        return Ok((None, tts.into_iter().collect()));
    }
    let mut vis = Visibility::Private;
    if let Some(TokenTree::Ident(id)) = tts.get(i)
        && id == "pub"
    {
        vis = Visibility::Public;
        i += 1;
        if let Some(TokenTree::Group(g)) = tts.get(i)
            && g.delimiter() == Delimiter::Parenthesis
        {
            if g.stream().to_string() != "crate" {
                return Err(syn::Error::new(
                    g.span(),
                    "an energy struct is `pub`, `pub(crate)` or private",
                ));
            }
            vis = Visibility::Crate;
            i += 1;
        }
    }
    let here = |k: usize| tts.get(k).map_or_else(Span::call_site, TokenTree::span);
    match tts.get(i) {
        Some(TokenTree::Ident(id)) if id == "struct" => i += 1,
        _ => return Err(syn::Error::new(here(i), "expected `struct Name;`")),
    }
    let name = match tts.get(i) {
        Some(TokenTree::Ident(id)) => id.clone(),
        _ => return Err(syn::Error::new(here(i), "expected the energy's type name")),
    };
    i += 1;
    match tts.get(i) {
        Some(TokenTree::Punct(p)) if p.as_char() == ';' => i += 1,
        _ => {
            return Err(syn::Error::new(
                here(i),
                "expected `;` after the type name (`pub struct Name;`)",
            ));
        }
    }
    let rest = tts[i..].iter().cloned().collect();
    Ok((Some(Header { docs, vis, name }), rest))
}

/// The text of `doc = "…"`.
fn doc_text(attr: TokenStream) -> Option<String> {
    let tts: Vec<TokenTree> = attr.into_iter().collect();
    match tts.as_slice() {
        [
            TokenTree::Ident(d),
            TokenTree::Punct(eq),
            TokenTree::Literal(l),
        ] if d == "doc" && eq.as_char() == '=' => {
            let lit: syn::LitStr = syn::parse2(TokenTree::Literal(l.clone()).into()).ok()?;
            Some(lit.value())
        }
        _ => None,
    }
}

/// `MyEnergy` → `my_energy` (the energy's `name()`).
pub(crate) fn snake(name: &str) -> String {
    let mut s = String::new();
    for (k, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if k > 0 {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        } else {
            s.push(c);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<(Option<Header>, TokenStream), syn::Error> {
        split(s.parse().unwrap_or_default())
    }

    #[test]
    fn expression_form_has_no_header() {
        let (h, rest) = parse("I2 - 2*I1 + 3").unwrap_or_else(|e| panic!("{e}"));
        assert!(h.is_none());
        assert_eq!(rest.to_string(), "I2 - 2 * I1 + 3");
    }

    #[test]
    fn item_form_header() {
        let (h, rest) = parse("/// Docs.\npub(crate) struct Snh; param mu = 1; psi = mu*I2")
            .unwrap_or_else(|e| panic!("{e}"));
        let h = h.unwrap_or_else(|| panic!("no header"));
        assert_eq!(h.name.to_string(), "Snh");
        assert_eq!(h.vis, Visibility::Crate);
        assert_eq!(h.docs, vec![" Docs.".to_string()]);
        assert!(rest.to_string().starts_with("param"));
    }

    #[test]
    fn header_errors() {
        assert!(parse("pub struct Snh psi = I2").is_err());
        assert!(parse("pub(super) struct Snh; psi = I2").is_err());
        assert!(parse("pub fn x; psi = I2").is_err());
        assert!(parse("#[derive(Debug)] struct X; psi = I2").is_err());
    }

    #[test]
    fn snake_names() {
        assert_eq!(snake("MyEnergy"), "my_energy");
        assert_eq!(snake("Snh"), "snh");
    }
}
