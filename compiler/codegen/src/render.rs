//! A tiny expression tree for generated arithmetic and its rendering to
//! tokens with the fewest parentheses Rust's precedence allows (the walk is
//! shared with the C++ back end: [`crate::syntax`]; this file supplies the
//! Rust tokens).
//!
//! Products keep their numerator and denominator apart so that
//! `c·x·y⁻¹·z⁻²` renders as `c * x / (y * z * z)`; sums keep the sign of each
//! term so that `x + (−2)·y` renders as `x - 2.0 * y`.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::syntax::{self, BinOp, Prec, Syntax};

/// An arithmetic expression in generated code.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Ex {
    /// An `f64` constant (may be negative or non-finite).
    Lit(f64),
    /// A local variable.
    Var(String),
    /// `±t0 ± t1 ± …`: (negated, term).
    Sum(Vec<(bool, Ex)>),
    /// `[-] n0 * n1 * … / (d0 * d1 * …)`; an empty numerator is `1.0`.
    Prod {
        /// Negate the product.
        neg: bool,
        /// Numerator factors.
        num: Vec<Ex>,
        /// Denominator factors.
        den: Vec<Ex>,
    },
    /// `receiver.method(args…)`, e.g. `x.sqrt()`, `x.powf(e)`.
    Method(Box<Ex>, &'static str, Vec<Ex>),
    /// An integer literal (the argument of `powi`).
    Int(i32),
}

impl Ex {
    /// `-self`, simplifying signs.
    pub(crate) fn negated(self) -> Ex {
        match self {
            Ex::Lit(v) => Ex::Lit(-v),
            Ex::Prod { neg, num, den } => Ex::Prod {
                neg: !neg,
                num,
                den,
            },
            Ex::Sum(terms) => Ex::Sum(terms.into_iter().map(|(n, t)| (!n, t)).collect()),
            other => Ex::Prod {
                neg: true,
                num: vec![other],
                den: vec![],
            },
        }
    }

    /// The expression with variables renamed by `map` (others unchanged).
    pub(crate) fn renamed(self, map: &std::collections::HashMap<String, String>) -> Ex {
        if map.is_empty() {
            return self;
        }
        match self {
            Ex::Var(n) => Ex::Var(map.get(&n).cloned().unwrap_or(n)),
            Ex::Sum(t) => Ex::Sum(t.into_iter().map(|(n, e)| (n, e.renamed(map))).collect()),
            Ex::Prod { neg, num, den } => Ex::Prod {
                neg,
                num: num.into_iter().map(|e| e.renamed(map)).collect(),
                den: den.into_iter().map(|e| e.renamed(map)).collect(),
            },
            Ex::Method(r, m, a) => Ex::Method(
                Box::new(r.renamed(map)),
                m,
                a.into_iter().map(|e| e.renamed(map)).collect(),
            ),
            other => other,
        }
    }

    /// Whether the expression is (syntactically) a negation or a negative
    /// constant, so that a sum may subtract its negation instead.
    pub(crate) fn is_negative(&self) -> bool {
        match self {
            Ex::Lit(v) => v.is_sign_negative() && *v != 0.0,
            Ex::Prod { neg, .. } => *neg,
            _ => false,
        }
    }

    /// The tokens of the expression.
    pub(crate) fn tokens(&self) -> TokenStream {
        syntax::render(&Rust, self).0
    }
}

/// Rust tokens for the shared printer ([`syntax`]).
struct Rust;

impl Syntax for Rust {
    type Out = TokenStream;

    /// An `f64` literal; a method receiver gets the `_f64` suffix.
    fn lit(&self, v: f64, receiver: bool) -> (TokenStream, Prec) {
        if v.is_nan() {
            return (quote!(f64::NAN), Prec::Atom);
        }
        if v.is_infinite() {
            return if v > 0.0 {
                (quote!(f64::INFINITY), Prec::Atom)
            } else {
                (quote!(f64::NEG_INFINITY), Prec::Atom)
            };
        }
        let text = format!("{:?}", v.abs());
        let text = if receiver {
            format!("{text}_f64")
        } else {
            text
        };
        let l: Literal = text
            .parse()
            .unwrap_or_else(|_| Literal::f64_unsuffixed(v.abs()));
        if v.is_sign_negative() && v != 0.0 {
            (quote!(-#l), Prec::Unary)
        } else {
            (quote!(#l), Prec::Atom)
        }
    }

    fn var(&self, name: &str) -> TokenStream {
        let id = Ident::new(name, Span::call_site());
        quote!(#id)
    }

    fn int(&self, n: i32) -> (TokenStream, Prec) {
        let l = Literal::i32_unsuffixed(n.abs());
        if n < 0 {
            (quote!(-#l), Prec::Unary)
        } else {
            (quote!(#l), Prec::Atom)
        }
    }

    fn call(&self, recv: (TokenStream, Prec), method: &str, args: Vec<TokenStream>) -> TokenStream {
        let r = syntax::wrap(self, recv, Prec::Atom);
        let m = Ident::new(method, Span::call_site());
        quote!(#r.#m(#(#args),*))
    }

    fn paren(&self, t: TokenStream) -> TokenStream {
        quote!((#t))
    }

    fn neg(&self, t: TokenStream) -> TokenStream {
        quote!(-#t)
    }

    fn bin(&self, a: TokenStream, op: BinOp, b: TokenStream) -> TokenStream {
        match op {
            BinOp::Add => quote!(#a + #b),
            BinOp::Sub => quote!(#a - #b),
            BinOp::Mul => quote!(#a * #b),
            BinOp::Div => quote!(#a / #b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(s: &str) -> Ex {
        Ex::Var(s.into())
    }

    fn text(e: &Ex) -> String {
        e.tokens().to_string()
    }

    #[test]
    fn sums_subtract_negative_terms() {
        let e = Ex::Sum(vec![
            (false, v("x")),
            (
                false,
                Ex::Prod {
                    neg: true,
                    num: vec![Ex::Lit(2.0), v("y")],
                    den: vec![],
                },
            ),
            (false, Ex::Lit(-3.0)),
        ]);
        assert_eq!(text(&e), "x - 2.0 * y - 3.0");
    }

    #[test]
    fn sums_lead_with_a_positive_term() {
        let e = Ex::Sum(vec![(true, v("x")), (false, v("y"))]);
        assert_eq!(text(&e), "y - x");
        let e = Ex::Sum(vec![(true, v("x")), (true, v("y"))]);
        assert_eq!(text(&e), "- x - y");
    }

    #[test]
    fn products_parenthesise_sums_and_denominators() {
        let s = Ex::Sum(vec![(false, v("a")), (false, v("b"))]);
        let e = Ex::Prod {
            neg: false,
            num: vec![Ex::Lit(0.5), s.clone()],
            den: vec![v("c"), v("c")],
        };
        assert_eq!(text(&e), "0.5 * (a + b) / (c * c)");
        let e = Ex::Prod {
            neg: false,
            num: vec![],
            den: vec![s],
        };
        assert_eq!(text(&e), "1.0 / (a + b)");
    }

    #[test]
    fn methods_wrap_receivers_and_suffix_literals() {
        let s = Ex::Sum(vec![(false, v("a")), (false, Ex::Lit(1.0))]);
        assert_eq!(
            text(&Ex::Method(Box::new(s), "ln", vec![])),
            "(a + 1.0) . ln ()"
        );
        assert_eq!(
            text(&Ex::Method(Box::new(Ex::Lit(2.0)), "ln", vec![])),
            "2.0_f64 . ln ()"
        );
    }

    #[test]
    fn negation_of_products() {
        let e = Ex::Prod {
            neg: true,
            num: vec![v("x")],
            den: vec![],
        };
        assert_eq!(text(&e), "- x");
        let e = Ex::Prod {
            neg: true,
            num: vec![v("x")],
            den: vec![v("y")],
        };
        assert_eq!(text(&e), "- x / y");
        // A negated product inside a product keeps its parentheses.
        let outer = Ex::Prod {
            neg: false,
            num: vec![v("z"), e],
            den: vec![],
        };
        assert_eq!(text(&outer), "z * (- x / y)");
    }

    #[test]
    fn literals() {
        assert_eq!(text(&Ex::Lit(1e-30)), "1e-30");
        assert_eq!(text(&Ex::Lit(-0.25)), "- 0.25");
        assert_eq!(text(&Ex::Lit(f64::INFINITY)), "f64 :: INFINITY");
    }
}
