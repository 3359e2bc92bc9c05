//! Lowering a graph to register instructions (see the parent module docs).

use std::collections::HashMap;

use ecc_dsl::{Graph, Id, Node, Sym};
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::{N_INPUTS, Op, Tape};
use crate::error::BuildError;

/// Largest |n| for which x^n is expanded into multiplications (repeated
/// squaring: at most 2·log2(n) products). Larger exponents use `powf`.
pub const MAX_CHAIN_EXPONENT: u64 = 1024;

/// Provisional register tags, resolved once the frozen block size is known.
const FROZEN: u32 = 1 << 30;
const MAIN: u32 = 1 << 31;
const INDEX: u32 = FROZEN - 1;

type Rational = num_rational::BigRational;

struct Lowerer<'g> {
    g: &'g Graph,
    node_reg: Vec<u32>,
    prelude: Vec<Op>,
    main: Vec<Op>,
    n_frozen: u32,
    n_main: u32,
    n_params: usize,
    consts: HashMap<u64, u32>,
    powers: HashMap<(u32, i64), u32>,
    roots: HashMap<(u32, u64), u32>,
}

/// `-1 · y` as a two-factor product: returns y.
fn negated(g: &Graph, id: Id) -> Option<Id> {
    match g.get(id) {
        Node::Mul(c) if c.len() == 2 => {
            let minus_one = g.as_num(c[0]).is_some_and(|r| *r == -Rational::one());
            minus_one.then_some(c[1])
        }
        _ => None,
    }
}

/// `y^e` with a negative rational constant e: returns (y, −e).
fn reciprocal_power(g: &Graph, id: Id) -> Option<(Id, Rational)> {
    match g.get(id) {
        Node::Pow([b, e]) => g
            .as_num(*e)
            .filter(|r| r.is_negative())
            .map(|r| (*b, -r.clone())),
        _ => None,
    }
}

impl Tape {
    /// Compile the nodes of `g` reachable from `roots` (see the module docs).
    /// Fails only if a root is not a node of `g`.
    pub fn compile(g: &Graph, roots: &[Id]) -> Result<Tape, BuildError> {
        if let Some(bad) = roots.iter().find(|r| r.index() >= g.len()) {
            return Err(BuildError::BadId { id: bad.0 });
        }
        let needed = needed_nodes(g, roots);
        let mut lw = Lowerer {
            g,
            node_reg: vec![u32::MAX; g.len()],
            prelude: Vec::new(),
            main: Vec::new(),
            n_frozen: 0,
            n_main: 0,
            n_params: g.param_names().len(),
            consts: HashMap::new(),
            powers: HashMap::new(),
            roots: HashMap::new(),
        };
        for (i, &is_needed) in needed.iter().enumerate() {
            if is_needed {
                let r = lw.lower_node(Id(i as u32));
                lw.node_reg[i] = r;
            }
        }
        let outputs: Vec<u32> = roots.iter().map(|r| lw.node_reg[r.index()]).collect();
        Ok(lw.finish(outputs))
    }
}

/// Which nodes get a register: the roots and, transitively, the operands the
/// lowering rules actually read (e.g. for `a + (−1)·b` only `a` and `b`).
fn needed_nodes(g: &Graph, roots: &[Id]) -> Vec<bool> {
    let mut needed = vec![false; g.len()];
    for r in roots {
        needed[r.index()] = true;
    }
    for i in (0..g.len()).rev() {
        if !needed[i] {
            continue;
        }
        let id = Id(i as u32);
        match g.get(id) {
            Node::Num(_) | Node::Sym(_) => {}
            Node::Add(c) => {
                for &x in c {
                    needed[negated(g, x).unwrap_or(x).index()] = true;
                }
            }
            Node::Mul(c) => {
                for &x in c {
                    if g.as_num(x).is_some() {
                        continue;
                    }
                    let y = reciprocal_power(g, x).map_or(x, |(y, _)| y);
                    needed[y.index()] = true;
                }
            }
            Node::Pow([b, e]) => {
                needed[b.index()] = true;
                if g.as_num(*e).is_none() {
                    needed[e.index()] = true;
                }
            }
            Node::Log(x) | Node::Exp(x) => needed[x.index()] = true,
        }
    }
    needed
}

fn is_frozen(r: u32) -> bool {
    r & FROZEN != 0
}

fn to_f64(r: &Rational) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

impl Lowerer<'_> {
    /// Allocate `dst` in the frozen block if every operand is frozen, else in
    /// the per-point block, and push the instruction built by `make`.
    fn emit(&mut self, operands: &[u32], make: impl FnOnce(u32) -> Op) -> u32 {
        if operands.iter().all(|&r| is_frozen(r)) {
            let dst = FROZEN | self.n_frozen;
            self.n_frozen += 1;
            self.prelude.push(make(dst));
            dst
        } else {
            let dst = MAIN | self.n_main;
            self.n_main += 1;
            self.main.push(make(dst));
            dst
        }
    }

    fn constant(&mut self, value: f64) -> u32 {
        if let Some(&r) = self.consts.get(&value.to_bits()) {
            return r;
        }
        let r = self.emit(&[], |dst| Op::Const { dst, value });
        self.consts.insert(value.to_bits(), r);
        r
    }

    fn reg(&self, id: Id) -> u32 {
        self.node_reg[id.index()]
    }

    fn lower_node(&mut self, id: Id) -> u32 {
        let g = self.g;
        match g.get(id) {
            Node::Num(r) => self.constant(to_f64(r)),
            Node::Sym(s) => match *s {
                Sym::Sigma(k) if k < 3 => u32::from(k),
                Sym::Sigma(_) => self.constant(f64::NAN),
                Sym::I1 => 3,
                Sym::I2 => 4,
                Sym::I3 => 5,
                // A fibre part ψ(I4, I5) has no σ: its tape reads I4, I5 and
                // sign(I4) from the σ input registers (`crate::fibre`).
                Sym::I4 => 0,
                Sym::I5 => 1,
                Sym::SignI4 => 2,
                Sym::Param(k) => {
                    self.n_params = self.n_params.max(usize::from(k) + 1);
                    self.emit(&[], |dst| Op::Param {
                        dst,
                        k: u32::from(k),
                    })
                }
            },
            Node::Add(c) => self.lower_sum(c),
            Node::Mul(c) => self.lower_product(c),
            Node::Pow([b, e]) => {
                let base = self.reg(*b);
                match g.as_num(*e) {
                    Some(r) => self.rational_power(base, r),
                    None => {
                        let ex = self.reg(*e);
                        self.emit(&[base, ex], |dst| Op::Powf {
                            dst,
                            a: base,
                            b: ex,
                        })
                    }
                }
            }
            Node::Log(x) => {
                let a = self.reg(*x);
                self.emit(&[a], |dst| Op::Log { dst, a })
            }
            Node::Exp(x) => {
                let a = self.reg(*x);
                self.emit(&[a], |dst| Op::Exp { dst, a })
            }
        }
    }

    /// Σ children: constant term last, `(−1)·y` terms subtracted, frozen
    /// terms first (so parameter-only partial sums land in the prelude).
    fn lower_sum(&mut self, children: &[Id]) -> u32 {
        let g = self.g;
        let mut constant = 0.0;
        let mut terms: Vec<(bool, u32)> = Vec::with_capacity(children.len());
        for &c in children {
            if let Some(r) = g.as_num(c) {
                constant += to_f64(r);
            } else if let Some(y) = negated(g, c) {
                terms.push((true, self.reg(y)));
            } else {
                terms.push((false, self.reg(c)));
            }
        }
        // Frozen terms first (prelude partial sums), then a positive term to start from.
        terms.sort_by_key(|&(neg, r)| (!is_frozen(r), neg));
        let mut acc = match terms.first() {
            None => return self.constant(constant),
            Some(&(false, r)) => r,
            Some(&(true, r)) => self.emit(&[r], |dst| Op::Neg { dst, a: r }),
        };
        for &(neg, r) in &terms[1..] {
            let a = acc;
            acc = if neg {
                self.emit(&[a, r], |dst| Op::Sub { dst, a, b: r })
            } else {
                self.emit(&[a, r], |dst| Op::Add { dst, a, b: r })
            };
        }
        if constant != 0.0 {
            let a = acc;
            acc = self.emit(&[a], |dst| Op::AddC {
                dst,
                a,
                c: constant,
            });
        }
        acc
    }

    /// Π children: c · (Π numerator factors) / (Π y^|e| over factors y^e, e < 0).
    fn lower_product(&mut self, children: &[Id]) -> u32 {
        let g = self.g;
        let mut coef = 1.0;
        let mut num = Vec::with_capacity(children.len());
        let mut den = Vec::new();
        for &c in children {
            if let Some(r) = g.as_num(c) {
                coef *= to_f64(r);
            } else if let Some((y, e)) = reciprocal_power(g, c) {
                let base = self.reg(y);
                den.push(self.rational_power(base, &e));
            } else {
                num.push(self.reg(c));
            }
        }
        let n = self.chain_product(&mut num);
        let d = self.chain_product(&mut den);
        match (n, d) {
            (None, None) => self.constant(coef),
            (None, Some(d)) => self.emit(&[d], |dst| Op::CDiv { dst, c: coef, a: d }),
            (Some(n), d) => {
                let q = match d {
                    Some(d) => self.emit(&[n, d], |dst| Op::Div { dst, a: n, b: d }),
                    None => n,
                };
                self.scale(q, coef)
            }
        }
    }

    fn scale(&mut self, a: u32, coef: f64) -> u32 {
        if coef == 1.0 {
            a
        } else if coef == -1.0 {
            self.emit(&[a], |dst| Op::Neg { dst, a })
        } else {
            self.emit(&[a], |dst| Op::MulC { dst, a, c: coef })
        }
    }

    fn chain_product(&mut self, regs: &mut [u32]) -> Option<u32> {
        regs.sort_by_key(|&r| !is_frozen(r));
        let (&first, rest) = regs.split_first()?;
        let mut acc = first;
        for &r in rest {
            let a = acc;
            acc = self.emit(&[a, r], |dst| Op::Mul { dst, a, b: r });
        }
        Some(acc)
    }

    /// base^e for an exact rational e (see the module docs for the rules).
    fn rational_power(&mut self, base: u32, e: &Rational) -> u32 {
        if e.is_zero() {
            return self.constant(1.0);
        }
        if e.is_negative() {
            let p = self.rational_power(base, &-e.clone());
            return self.emit(&[p], |dst| Op::CDiv { dst, c: 1.0, a: p });
        }
        let p = e.numer().to_u64().filter(|&p| p <= MAX_CHAIN_EXPONENT);
        let q = e.denom().to_u64();
        match (p, q) {
            (Some(p), Some(1)) => self.int_power(base, p as i64),
            (Some(p), Some(q)) if q == 2 || q % 2 == 1 => {
                let root = self.root(base, q);
                self.int_power(root, p as i64)
            }
            _ => {
                let odd_q = e.denom().is_odd();
                let odd_p = e.numer().is_odd();
                let ef = to_f64(e);
                self.emit(&[base], |dst| Op::PowRat {
                    dst,
                    a: base,
                    e: ef,
                    odd_q,
                    odd_p,
                })
            }
        }
    }

    /// The real q-th root of `base` (q = 2 or odd), shared between uses.
    fn root(&mut self, base: u32, q: u64) -> u32 {
        if let Some(&r) = self.roots.get(&(base, q)) {
            return r;
        }
        let r = match q {
            2 => self.emit(&[base], |dst| Op::Sqrt { dst, a: base }),
            3 => self.emit(&[base], |dst| Op::Cbrt { dst, a: base }),
            _ => {
                let e = 1.0 / q as f64;
                self.emit(&[base], |dst| Op::RootOdd { dst, a: base, e })
            }
        };
        self.roots.insert((base, q), r);
        r
    }

    /// base^n for 1 ≤ n ≤ MAX_CHAIN_EXPONENT by repeated squaring, sharing
    /// every intermediate power.
    fn int_power(&mut self, base: u32, n: i64) -> u32 {
        if n == 1 {
            return base;
        }
        if let Some(&r) = self.powers.get(&(base, n)) {
            return r;
        }
        let r = if n % 2 == 0 {
            let h = self.int_power(base, n / 2);
            self.emit(&[h], |dst| Op::Mul { dst, a: h, b: h })
        } else {
            let h = self.int_power(base, n - 1);
            self.emit(&[h, base], |dst| Op::Mul { dst, a: h, b: base })
        };
        self.powers.insert((base, n), r);
        r
    }

    /// Resolve provisional registers into the final layout.
    fn finish(self, outputs: Vec<u32>) -> Tape {
        let n_frozen = self.n_frozen;
        let fix = |r: u32| -> u32 {
            if r & MAIN != 0 {
                N_INPUTS as u32 + n_frozen + (r & INDEX)
            } else if r & FROZEN != 0 {
                N_INPUTS as u32 + (r & INDEX)
            } else {
                r
            }
        };
        let remap =
            |ops: Vec<Op>| -> Vec<Op> { ops.into_iter().map(|op| op.map_regs(fix)).collect() };
        Tape {
            prelude: remap(self.prelude),
            main: remap(self.main),
            n_frozen: n_frozen as usize,
            n_regs: N_INPUTS + (n_frozen + self.n_main) as usize,
            outputs: outputs.into_iter().map(fix).collect(),
            n_params: self.n_params,
        }
    }
}

impl Op {
    /// The same instruction with every register renamed by `f`.
    fn map_regs(self, f: impl Fn(u32) -> u32) -> Op {
        match self {
            Op::Const { dst, value } => Op::Const { dst: f(dst), value },
            Op::Param { dst, k } => Op::Param { dst: f(dst), k },
            Op::Add { dst, a, b } => Op::Add {
                dst: f(dst),
                a: f(a),
                b: f(b),
            },
            Op::Sub { dst, a, b } => Op::Sub {
                dst: f(dst),
                a: f(a),
                b: f(b),
            },
            Op::Mul { dst, a, b } => Op::Mul {
                dst: f(dst),
                a: f(a),
                b: f(b),
            },
            Op::Div { dst, a, b } => Op::Div {
                dst: f(dst),
                a: f(a),
                b: f(b),
            },
            Op::AddC { dst, a, c } => Op::AddC {
                dst: f(dst),
                a: f(a),
                c,
            },
            Op::MulC { dst, a, c } => Op::MulC {
                dst: f(dst),
                a: f(a),
                c,
            },
            Op::CDiv { dst, c, a } => Op::CDiv {
                dst: f(dst),
                c,
                a: f(a),
            },
            Op::Neg { dst, a } => Op::Neg {
                dst: f(dst),
                a: f(a),
            },
            Op::Sqrt { dst, a } => Op::Sqrt {
                dst: f(dst),
                a: f(a),
            },
            Op::Cbrt { dst, a } => Op::Cbrt {
                dst: f(dst),
                a: f(a),
            },
            Op::RootOdd { dst, a, e } => Op::RootOdd {
                dst: f(dst),
                a: f(a),
                e,
            },
            Op::PowRat {
                dst,
                a,
                e,
                odd_q,
                odd_p,
            } => Op::PowRat {
                dst: f(dst),
                a: f(a),
                e,
                odd_q,
                odd_p,
            },
            Op::Powf { dst, a, b } => Op::Powf {
                dst: f(dst),
                a: f(a),
                b: f(b),
            },
            Op::Log { dst, a } => Op::Log {
                dst: f(dst),
                a: f(a),
            },
            Op::Exp { dst, a } => Op::Exp {
                dst: f(dst),
                a: f(a),
            },
        }
    }
}
