//! Fibre names in the language: `fiber a` (or `fibre a`), the variables
//! I4 = aᵀ S a and I5 = ‖F a‖² = aᵀ C a, the alias `IVC` = aᵀ C a (= I5,
//! the "I4" of Holzapfel's notation), `sign(I4)`, and the located errors for
//! their misuse (see LANGUAGE.md, "Fibres").

use super::ast::Stmt;
use super::resolved::{RExpr, Var};
use crate::diag::Error;
use crate::span::Span;

/// Built-in fibre variables (never shadowable, like I1..I3).
pub const VARS: [(&str, Var); 2] = [("I4", Var::I4), ("I5", Var::I5)];

/// Fibre aliases (shadowable, like IC): `IVC` = aᵀ C a = I5.
pub const ALIASES: [(&str, Var); 1] = [("IVC", Var::I5)];

/// Holzapfel's aᵀ C² a, which is not a function of I4, I5 alone.
pub const C2: &str = "VC";

/// The first `fiber` statement: the direction's name and the statement.
pub fn declaration(stmts: &[Stmt]) -> Option<(String, Span)> {
    stmts.iter().find_map(|s| match s {
        Stmt::Fiber { name, span, .. } => Some((name.clone(), *span)),
        _ => None,
    })
}

/// Whether `name` is a fibre variable or alias a parameter default may not use.
pub fn is_fibre_name(name: &str) -> bool {
    VARS.iter().chain(ALIASES.iter()).any(|(n, _)| *n == name) || name == C2
}

/// `I4`/`I5`/`IVC` used in a file without `fiber a`.
pub fn undeclared(name: &str, span: Span) -> Error {
    Error::Fibre {
        span,
        message: format!("`{name}` is a fibre invariant, but no fibre direction is declared"),
        label: "needs a fibre direction".into(),
        notes: vec![
            "help: add `fiber a` (or `fibre a`) to the file: it declares the per-element unit direction a, and then I4 = aᵀ S a and I5 = ‖F a‖² can be used".into(),
        ],
    }
}

/// `VC` (aᵀ C² a): explains why it is not available.
pub fn c_squared(span: Span) -> Error {
    Error::Fibre {
        span,
        message: "`VC` = aᵀ C² a (Holzapfel's I5) is not supported".into(),
        label: "not a function of I4 and I5".into(),
        notes: vec![
            "note: ecc's fibre invariants are I4 = aᵀ S a and I5 = aᵀ C a = ‖F a‖² (Kim et al. 2019); aᵀ C² a = aᵀ S⁴ a is, by Cayley–Hamilton in 3D, (I1² − J2) I5 + (I3 − I1 J2) I4 + I1 I3 with J2 = (I1² − I2)/2: it couples the fibre and isotropic parts, which the runtime projects separately".into(),
            "help: write the fibre term with I4 and I5 (IVC = aᵀ C a is I5)".into(),
        ],
    }
}

/// The direction's own name used in an expression.
pub fn direction_used(name: &str, span: Span, decl: Span) -> Error {
    Error::Fibre {
        span,
        message: format!("`{name}` is the fibre direction (a vector), not a number"),
        label: "a vector".into(),
        notes: vec![
            format!(
                "note: declared by the `fiber` statement at bytes {}..{}",
                decl.start, decl.end
            ),
            "help: psi sees the direction through I4 = aᵀ S a and I5 = ‖F a‖² = aᵀ C a".into(),
        ],
    }
}

/// `sign(x)` with x other than I4; `Poison` passes through silently.
pub fn sign_of(arg: RExpr, span: Span) -> Result<RExpr, Error> {
    match arg {
        RExpr::Var(Var::I4) => Ok(RExpr::Var(Var::SignI4)),
        RExpr::Poison => Ok(RExpr::Poison),
        _ => Err(Error::Fibre {
            span,
            message: "`sign` is only defined for I4".into(),
            label: "expected `I4`".into(),
            notes: vec![
                "note: sign(I4) is +1 for I4 > 0 and −1 otherwise (I4 = 0 included, HOBAK's convention); its derivative is taken as 0 (it is piecewise constant), as anisotropic ARAP needs: psi = mu/2*(sqrt(I5) - sign(I4))^2".into(),
            ],
        }),
    }
}
