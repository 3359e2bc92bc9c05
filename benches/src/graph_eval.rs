//! Evaluate an energy's CAS graph ([`ecc_dsl::DimIr`]) in any [`Real`] type.
//!
//! The DSL's own evaluator is f64-only; this walks the same nodes with the
//! same real-valued semantics (see [`ecc_dsl::Node::Pow`]): an integer
//! exponent is an exact power, ½ is `sqrt`, p/q with odd q is the real
//! power (odd roots of negative bases), anything else `powf`; log of a
//! negative number is NaN. Rational constants are converted to the target
//! precision (exactly representable ones exactly). Ψ = NaN is reported as
//! +∞ (outside the domain), as the runtime does.

use ecc_dsl::{DimIr, Graph, Id, Node, Sym};
use num_rational::BigRational;
use num_traits::ToPrimitive;

use ecc_tests::real::Real;

/// A compiled evaluation order for some roots of a graph.
#[derive(Clone, Debug)]
pub struct GraphEval {
    order: Vec<Id>,
    slot: Vec<usize>,
    roots: Vec<Id>,
    consts: Vec<Option<(i128, i128)>>,
}

/// Roots of interest in an energy's IR: Ψ, ∂Ψ/∂σ, ∂²Ψ/∂σ².
pub struct StretchRoots {
    pub psi: usize,
    pub grad: Vec<usize>,
    pub hess: Vec<Vec<usize>>,
}

fn ratio(r: &BigRational) -> Option<(i128, i128)> {
    Some((r.numer().to_i128()?, r.denom().to_i128()?))
}

impl GraphEval {
    /// Prepare to evaluate `roots` of `g`.
    pub fn new(g: &Graph, roots: &[Id]) -> Self {
        let order = g.reachable(roots);
        let mut slot = vec![usize::MAX; g.len()];
        for (k, id) in order.iter().enumerate() {
            slot[id.index()] = k;
        }
        let consts = order
            .iter()
            .map(|&id| g.as_num(id).and_then(ratio))
            .collect();
        GraphEval {
            order,
            slot,
            roots: roots.to_vec(),
            consts,
        }
    }

    /// Ψ, d_sigma and h_sigma of an IR, in that order (see [`StretchRoots`]).
    pub fn stretch(ir: &DimIr) -> (Self, StretchRoots) {
        let d = ir.dim as usize;
        let mut roots = vec![ir.psi];
        roots.extend_from_slice(&ir.d_sigma);
        roots.extend(ir.h_sigma.iter().flatten().copied());
        let idx = StretchRoots {
            psi: 0,
            grad: (1..=d).collect(),
            hess: (0..d)
                .map(|i| (0..d).map(|j| 1 + d + i * d + j).collect())
                .collect(),
        };
        (Self::new(&ir.graph, &roots), idx)
    }

    /// Values of the roots at signed singular values `sigma` (length 2 or 3)
    /// with parameter values `params`, into `out` (one per root); `work` is scratch.
    pub fn eval<R: Real>(
        &self,
        g: &Graph,
        sigma: &[R],
        params: &[f64],
        work: &mut Vec<R>,
        out: &mut [R],
    ) {
        let zero = R::zero();
        let i1 = sigma.iter().fold(zero, |a, &s| a + s);
        let i2 = sigma.iter().fold(zero, |a, &s| a + s * s);
        let i3 = sigma.iter().fold(R::one(), |a, &s| a * s);
        work.clear();
        for (k, &id) in self.order.iter().enumerate() {
            let v = |c: &Id| work[self.slot[c.index()]];
            let x = match g.get(id) {
                Node::Num(r) => match self.consts[k] {
                    Some((n, d)) => R::from_ratio(n, d),
                    None => R::from_f64(r.to_f64().unwrap_or(f64::NAN)),
                },
                Node::Sym(s) => match *s {
                    Sym::I1 => i1,
                    Sym::I2 => i2,
                    Sym::I3 => i3,
                    Sym::Sigma(i) => sigma
                        .get(i as usize)
                        .copied()
                        .unwrap_or(R::from_f64(f64::NAN)),
                    Sym::Param(i) => {
                        R::from_f64(params.get(i as usize).copied().unwrap_or(f64::NAN))
                    }
                    // Isotropic energies only: a fibre part has no σ.
                    Sym::I4 | Sym::I5 | Sym::SignI4 => R::from_f64(f64::NAN),
                },
                Node::Add(c) => c.iter().fold(zero, |a, c| a + v(c)),
                Node::Mul(c) => c.iter().fold(R::one(), |a, c| a * v(c)),
                Node::Pow([b, e]) => pow(v(b), v(e), g.as_num(*e)),
                Node::Log(x) => {
                    let a = v(x);
                    if a < zero {
                        R::from_f64(f64::NAN)
                    } else {
                        a.ln()
                    }
                }
                Node::Exp(x) => v(x).exp(),
            };
            work.push(x);
        }
        for (o, r) in out.iter_mut().zip(&self.roots) {
            *o = work[self.slot[r.index()]];
        }
    }
}

fn pow<R: Real>(b: R, e: R, num: Option<&BigRational>) -> R {
    let Some(r) = num else { return b.powf(e) };
    if r.is_integer()
        && let Some(n) = r.numer().to_i32()
    {
        return b.powi(n);
    }
    let (Some(p), Some(q)) = (r.numer().to_i64(), r.denom().to_i64()) else {
        return b.powf(e);
    };
    if p == 1 && q == 2 {
        return b.sqrt();
    }
    if q % 2 == 1 {
        let m = b.abs().powf(e);
        return if b < R::zero() && p % 2 != 0 { -m } else { m };
    }
    if q == 2 {
        // b^(p/2) = sqrt(b)^p: exact-power route, more accurate than exp(e ln b)
        return b.sqrt().powi(p as i32);
    }
    b.powf(e)
}
