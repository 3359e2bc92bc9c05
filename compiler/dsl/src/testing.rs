//! Parser-backed helpers that make CAS tests one-liners.
//!
//! Sources are bare expressions (or whole programs); identifiers that are not
//! built-in become parameters (default 1), so `a*b + b*a` is accepted.
//!
//! ```
//! use ecc_dsl::testing::{canon, derivative};
//! assert_eq!(canon("x*x/x + 0*y").unwrap(), "x");
//! assert_eq!(derivative("I1^2*I3", "I1").unwrap(), "2*I1*I3");
//! ```

use crate::cas::{Graph, Id, Sym};
use crate::compile::front_end;
use crate::diag::{Diagnostics, Error};
use crate::front::lower::lower_program;
use crate::poly::{Converter, Proof};
use crate::span::Span;

/// Parse, resolve and lower `src` for `dim`.
pub fn lower(src: &str, dim: u8) -> Result<(Graph, Id), Diagnostics> {
    let prog = front_end(src, true)?;
    lower_program(&prog, dim).map_err(|errors| Diagnostics { errors })
}

/// The canonical text of `src` in 3D (`d` = 3).
pub fn canon(src: &str) -> Result<String, Diagnostics> {
    canon_dim(src, 3)
}

/// The canonical text of `src` in dimension `dim`.
pub fn canon_dim(src: &str, dim: u8) -> Result<String, Diagnostics> {
    let (g, id) = lower(src, dim)?;
    Ok(g.to_text(id))
}

/// The symbol called `name` in `g` (I1..I3, s1..s3 or a parameter).
pub fn symbol(g: &Graph, name: &str) -> Option<Sym> {
    Some(match name {
        "I1" => Sym::I1,
        "I2" => Sym::I2,
        "I3" => Sym::I3,
        "s1" => Sym::Sigma(0),
        "s2" => Sym::Sigma(1),
        "s3" => Sym::Sigma(2),
        _ => Sym::Param(g.param_names().iter().position(|p| p == name)? as u16),
    })
}

/// The canonical text of ∂`src`/∂`var` (3D).
pub fn derivative(src: &str, var: &str) -> Result<String, Diagnostics> {
    let (mut g, id) = lower(src, 3)?;
    let Some(s) = symbol(&g, var) else {
        return Err(Error::UnknownIdent {
            span: Span::default(),
            name: var.into(),
            suggestion: None,
            defined_later: None,
        }
        .into());
    };
    let d = g.diff(id, s);
    Ok(g.to_text(d))
}

/// Decide `src ≡ 0` as a function of σ (invariants substituted for `dim`).
pub fn prove_zero(src: &str, dim: u8) -> Result<Proof, Diagnostics> {
    let (mut g, id) = lower(src, dim)?;
    let mut c = Converter::new(&g, dim);
    Ok(c.is_zero(&mut g, id))
}

/// The exact quotient `src / (σi + s·σj)` as canonical text, if the
/// numerator vanishes on that hyperplane (and `src` is rational in σ).
pub fn divide(
    src: &str,
    dim: u8,
    i: usize,
    j: usize,
    s: i64,
) -> Result<Option<String>, Diagnostics> {
    let (mut g, id) = lower(src, dim)?;
    let mut c = Converter::new(&g, dim);
    let Some(r) = c.rational(&mut g, id) else {
        return Ok(None);
    };
    let Ok(Some(q)) = r.div_linear(i, j, s) else {
        return Ok(None);
    };
    let e = c.to_expr(&mut g, &q);
    Ok(Some(g.to_text(e)))
}
