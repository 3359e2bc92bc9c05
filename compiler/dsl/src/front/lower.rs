//! Lowering a resolved program into the CAS for one dimension.
//!
//! Aliases are rewritten into I1, I2, I3 (Smith et al. 2019, App. A):
//! IC = I2; IIC = ‖FᵀF‖² = Σσ⁴ = I2² − 2 I3² in 2D and
//! ½ I2² − ½ I1⁴ + I1² I2 + 4 I1 I3 in 3D (the paper labels this line
//! III_C, but it is II_C: it equals Σσ⁴, checked in the tests);
//! IIIC = I3²; J = I3. `d` folds to the dimension. Divisions by, negative
//! powers of, and logs of something that folds to exactly 0 are errors.
//! The domain conditions of what is written (`log(x)` needs x > 0, …) are
//! recorded before the CAS simplifies them away ([`super::domain`]).

use num_rational::BigRational;
use num_traits::Signed;

use super::ast::BinOp;
use super::domain;
use super::resolved::{Func, Program, RExpr, Var, mentions_d};
use crate::cas::{Graph, Id, Sym};
use crate::diag::Error;
use crate::ir::DomainGuard;

/// Lower `prog` for dimension `dim`: the graph and Ψ's id, or the errors
/// found (empty when Ψ depends on something already reported as an error).
pub fn lower_program(prog: &Program, dim: u8) -> Result<(Graph, Id), Vec<Error>> {
    lower_with_domain(prog, dim).map(|(g, psi, _)| (g, psi))
}

/// [`lower_program`] plus the domain of Ψ as written (before any
/// simplification; see [`super::domain`]): the conditions of Ψ's own
/// expression and of every `let` it uses.
pub fn lower_with_domain(
    prog: &Program,
    dim: u8,
) -> Result<(Graph, Id, Vec<DomainGuard>), Vec<Error>> {
    let names = prog.params.iter().map(|p| p.name.clone()).collect();
    let mut g = Graph::new(names);
    let mut errors = Vec::new();
    let lets_d: Vec<bool> = prog.lets.iter().map(|l| l.mentions_d).collect();
    let mut lets: Vec<Option<Id>> = Vec::with_capacity(prog.lets.len());
    let mut let_guards: Vec<Vec<DomainGuard>> = Vec::with_capacity(prog.lets.len());
    for l in &prog.lets {
        let mut cx = Cx {
            g: &mut g,
            dim,
            lets: &lets,
            lets_d: &lets_d,
            let_guards: &let_guards,
            errors: &mut errors,
            guards: Vec::new(),
        };
        let v = cx.expr(&l.expr);
        let guards = cx.guards;
        lets.push(v);
        let_guards.push(guards);
    }
    let mut cx = Cx {
        g: &mut g,
        dim,
        lets: &lets,
        lets_d: &lets_d,
        let_guards: &let_guards,
        errors: &mut errors,
        guards: Vec::new(),
    };
    let psi = cx.expr(&prog.psi);
    let guards = cx.guards;
    if let Some(p) = psi {
        errors.extend(constants_beyond_f64(&g, p, prog.psi_span));
    }
    match psi {
        Some(p) if errors.is_empty() => Ok((g, p, guards)),
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
    let no_guards: Vec<Vec<DomainGuard>> = vec![Vec::new(); lets.len()];
    let mut cx = Cx {
        g,
        dim,
        lets,
        lets_d,
        let_guards: &no_guards,
        errors,
        guards: Vec::new(),
    };
    cx.expr(e)
}

/// The state of lowering one expression: the graph, the `let`s above it
/// (their ids, whether they mention `d`, their domain conditions), the
/// errors found and the domain conditions of what was written so far.
struct Cx<'a> {
    g: &'a mut Graph,
    dim: u8,
    lets: &'a [Option<Id>],
    lets_d: &'a [bool],
    let_guards: &'a [Vec<DomainGuard>],
    errors: &'a mut Vec<Error>,
    guards: Vec<DomainGuard>,
}

impl Cx<'_> {
    fn tag(&self, x: &RExpr) -> Option<u8> {
        mentions_d(x, self.lets_d).then_some(self.dim)
    }

    /// Lower `e`, recording the domain condition of every restricting
    /// operation on its operands as written.
    fn expr(&mut self, e: &RExpr) -> Option<Id> {
        Some(match e {
            RExpr::Num(r) => self.g.num(r.clone()),
            RExpr::Var(v) => var(self.g, *v, self.dim)?,
            RExpr::Param(k) => self.g.sym(Sym::Param(*k)),
            RExpr::Let(k) => {
                let id = (*self.lets.get(*k)?)?;
                if let Some(more) = self.let_guards.get(*k) {
                    domain::extend(self.g, &mut self.guards, more);
                }
                id
            }
            RExpr::Neg(x) => {
                let v = self.expr(x)?;
                self.g.neg(v)
            }
            RExpr::Chain(first, rest)
                if rest
                    .iter()
                    .all(|(op, ..)| matches!(op, BinOp::Add | BinOp::Sub)) =>
            {
                self.sum(first, rest)?
            }
            RExpr::Chain(first, rest) => self.chain(first, rest)?,
            RExpr::Pow(b, x, span) => {
                let bv = self.expr(b);
                let xv = self.expr(x);
                let (bv, xv) = (bv?, xv?);
                if self.g.is_int(bv, 0) && self.g.as_num(xv).is_some_and(|r| r.is_negative()) {
                    let dt = (mentions_d(b, self.lets_d) || mentions_d(x, self.lets_d))
                        .then_some(self.dim);
                    self.errors.push(Error::DivisionByZero {
                        span: *span,
                        dim: dt,
                    });
                    return None;
                }
                domain::pow(self.g, &mut self.guards, bv, xv);
                self.g.pow(bv, xv)
            }
            RExpr::Call(f, x, span) => {
                let v = self.expr(x)?;
                match f {
                    Func::Sqrt => {
                        let half = self.g.num(half());
                        domain::pow(self.g, &mut self.guards, v, half);
                        self.g.sqrt(v)
                    }
                    Func::Exp => self.g.exp(v),
                    // Sema resolves `sign(I4)` to `Var::SignI4` and refuses
                    // every other argument, so no `Sign` call reaches here.
                    Func::Sign => {
                        let i4 = self.g.sym(Sym::I4);
                        if v != i4 {
                            return None;
                        }
                        self.g.sym(Sym::SignI4)
                    }
                    Func::Log | Func::Pow => {
                        if self.g.is_int(v, 0) {
                            let dim = self.tag(x);
                            self.errors.push(Error::LogOfZero { span: *span, dim });
                            return None;
                        }
                        domain::log(self.g, &mut self.guards, v);
                        self.g.log(v)
                    }
                }
            }
            RExpr::Poison => return None,
        })
    }

    /// A chain with `*` or `/` (left to right).
    fn chain(&mut self, first: &RExpr, rest: &[(BinOp, RExpr, crate::span::Span)]) -> Option<Id> {
        let mut acc = self.expr(first);
        for (op, x, span) in rest {
            let v = self.expr(x);
            let (Some(a), Some(b)) = (acc, v) else {
                acc = None;
                continue;
            };
            acc = Some(match op {
                BinOp::Add => self.g.add2(a, b),
                BinOp::Sub => self.g.sub(a, b),
                BinOp::Mul => self.g.mul2(a, b),
                BinOp::Div | BinOp::Pow => {
                    if self.g.is_int(b, 0) {
                        let dim = self.tag(x);
                        self.errors.push(Error::DivisionByZero { span: *span, dim });
                        acc = None;
                        continue;
                    }
                    domain::nonzero(self.g, &mut self.guards, b);
                    self.g.div(a, b)
                }
            });
        }
        acc
    }

    /// A run of `+`/`-` as one canonical sum (adding term by term would
    /// re-collect the growing sum at every step: quadratic in its length).
    /// The result is the same node: sums are flattened and like terms
    /// collected.
    fn sum(&mut self, first: &RExpr, rest: &[(BinOp, RExpr, crate::span::Span)]) -> Option<Id> {
        let mut terms = Vec::with_capacity(rest.len() + 1);
        let mut ok = match self.expr(first) {
            Some(a) => {
                terms.push(a);
                true
            }
            None => false,
        };
        for (op, x, _) in rest {
            match self.expr(x) {
                Some(b) if ok => terms.push(match op {
                    BinOp::Sub => self.g.neg(b),
                    _ => b,
                }),
                _ => ok = false,
            }
        }
        ok.then(|| self.g.sum(&terms))
    }
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
        Var::I4 => g.sym(Sym::I4),
        Var::I5 => g.sym(Sym::I5),
        Var::SignI4 => g.sym(Sym::SignI4),
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
