//! The syntax tree, with byte spans into the whole source text.

use num_rational::BigRational;

use crate::span::Span;

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

/// An expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A number literal, converted exactly.
    Num(BigRational, Span),
    /// A name.
    Ident(String, Span),
    /// Unary minus.
    Neg(Box<Expr>, Span),
    /// `first op1 x1 op2 x2 …` for a run of `+ -` or of `* /` (kept flat so
    /// long sums never make deep trees); each op carries its own span.
    Chain(Box<Expr>, Vec<(BinOp, Span, Expr)>, Span),
    /// `base ^ exponent`.
    Pow(Box<Expr>, Box<Expr>, Span),
    /// `name(args)`; the first span is the name's, the second the call's.
    Call(String, Span, Vec<Expr>, Span),
}

impl Expr {
    /// The span of the whole expression.
    pub fn span(&self) -> Span {
        match self {
            Expr::Num(_, s)
            | Expr::Ident(_, s)
            | Expr::Neg(_, s)
            | Expr::Chain(.., s)
            | Expr::Pow(.., s)
            | Expr::Call(.., s) => *s,
        }
    }
}

/// A statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `dim 2` / `dim 3` (the value is checked later).
    Dim {
        /// The value's text.
        value: String,
        /// The value's span.
        value_span: Span,
        /// The whole statement.
        span: Span,
    },
    /// `param name = default`.
    Param {
        /// The name.
        name: String,
        /// The name's span.
        name_span: Span,
        /// The default (a constant expression).
        expr: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `let name = expr`.
    Let {
        /// The name.
        name: String,
        /// The name's span.
        name_span: Span,
        /// The definition.
        expr: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `fiber a` / `fibre a`: the per-element fibre direction.
    Fiber {
        /// The direction's name.
        name: String,
        /// The name's span.
        name_span: Span,
        /// The whole statement.
        span: Span,
    },
    /// `psi = expr`, or a bare expression (`bare`).
    Psi {
        /// The energy.
        expr: Expr,
        /// The `psi` keyword (or the bare expression).
        key_span: Span,
        /// Whether it was written as a bare expression.
        bare: bool,
    },
}
