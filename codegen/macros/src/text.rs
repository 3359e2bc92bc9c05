//! Rust tokens → energy-language text, remembering where each token went.
//!
//! Tokens are printed separated by one space (a `Joint` punctuation is glued
//! to the next one, so `**` stays `**` and is reported as the syntax error
//! it is). Parentheses are kept; other delimiters are printed too, so that
//! the energy language reports them. Each token's byte range in the text is
//! recorded with its span, so that an error at DSL bytes `a..b` can be
//! reported at the Rust tokens covering them.

use std::ops::Range;

use proc_macro2::{Delimiter, Spacing, Span, TokenStream, TokenTree};

/// The text and the span of every token in it.
pub(crate) struct Text {
    pub text: String,
    spans: Vec<(Range<usize>, Span)>,
}

impl Text {
    /// Print `tokens` as energy-language text.
    pub(crate) fn from_tokens(tokens: TokenStream) -> Text {
        let mut t = Text {
            text: String::new(),
            spans: Vec::new(),
        };
        let mut glue = false;
        t.push_stream(tokens, &mut glue);
        t
    }

    fn push(&mut self, s: &str, span: Span, glue: &mut bool, joint: bool) {
        if !self.text.is_empty() && !*glue {
            self.text.push(' ');
        }
        let start = self.text.len();
        self.text.push_str(s);
        self.spans.push((start..self.text.len(), span));
        *glue = joint;
    }

    fn push_stream(&mut self, tokens: TokenStream, glue: &mut bool) {
        for tt in tokens {
            match tt {
                TokenTree::Ident(i) => self.push(&i.to_string(), i.span(), glue, false),
                TokenTree::Literal(l) => self.push(&l.to_string(), l.span(), glue, false),
                TokenTree::Punct(p) => {
                    let joint = p.spacing() == Spacing::Joint;
                    self.push(&p.as_char().to_string(), p.span(), glue, joint)
                }
                TokenTree::Group(g) => {
                    let (open, close) = match g.delimiter() {
                        Delimiter::Parenthesis => ("(", ")"),
                        Delimiter::Brace => ("{", "}"),
                        Delimiter::Bracket => ("[", "]"),
                        Delimiter::None => ("", ""),
                    };
                    if !open.is_empty() {
                        self.push(open, g.span_open(), glue, false);
                    }
                    self.push_stream(g.stream(), glue);
                    if !close.is_empty() {
                        self.push(close, g.span_close(), glue, false);
                    }
                }
            }
        }
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
    fn prints_tokens_with_single_spaces() {
        let ts: TokenStream = "I2 - 2*I1 + (s1^-2)".parse().unwrap_or_default();
        let t = Text::from_tokens(ts);
        assert_eq!(t.text, "I2 - 2 * I1 + ( s1 ^- 2 )");
    }

    #[test]
    fn statements_keep_their_semicolons() {
        let ts: TokenStream = "param mu = 1.5; psi = mu*I2".parse().unwrap_or_default();
        assert_eq!(Text::from_tokens(ts).text, "param mu = 1.5 ; psi = mu * I2");
    }

    #[test]
    fn ranges_map_back_to_tokens() {
        let ts: TokenStream = "I2 - I4".parse().unwrap_or_default();
        let t = Text::from_tokens(ts);
        assert!(t.spans_of(5..7).is_some());
        assert!(t.spans_of(100..100).is_some());
    }
}
