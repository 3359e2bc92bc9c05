//! The resolved program: the output of name resolution ([`super::sema`])
//! and the input of lowering into the CAS ([`super::lower`]).

use num_rational::BigRational;

use super::ast::BinOp;
use crate::span::Span;

/// A built-in variable or alias.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    /// I1 = Σσ.
    I1,
    /// I2 = Σσ².
    I2,
    /// I3 = Πσ.
    I3,
    /// The stretch σ_k (`s{k+1}`).
    S(u8),
    /// The dimension.
    D,
    /// IC = tr C = I2.
    IC,
    /// IIC = ‖C‖² (Appendix A).
    IIC,
    /// IIIC = det C = I3².
    IIIC,
    /// J = det F = I3.
    J,
    /// I4 = aᵀ S a (needs `fiber a`).
    I4,
    /// I5 = ‖F a‖² = aᵀ C a (needs `fiber a`; also spelt `IVC`).
    I5,
    /// sign(I4): +1 for I4 > 0, −1 otherwise; written `sign(I4)`.
    SignI4,
}

/// A function of the language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// `sqrt(x)`.
    Sqrt,
    /// `log(x)`, natural.
    Log,
    /// `exp(x)`.
    Exp,
    /// `pow(a, b)`.
    Pow,
    /// `sign(I4)` (resolved to [`Var::SignI4`]; no other argument is allowed).
    Sign,
}

/// A resolved expression.
#[derive(Clone, Debug, PartialEq)]
pub enum RExpr {
    /// A constant.
    Num(BigRational),
    /// A built-in variable or alias.
    Var(Var),
    /// Parameter k.
    Param(u16),
    /// The value of let number k.
    Let(usize),
    /// `-x`.
    Neg(Box<RExpr>),
    /// A flat chain of `+ -` or `* /`; each operand keeps its span.
    Chain(Box<RExpr>, Vec<(BinOp, RExpr, Span)>),
    /// `base ^ exp` (also `pow(base, exp)`), with the span of the power.
    Pow(Box<RExpr>, Box<RExpr>, Span),
    /// `sqrt`, `log` or `exp` of an argument (with its span).
    Call(Func, Box<RExpr>, Span),
    /// Something already reported as an error.
    Poison,
}

/// A declared parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamInfo {
    /// Name.
    pub name: String,
    /// Default value.
    pub default: f64,
    /// The statement's span.
    pub span: Span,
}

/// A `let`.
#[derive(Clone, Debug, PartialEq)]
pub struct LetInfo {
    /// Name.
    pub name: String,
    /// Definition.
    pub expr: RExpr,
    /// Whether the definition mentions `d` (directly or through other lets).
    pub mentions_d: bool,
}

/// A resolved program.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// Parameters in declaration order.
    pub params: Vec<ParamInfo>,
    /// Lets in definition order.
    pub lets: Vec<LetInfo>,
    /// The energy and the span of its definition.
    pub psi: RExpr,
    /// The span of the `psi = …` expression.
    pub psi_span: Span,
    /// `dim N` if declared, with its span.
    pub dim: Option<(u8, Span)>,
    /// Every use of a stretch: (k, span).
    pub stretch_uses: Vec<(u8, Span)>,
    /// `fiber a`: the direction's name and the statement's span.
    pub fiber: Option<(String, Span)>,
}

/// Whether `e` mentions `d`, directly or through lets.
pub fn mentions_d(e: &RExpr, lets: &[bool]) -> bool {
    match e {
        RExpr::Var(Var::D) => true,
        RExpr::Let(k) => lets.get(*k).copied().unwrap_or(false),
        RExpr::Neg(x) | RExpr::Call(_, x, _) => mentions_d(x, lets),
        RExpr::Chain(f, rest) => {
            mentions_d(f, lets) || rest.iter().any(|(_, x, _)| mentions_d(x, lets))
        }
        RExpr::Pow(b, x, _) => mentions_d(b, lets) || mentions_d(x, lets),
        RExpr::Num(_) | RExpr::Var(_) | RExpr::Param(_) | RExpr::Poison => false,
    }
}
