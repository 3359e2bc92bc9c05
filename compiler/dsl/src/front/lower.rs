//! Lowering a resolved program into the CAS for one dimension.
//!
//! Aliases are rewritten into I1, I2, I3 (Smith et al. 2019, App. A):
//! IC = I2; IIC = ‖FᵀF‖² = Σσ⁴ = I2² − 2 I3² in 2D and
//! ½ I2² − ½ I1⁴ + I1² I2 + 4 I1 I3 in 3D (the paper labels this line
//! III_C, but it is II_C: it equals Σσ⁴, checked in the tests);
//! IIIC = I3²; J = I3. `d` folds to the dimension. Divisions by, negative
//! powers of, and logs of something that folds to exactly 0 are errors.

use num_rational::BigRational;
use num_traits::Signed;

use super::ast::BinOp;
use super::resolved::{Func, Program, RExpr, Var, mentions_d};
use crate::cas::{Graph, Id, Sym};
use crate::diag::Error;

/// Lower `prog` for dimension `dim`: the graph and Ψ's id, or the errors
/// found (empty when Ψ depends on something already reported as an error).
pub fn lower_program(prog: &Program, dim: u8) -> Result<(Graph, Id), Vec<Error>> {
    let names = prog.params.iter().map(|p| p.name.clone()).collect();
    let mut g = Graph::new(names);
    let mut errors = Vec::new();
    let lets_d: Vec<bool> = prog.lets.iter().map(|l| l.mentions_d).collect();
    let mut lets: Vec<Option<Id>> = Vec::with_capacity(prog.lets.len());
    for l in &prog.lets {
        let v = lower_expr(&mut g, &l.expr, dim, &lets, &lets_d, &mut errors);
        lets.push(v);
    }
    let psi = lower_expr(&mut g, &prog.psi, dim, &lets, &lets_d, &mut errors);
    if let Some(p) = psi {
        errors.extend(constants_beyond_f64(&g, p, prog.psi_span));
    }
    match psi {
        Some(p) if errors.is_empty() => Ok((g, p)),
        // `errors` is empty only when psi was poisoned by an earlier
        // (already reported) error.
        _ => Err(errors),
    }
}

/// Constants of Ψ (after exact folding: `10^400*I2`, `1e200*1e200*I2`)
/// that do not fit an f64, reported at the `psi` expression like a literal
/// out of range ([`Error::NumberNotF64`]); the text is the power of ten.
/// Intermediate constants may be huge (`10^400*10^-400*I2` is `I2`): only
/// those left in Ψ, which the generated code would evaluate, count.
fn constants_beyond_f64(g: &Graph, psi: Id, span: crate::span::Span) -> Option<Error> {
    g.reachable(&[psi]).into_iter().find_map(|id| {
        let r = g.as_num(id)?;
        let v = crate::cas::rat::to_f64(r);
        let overflow = !v.is_finite();
        let underflow = !num_traits::Zero::is_zero(r) && v.abs() < f64::MIN_POSITIVE;
        (overflow || underflow).then(|| {
            let digits = |n: &num_bigint::BigInt| n.abs().to_string().len() as i64;
            let exp = digits(r.numer()) - digits(r.denom());
            Error::NumberNotF64 {
                span,
                text: format!("≈1e{exp} (a constant of psi after folding)"),
                overflow,
            }
        })
    })
}

/// Lower one expression. `None` when it (or a let it uses) failed; the
/// reasons are pushed to `errors` (a poisoned let adds nothing new).
pub fn lower_expr(
    g: &mut Graph,
    e: &RExpr,
    dim: u8,
    lets: &[Option<Id>],
    lets_d: &[bool],
    errors: &mut Vec<Error>,
) -> Option<Id> {
    let tag = |x: &RExpr| mentions_d(x, lets_d).then_some(dim);
    Some(match e {
        RExpr::Num(r) => g.num(r.clone()),
        RExpr::Var(v) => var(g, *v, dim)?,
        RExpr::Param(k) => g.sym(Sym::Param(*k)),
        RExpr::Let(k) => (*lets.get(*k)?)?,
        RExpr::Neg(x) => {
            let v = lower_expr(g, x, dim, lets, lets_d, errors)?;
            g.neg(v)
        }
        RExpr::Chain(first, rest)
            if rest
                .iter()
                .all(|(op, ..)| matches!(op, BinOp::Add | BinOp::Sub)) =>
        {
            lower_sum(g, first, rest, dim, lets, lets_d, errors)?
        }
        RExpr::Chain(first, rest) => {
            let mut acc = lower_expr(g, first, dim, lets, lets_d, errors);
            for (op, x, span) in rest {
                let v = lower_expr(g, x, dim, lets, lets_d, errors);
                let (Some(a), Some(b)) = (acc, v) else {
                    acc = None;
                    continue;
                };
                acc = Some(match op {
                    BinOp::Add => g.add2(a, b),
                    BinOp::Sub => g.sub(a, b),
                    BinOp::Mul => g.mul2(a, b),
                    BinOp::Div | BinOp::Pow => {
                        if g.is_int(b, 0) {
                            errors.push(Error::DivisionByZero {
                                span: *span,
                                dim: tag(x),
                            });
                            acc = None;
                            continue;
                        }
                        g.div(a, b)
                    }
                });
            }
            acc?
        }
        RExpr::Pow(b, x, span) => {
            let bv = lower_expr(g, b, dim, lets, lets_d, errors);
            let xv = lower_expr(g, x, dim, lets, lets_d, errors);
            let (bv, xv) = (bv?, xv?);
            if g.is_int(bv, 0) && g.as_num(xv).is_some_and(|r| r.is_negative()) {
                let dt = (mentions_d(b, lets_d) || mentions_d(x, lets_d)).then_some(dim);
                errors.push(Error::DivisionByZero {
                    span: *span,
                    dim: dt,
                });
                return None;
            }
            g.pow(bv, xv)
        }
        RExpr::Call(f, x, span) => {
            let v = lower_expr(g, x, dim, lets, lets_d, errors)?;
            match f {
                Func::Sqrt => g.sqrt(v),
                Func::Exp => g.exp(v),
                Func::Log | Func::Pow => {
                    if g.is_int(v, 0) {
                        errors.push(Error::LogOfZero {
                            span: *span,
                            dim: tag(x),
                        });
                        return None;
                    }
                    g.log(v)
                }
            }
        }
        RExpr::Poison => return None,
    })
}

/// A run of `+`/`-` as one canonical sum (adding term by term would
/// re-collect the growing sum at every step: quadratic in its length). The
/// result is the same node: sums are flattened and like terms collected.
fn lower_sum(
    g: &mut Graph,
    first: &RExpr,
    rest: &[(BinOp, RExpr, crate::span::Span)],
    dim: u8,
    lets: &[Option<Id>],
    lets_d: &[bool],
    errors: &mut Vec<Error>,
) -> Option<Id> {
    let mut terms = Vec::with_capacity(rest.len() + 1);
    let mut ok = match lower_expr(g, first, dim, lets, lets_d, errors) {
        Some(a) => {
            terms.push(a);
            true
        }
        None => false,
    };
    for (op, x, _) in rest {
        match lower_expr(g, x, dim, lets, lets_d, errors) {
            Some(b) if ok => terms.push(match op {
                BinOp::Sub => g.neg(b),
                _ => b,
            }),
            _ => ok = false,
        }
    }
    ok.then(|| g.sum(&terms))
}

fn half() -> BigRational {
    BigRational::new(1.into(), 2.into())
}

/// A variable or alias as an expression in I1, I2, I3, σ for `dim`.
fn var(g: &mut Graph, v: Var, dim: u8) -> Option<Id> {
    Some(match v {
        Var::I1 => g.sym(Sym::I1),
        Var::I2 | Var::IC => g.sym(Sym::I2),
        Var::I3 | Var::J => g.sym(Sym::I3),
        Var::S(k) if k < dim => g.sym(Sym::Sigma(k)),
        Var::S(_) => return None,
        Var::D => g.int(dim as i64),
        Var::IIIC => {
            let i3 = g.sym(Sym::I3);
            g.powi(i3, 2)
        }
        Var::IIC => {
            let (i1, i2, i3) = (g.sym(Sym::I1), g.sym(Sym::I2), g.sym(Sym::I3));
            let i2sq = g.powi(i2, 2);
            if dim == 2 {
                let i3sq = g.powi(i3, 2);
                let t = g.scale(BigRational::from_integer((-2).into()), i3sq);
                g.add2(i2sq, t)
            } else {
                let a = g.scale(half(), i2sq);
                let i1_4 = g.powi(i1, 4);
                let b = g.scale(-half(), i1_4);
                let i1sq = g.powi(i1, 2);
                let c = g.mul2(i1sq, i2);
                let four = g.int(4);
                let d = g.product(&[four, i1, i3]);
                g.sum(&[a, b, c, d])
            }
        }
    })
}
