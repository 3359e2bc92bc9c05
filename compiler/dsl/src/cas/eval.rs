//! f64 evaluation of expressions.

use num_rational::BigRational;
use num_traits::ToPrimitive;

use super::graph::Graph;
use super::node::{Id, Node, Sym};
use super::rat;

/// Values of the leaves: σ, the invariants and the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Env {
    /// σ0, σ1, σ2 (σ2 unused in 2D).
    pub sigma: [f64; 3],
    /// I1, I2, I3.
    pub inv: [f64; 3],
    /// Parameter values by index.
    pub params: Vec<f64>,
    /// I4, I5 and sign(I4) of a fibre part (NaN unless set by [`Env::with_fibre`]).
    pub fibre: [f64; 3],
}

impl Env {
    /// An environment for dimension `dim` whose invariants are computed from
    /// σ: I1 = Σσi, I2 = Σσi², I3 = Πσi (over the first `dim` entries).
    pub fn new(dim: u8, sigma: &[f64], params: &[f64]) -> Self {
        let mut s = [0.0; 3];
        let n = (dim as usize).min(3).min(sigma.len());
        s[..n].copy_from_slice(&sigma[..n]);
        let i1 = s[..n].iter().sum();
        let i2 = s[..n].iter().map(|x| x * x).sum();
        let i3 = s[..n].iter().product();
        Env {
            sigma: s,
            inv: [i1, i2, i3],
            params: params.to_vec(),
            fibre: [f64::NAN; 3],
        }
    }

    /// This environment with the fibre invariants I4, I5 set; sign(I4) is
    /// +1 for I4 > 0 and −1 otherwise (NaN for a NaN I4).
    pub fn with_fibre(mut self, i4: f64, i5: f64) -> Self {
        self.fibre = [i4, i5, sign_i4(i4)];
        self
    }

    fn sym(&self, s: Sym) -> f64 {
        match s {
            Sym::I1 => self.inv[0],
            Sym::I2 => self.inv[1],
            Sym::I3 => self.inv[2],
            Sym::Sigma(k) => self.sigma.get(k as usize).copied().unwrap_or(f64::NAN),
            Sym::Param(k) => self.params.get(k as usize).copied().unwrap_or(f64::NAN),
            Sym::I4 => self.fibre[0],
            Sym::I5 => self.fibre[1],
            Sym::SignI4 => self.fibre[2],
        }
    }
}

/// sign(I4) as every back end computes it: +1 for I4 > 0, −1 otherwise
/// (I4 = 0 included, HOBAK's convention), NaN for NaN.
pub fn sign_i4(i4: f64) -> f64 {
    if i4 > 0.0 {
        1.0
    } else if i4.is_nan() {
        f64::NAN
    } else {
        -1.0
    }
}

/// Evaluate `id` at `env` (IEEE semantics: 1/0 = ∞, log(−1) = NaN).
pub fn eval(g: &Graph, id: Id, env: &Env) -> f64 {
    Tape::new(g, &[id]).eval(env)[0]
}

/// Evaluate several roots at once.
pub fn eval_many(g: &Graph, ids: &[Id], env: &Env) -> Vec<f64> {
    Tape::new(g, ids).eval(env)
}

/// A straight-line program for repeated evaluation of some roots of a graph.
#[derive(Clone, Debug)]
pub struct Tape {
    ops: Vec<Op>,
    roots: Vec<usize>,
}

#[derive(Clone, Debug)]
enum Op {
    Const(f64),
    Sym(Sym),
    Add(Vec<usize>),
    Mul(Vec<usize>),
    PowI(usize, i32),
    /// base^(p/q) with odd q: real odd roots of negative bases.
    PowOdd(usize, f64, bool),
    Sqrt(usize),
    Pow(usize, usize),
    Log(usize),
    Exp(usize),
}

impl Tape {
    /// Compile the nodes reachable from `roots` into a tape.
    pub fn new(g: &Graph, roots: &[Id]) -> Self {
        let order = g.reachable(roots);
        let mut slot = std::collections::HashMap::with_capacity(order.len());
        let mut ops = Vec::with_capacity(order.len());
        for id in order {
            let s = |c: &Id| slot[c];
            let op = match g.get(id) {
                Node::Num(r) => Op::Const(rat::to_f64(r)),
                Node::Sym(x) => Op::Sym(*x),
                Node::Add(c) => Op::Add(c.iter().map(s).collect()),
                Node::Mul(c) => Op::Mul(c.iter().map(s).collect()),
                Node::Pow([b, e]) => pow_op(g, slot[b], slot[e], g.as_num(*e)),
                Node::Log(x) => Op::Log(slot[x]),
                Node::Exp(x) => Op::Exp(slot[x]),
            };
            slot.insert(id, ops.len());
            ops.push(op);
        }
        let roots = roots.iter().map(|r| slot[r]).collect();
        Tape { ops, roots }
    }

    /// Values of the roots at `env`.
    pub fn eval(&self, env: &Env) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.ops.len());
        for op in &self.ops {
            let x = match op {
                Op::Const(c) => *c,
                Op::Sym(s) => env.sym(*s),
                Op::Add(c) => c.iter().map(|&i| v[i]).sum(),
                Op::Mul(c) => c.iter().map(|&i| v[i]).product(),
                Op::PowI(b, n) => f64::powi(v[*b], *n),
                Op::PowOdd(b, e, odd_numer) => {
                    let x: f64 = v[*b];
                    let r = x.abs().powf(*e);
                    if x < 0.0 && *odd_numer { -r } else { r }
                }
                Op::Sqrt(b) => f64::sqrt(v[*b]),
                Op::Pow(b, e) => f64::powf(v[*b], v[*e]),
                Op::Log(x) => f64::ln(v[*x]),
                Op::Exp(x) => f64::exp(v[*x]),
            };
            v.push(x);
        }
        self.roots.iter().map(|&r| v[r]).collect()
    }
}

fn pow_op(_g: &Graph, b: usize, e: usize, num: Option<&BigRational>) -> Op {
    let Some(r) = num else { return Op::Pow(b, e) };
    if let Some(n) = rat::as_i64(r).and_then(|n| i32::try_from(n).ok()) {
        return Op::PowI(b, n);
    }
    if *r == BigRational::new(1.into(), 2.into()) {
        return Op::Sqrt(b);
    }
    let q_odd = r.denom().to_u64().is_some_and(|q| q % 2 == 1);
    if q_odd {
        let p_odd = r.numer().to_i64().is_some_and(|p| p % 2 != 0);
        return Op::PowOdd(b, rat::to_f64(r), p_odd);
    }
    Op::Pow(b, e)
}
