//! Rust tokens → energy-language text, remembering where each token went.
//!
//! The text reads like hand-written energy code (`mu/2*(IC - d)`): binary
//! `+`, `-` and `=` are spaced, `*`, `/`, `^`, unary signs, calls and
//! parentheses are not, and each `;` ends a line. A `Joint` punctuation is
//! glued to the next one, so `**` stays `**` and is reported as the syntax
//! error it is; brackets and braces are printed too, so that the energy
//! language reports them. Each token's byte range in the text is recorded
//! with its span, so that an error at DSL bytes `a..b` can be reported at
//! the Rust tokens covering them.

use std::ops::Range;

use proc_macro2::{Delimiter, Spacing, Span, TokenStream, TokenTree};

/// The text and the span of every token in it.
pub(crate) struct Text {
    pub text: String,
    spans: Vec<(Range<usize>, Span)>,
    /// Every `#` token, and whether it starts a doc comment (`#[doc = …]`,
    /// i.e. `///`). In the energy language `#` starts a comment to the end
    /// of the line, which would silently drop the rest of the macro input
    /// (it has no lines): these are errors, see [`Text::hash_errors`].
    hashes: Vec<(Span, bool)>,
    /// The previous token's text ("" at the start).
    prev: String,
    /// The previous token was a unary sign or a `Joint` punctuation.
    glue_next: bool,
}

/// Tokens after which a `+`/`-` is a sign, not a binary operator.
fn opens_operand(prev: &str) -> bool {
    matches!(
        prev,
        "" | "(" | "[" | "{" | "," | ";" | "=" | "+" | "-" | "*" | "/" | "^"
    )
}

impl Text {
    /// Print `tokens` as energy-language text.
    pub(crate) fn from_tokens(tokens: TokenStream) -> Text {
        let mut t = Text {
            text: String::new(),
            spans: Vec::new(),
            hashes: Vec::new(),
            prev: String::new(),
            glue_next: false,
        };
        t.push_stream(tokens);
        t
    }

    fn push(&mut self, s: &str, span: Span, joint: bool) {
        let tight = matches!(s, ")" | "]" | "}" | "," | ";" | "*" | "/" | "^" | ".")
            || matches!(self.prev.as_str(), "(" | "[" | "{" | "*" | "/" | "^" | ".")
            || (s == "("
                && self
                    .prev
                    .starts_with(|c: char| c.is_alphabetic() || c == '_'));
        if self.prev == ";" {
            self.text.push('\n');
        } else if !self.text.is_empty() && !self.glue_next && !tight {
            self.text.push(' ');
        }
        let start = self.text.len();
        self.text.push_str(s);
        self.spans.push((start..self.text.len(), span));
        let sign = matches!(s, "+" | "-") && opens_operand(&self.prev);
        self.glue_next = joint || sign;
        self.prev = if sign { "^".to_string() } else { s.to_string() };
    }

    fn push_stream(&mut self, tokens: TokenStream) {
        let mut tokens = tokens.into_iter().peekable();
        while let Some(tt) = tokens.next() {
            if let TokenTree::Punct(p) = &tt
                && p.as_char() == '#'
            {
                let doc = matches!(tokens.peek(), Some(TokenTree::Group(g))
                    if g.delimiter() == Delimiter::Bracket
                        && g.stream().to_string().starts_with("doc"));
                self.hashes.push((p.span(), doc));
            }
            match tt {
                TokenTree::Ident(i) => self.push(&i.to_string(), i.span(), false),
                TokenTree::Literal(l) => self.push(&l.to_string(), l.span(), false),
                TokenTree::Punct(p) => {
                    let joint = p.spacing() == Spacing::Joint;
                    self.push(&p.as_char().to_string(), p.span(), joint)
                }
                TokenTree::Group(g) => {
                    let (open, close) = match g.delimiter() {
                        Delimiter::Parenthesis => ("(", ")"),
                        Delimiter::Brace => ("{", "}"),
                        Delimiter::Bracket => ("[", "]"),
                        Delimiter::None => ("", ""),
                    };
                    if !open.is_empty() {
                        self.push(open, g.span_open(), false);
                    }
                    self.push_stream(g.stream());
                    if !close.is_empty() {
                        self.push(close, g.span_close(), false);
                    }
                }
            }
        }
    }

    /// A `compile_error!` at each `#`: inside Rust tokens it is not a
    /// comment (the energy language would drop everything after it).
    pub(crate) fn hash_errors(&self) -> Option<syn::Error> {
        self.hashes
            .iter()
            .map(|&(span, doc)| {
                let m = if doc {
                    "doc comments (`///`, `//!`) cannot be used inside `energy!` \
                     statements; use `//` comments (Rust removes them)"
                } else {
                    "`#` is not a comment inside `energy!` (the macro input is Rust \
                     tokens); use `//` comments, which Rust removes"
                };
                syn::Error::new(span, m)
            })
            .reduce(|mut all, e| {
                all.combine(e);
                all
            })
    }

    /// The spans of the first and last tokens overlapping `range` (the
    /// nearest token before it for an empty range or one past the end).
    pub(crate) fn spans_of(&self, range: Range<usize>) -> Option<(Span, Span)> {
        let hits: Vec<Span> = self
            .spans
            .iter()
            .filter(|(r, _)| r.start < range.end.max(range.start + 1) && range.start < r.end)
            .map(|(_, s)| *s)
            .collect();
        if let (Some(first), Some(last)) = (hits.first(), hits.last()) {
            return Some((*first, *last));
        }
        self.spans
            .iter()
            .rev()
            .find(|(r, _)| r.start <= range.start)
            .or_else(|| self.spans.first())
            .map(|(_, s)| (*s, *s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prints_tokens_like_hand_written_text() {
        let ts: TokenStream = "I2 - 2*I1 + (s1^-2)".parse().unwrap_or_default();
        let t = Text::from_tokens(ts);
        assert_eq!(t.text, "I2 - 2*I1 + (s1^-2)");
    }

    #[test]
    fn statements_keep_their_semicolons() {
        let ts: TokenStream = "param mu = 1.5; psi = mu*I2".parse().unwrap_or_default();
        assert_eq!(Text::from_tokens(ts).text, "param mu = 1.5;\npsi = mu*I2");
        let ts: TokenStream = "mu/2*(IC - d) - -mu*log(IC + 1)"
            .parse()
            .unwrap_or_default();
        assert_eq!(
            Text::from_tokens(ts).text,
            "mu/2*(IC - d) - -mu*log(IC + 1)"
        );
    }

    #[test]
    fn every_hash_is_an_error() {
        let ts: TokenStream = "I2 # note\n - 2*I1 + d".parse().unwrap_or_default();
        let t = Text::from_tokens(ts);
        let e = t.hash_errors().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("`#` is not a comment"), "{e}");
        let ts: TokenStream = "I2 - 2*I1 + d".parse().unwrap_or_default();
        assert!(Text::from_tokens(ts).hash_errors().is_none());
        let ts: TokenStream = "param k = 1; /// doc\n psi = k*I2"
            .parse()
            .unwrap_or_default();
        let e = Text::from_tokens(ts).hash_errors().map(|e| e.to_string());
        assert!(e.unwrap_or_default().contains("doc comments"));
        let ts: TokenStream = "I2 # a\n # b\n + d".parse().unwrap_or_default();
        let n = Text::from_tokens(ts)
            .hash_errors()
            .map_or(0, |e| e.into_iter().count());
        assert_eq!(n, 2);
    }

    #[test]
    fn ranges_map_back_to_tokens() {
        let ts: TokenStream = "I2 - I4".parse().unwrap_or_default();
        let t = Text::from_tokens(ts);
        assert!(t.spans_of(5..7).is_some());
        assert!(t.spans_of(100..100).is_some());
    }
}
