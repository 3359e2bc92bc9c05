//! Canonicalising smart constructors.
//!
//! Rules applied (all exact; the ones marked † hold only where both sides are
//! defined, which is the documented convention of this CAS):
//!
//! * sums are flattened, like terms collected with rational coefficients
//!   (`2*x*y + 3*y*x = 5*x*y`), constants folded, zero terms dropped;
//! * a rational coefficient times a single sum distributes (`2*(x+y) = 2*x + 2*y`);
//!   a sum multiplied by anything else, or raised to an integer power, gives
//!   up its rational content instead (`k*(2*x - 4) = 2*k*(x - 2)`);
//! * products are flattened, powers of a common base collected
//!   (`x^a * x^b = x^(a+b)`, hence † `x/x = x^0 = 1` for x ≠ 0), the rational
//!   coefficient folded, † `0*x = 0` (for finite x);
//! * `x^0 = 1`, `x^1 = x`, `1^y = 1`, `0^y = 0` for constant y > 0;
//!   rational powers of rationals fold when exact (`4^(1/2) = 2`,
//!   `(-8)^(1/3) = -2`, `2^-2 = 1/4`);
//! * `(x^a)^n = x^(a*n)` and `(x*y)^n = x^n * y^n` only for integer n (always
//!   valid), `exp(x)^y = exp(x*y)`;
//! * `log(1) = 0`, `exp(0) = 1`, `log(exp(x)) = x`, † `exp(log(x)) = x`
//!   (valid wherever `log(x)` is defined);
//! * `sqrt(x) = x^(1/2)`, `a - b = a + (-1)*b`, `a / b = a * b^-1`.

use std::collections::BTreeMap;

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::graph::Graph;
use super::node::{Id, Node};
use super::rat;

/// Largest rational content (numerator + denominator bits) pulled out of a
/// sum. Beyond it the sum is kept as it is: a content such as
/// lcm(1…n)⁻¹ (Σ_k c_k/k · x_k, ≈ 1.44 n bits) would give every one of the
/// n coefficients ≈ 1.44 n bits, a quadratic blow-up of an input of linear
/// size (e.g. the gradient of Σ_k exp(I1/k)).
pub const MAX_CONTENT_BITS: u64 = 64;

impl Graph {
    /// The constant 0.
    pub fn zero(&mut self) -> Id {
        self.int(0)
    }

    /// The constant 1.
    pub fn one(&mut self) -> Id {
        self.int(1)
    }

    /// Whether `id` is the constant `value`.
    pub fn is_int(&self, id: Id, value: i64) -> bool {
        self.as_num(id).is_some_and(|r| *r == rat::int(value))
    }

    /// `a + b`.
    pub fn add2(&mut self, a: Id, b: Id) -> Id {
        self.sum(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.sum(&[a, nb])
    }

    /// `-a`.
    pub fn neg(&mut self, a: Id) -> Id {
        let m1 = self.int(-1);
        self.product(&[m1, a])
    }

    /// `a * b`.
    pub fn mul2(&mut self, a: Id, b: Id) -> Id {
        self.product(&[a, b])
    }

    /// `a / b` (= a * b^-1).
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let m1 = self.int(-1);
        let inv = self.pow(b, m1);
        self.product(&[a, inv])
    }

    /// `b^n` for an integer n.
    pub fn powi(&mut self, b: Id, n: i64) -> Id {
        let e = self.int(n);
        self.pow(b, e)
    }

    /// `sqrt(x)` = x^(1/2).
    pub fn sqrt(&mut self, x: Id) -> Id {
        let half = self.num(BigRational::new(1.into(), 2.into()));
        self.pow(x, half)
    }

    /// `c * x` for a rational c.
    pub fn scale(&mut self, c: BigRational, x: Id) -> Id {
        let c = self.num(c);
        self.product(&[c, x])
    }

    /// The canonical sum of `terms`.
    pub fn sum(&mut self, terms: &[Id]) -> Id {
        let mut constant = BigRational::zero();
        // rest -> coefficient, ordered by id for a deterministic layout.
        let mut collected: BTreeMap<Id, BigRational> = BTreeMap::new();
        let mut stack: Vec<Id> = terms.iter().rev().copied().collect();
        while let Some(t) = stack.pop() {
            super::graph::count_work(1);
            match self.get(t).clone() {
                Node::Num(c) => constant = rat::add(&constant, &c),
                Node::Add(children) => stack.extend(children.iter().rev()),
                _ => {
                    let (c, rest) = self.split_coefficient(t);
                    let e = collected.entry(rest).or_insert_with(BigRational::zero);
                    *e = rat::add(e, &c);
                }
            }
        }
        let mut out: Vec<Id> = Vec::with_capacity(collected.len() + 1);
        for (rest, c) in collected {
            if c.is_zero() {
                continue;
            }
            out.push(self.with_coefficient(c, rest));
        }
        out.sort();
        match (out.len(), constant.is_zero()) {
            (0, _) => self.num(constant),
            (1, true) => out[0],
            _ => {
                if !constant.is_zero() {
                    out.insert(0, self.num(constant));
                }
                self.add(Node::Add(out))
            }
        }
    }

    /// The canonical product of `factors`.
    pub fn product(&mut self, factors: &[Id]) -> Id {
        let mut pending: Vec<Id> = factors.to_vec();
        // Re-run when collecting powers produced new products or constants
        // (e.g. (x*y)^(1/2) * (x*y)^(3/2) = (x*y)^2 = x^2*y^2).
        for _round in 0..8 {
            let (mut coef, bases) = self.gather_factors(&pending);
            if coef.is_zero() {
                return self.zero();
            }
            let mut out: Vec<Id> = Vec::with_capacity(bases.len() + 1);
            let mut again = false;
            for (b, exps) in bases {
                let e = if exps.len() == 1 {
                    exps[0]
                } else {
                    self.sum(&exps)
                };
                let p = self.pow(b, e);
                match self.get(p) {
                    Node::Num(c) => coef = rat::mul(&coef, c),
                    Node::Mul(_) => {
                        again = true;
                        out.push(p);
                    }
                    _ => out.push(p),
                }
            }
            if coef.is_zero() {
                return self.zero();
            }
            if again {
                let c = self.num(coef);
                out.push(c);
                pending = out;
                continue;
            }
            self.pull_sum_content(&mut out, &mut coef);
            return self.assemble_product(out, coef);
        }
        // Unreachable in practice (each round strictly removes products of
        // products); keep an exact, merely less canonical, result.
        pending.sort();
        pending.dedup();
        self.add(Node::Mul(pending))
    }

    /// Flattens nested products of `factors` into the rational coefficient
    /// and, per base, the list of its exponents (a bare factor has exponent 1).
    fn gather_factors(&mut self, factors: &[Id]) -> (BigRational, BTreeMap<Id, Vec<Id>>) {
        let mut coef = BigRational::one();
        let mut bases: BTreeMap<Id, Vec<Id>> = BTreeMap::new();
        let mut stack: Vec<Id> = factors.iter().rev().copied().collect();
        while let Some(f) = stack.pop() {
            super::graph::count_work(1);
            match self.get(f).clone() {
                Node::Num(c) => coef = rat::mul(&coef, &c),
                Node::Mul(children) => stack.extend(children.iter().rev()),
                Node::Pow([b, e]) => bases.entry(b).or_default().push(e),
                _ => {
                    let one = self.one();
                    bases.entry(f).or_default().push(one)
                }
            }
        }
        (coef, bases)
    }

    /// Pulls the rational content out of sums that are multiplied by
    /// something else or raised to an integer power, into `coef`:
    /// kappa*(2*I1 - 4) = 2*kappa*(I1 - 2), (2*x + 2)^-1 = (x + 1)^-1/2.
    fn pull_sum_content(&mut self, out: &mut [Id], coef: &mut BigRational) {
        let several = out.len() >= 2;
        for f in out.iter_mut() {
            let (base, n) = match self.get(*f).clone() {
                Node::Add(_) if several => (*f, 1),
                Node::Pow([b, e]) if matches!(self.get(b), Node::Add(_)) => {
                    match self.as_num(e).and_then(rat::as_i64) {
                        Some(n) => (b, n),
                        None => continue,
                    }
                }
                _ => continue,
            };
            if let Some((g, prim)) = self.add_content(base) {
                match rat::pow_int(&g, n) {
                    Some(gn) => {
                        *coef = rat::mul(coef, &gn);
                        *f = self.powi(prim, n);
                    }
                    None => continue,
                }
            }
        }
    }

    /// The canonical product node of the collected factors `out` (sorted
    /// here) and the rational coefficient `coef`.
    fn assemble_product(&mut self, mut out: Vec<Id>, coef: BigRational) -> Id {
        out.sort();
        // A rational coefficient times a single sum distributes:
        // 2*(x + y) = 2*x + 2*y (keeps sums canonical, like SymPy).
        if out.len() == 1
            && !coef.is_one()
            && let Node::Add(terms) = self.get(out[0]).clone()
        {
            let c = self.num(coef);
            let scaled: Vec<Id> = terms.iter().map(|&t| self.product(&[c, t])).collect();
            return self.sum(&scaled);
        }
        match (out.len(), coef.is_one()) {
            (0, _) => self.num(coef),
            (1, true) => out[0],
            _ => {
                if !coef.is_one() {
                    out.insert(0, self.num(coef));
                }
                self.add(Node::Mul(out))
            }
        }
    }

    /// The canonical `base ^ exp`.
    pub fn pow(&mut self, base: Id, exp: Id) -> Id {
        if let Some(e) = self.as_num(exp).cloned() {
            if e.is_zero() {
                return self.one();
            }
            if e.is_one() {
                return base;
            }
            let int_e = rat::as_i64(&e);
            match self.get(base).clone() {
                Node::Num(b) => {
                    if b.is_one() || (b.is_zero() && e.is_positive()) {
                        return base;
                    }
                    if let Some(v) = rat::pow_rat(&b, &e) {
                        return self.num(v);
                    }
                }
                Node::Pow([bb, be]) if int_e.is_some() => {
                    let ne = self.product(&[be, exp]);
                    return self.pow(bb, ne);
                }
                Node::Mul(children) if int_e.is_some() => {
                    let parts: Vec<Id> = children.iter().map(|&c| self.pow(c, exp)).collect();
                    return self.product(&parts);
                }
                Node::Exp(x) => {
                    let xe = self.product(&[x, exp]);
                    return self.exp(xe);
                }
                Node::Add(_) if int_e.is_some() => {
                    if let Some((g, prim)) = self.add_content(base)
                        && let Some(gn) = int_e.and_then(|n| rat::pow_int(&g, n))
                    {
                        let p = self.add(Node::Pow([prim, exp]));
                        let c = self.num(gn);
                        return self.product(&[c, p]);
                    }
                }
                _ => {}
            }
        } else if self.is_int(base, 1) {
            return base;
        } else if let Node::Exp(x) = self.get(base).clone() {
            let xe = self.product(&[x, exp]);
            return self.exp(xe);
        }
        self.add(Node::Pow([base, exp]))
    }

    /// The canonical natural logarithm.
    pub fn log(&mut self, x: Id) -> Id {
        if self.is_int(x, 1) {
            return self.zero();
        }
        if let Node::Exp(y) = self.get(x) {
            return *y;
        }
        self.add(Node::Log(x))
    }

    /// The canonical exponential.
    pub fn exp(&mut self, x: Id) -> Id {
        if self.is_int(x, 0) {
            return self.one();
        }
        if let Node::Log(y) = self.get(x) {
            return *y;
        }
        self.add(Node::Exp(x))
    }

    /// For a sum with positive rational content g ≠ 1 (the gcd of the
    /// numerators over the lcm of the denominators of its coefficients) of at
    /// most [`MAX_CONTENT_BITS`] bits, `(g, sum / g)`.
    fn add_content(&mut self, add: Id) -> Option<(BigRational, Id)> {
        if let Some(known) = self.contents.get(&add) {
            return known.clone();
        }
        let r = self.compute_add_content(add);
        self.contents.insert(add, r.clone());
        r
    }

    /// [`Graph::add_content`], uncached.
    fn compute_add_content(&mut self, add: Id) -> Option<(BigRational, Id)> {
        let Node::Add(terms) = self.get(add).clone() else {
            return None;
        };
        let mut num = num_bigint::BigInt::zero();
        let mut den = num_bigint::BigInt::one();
        for t in &terms {
            let c = match self.get(*t) {
                Node::Num(c) => c.clone(),
                Node::Mul(f) => self.as_num(f[0]).cloned().unwrap_or_else(BigRational::one),
                _ => BigRational::one(),
            };
            num = rat::gcd(&num, c.numer());
            den = rat::lcm(&den, c.denom());
            if den.bits() > MAX_CONTENT_BITS {
                return None;
            }
        }
        // Coprime: a prime dividing every numerator divides no denominator.
        let g = BigRational::new_raw(num, den);
        if g.is_one() || g.is_zero() || g.numer().bits() + g.denom().bits() > MAX_CONTENT_BITS {
            return None;
        }
        let inv = self.num(g.recip());
        let scaled: Vec<Id> = terms.iter().map(|&t| self.product(&[inv, t])).collect();
        Some((g, self.sum(&scaled)))
    }

    /// Split a non-sum term into (rational coefficient, the rest).
    fn split_coefficient(&mut self, t: Id) -> (BigRational, Id) {
        if let Node::Mul(children) = self.get(t)
            && let Node::Num(c) = self.get(children[0])
        {
            let c = c.clone();
            let rest: Vec<Id> = children[1..].to_vec();
            let rest = if rest.len() == 1 {
                rest[0]
            } else {
                self.add(Node::Mul(rest))
            };
            return (c, rest);
        }
        (BigRational::one(), t)
    }

    /// `c * rest` where `rest` is a canonical non-constant, non-sum term.
    fn with_coefficient(&mut self, c: BigRational, rest: Id) -> Id {
        if c.is_one() {
            return rest;
        }
        let cn = self.num(c);
        let mut children = vec![cn];
        match self.get(rest) {
            Node::Mul(f) => children.extend_from_slice(f),
            _ => children.push(rest),
        }
        self.add(Node::Mul(children))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::Sym;

    #[test]
    fn like_terms_and_powers_collect() {
        let mut g = Graph::new(vec![]);
        let x = g.sym(Sym::I1);
        let y = g.sym(Sym::I2);
        let xy = g.mul2(x, y);
        let yx = g.mul2(y, x);
        assert_eq!(xy, yx);
        let two = g.int(2);
        let a = g.product(&[two, x, y]);
        let s = g.sum(&[a, yx]);
        let three = g.int(3);
        let expect = g.product(&[three, y, x]);
        assert_eq!(s, expect);
        let d = g.div(x, x);
        assert!(g.is_int(d, 1));
        let z = g.sub(xy, yx);
        assert!(g.is_int(z, 0));
    }

    #[test]
    fn rational_powers_fold_exactly() {
        let mut g = Graph::new(vec![]);
        let four = g.int(4);
        let r = g.sqrt(four);
        assert!(g.is_int(r, 2));
        let m8 = g.int(-8);
        let third = g.num(BigRational::new(1.into(), 3.into()));
        let c = g.pow(m8, third);
        assert!(g.is_int(c, -2));
        let two = g.int(2);
        let r2 = g.sqrt(two);
        assert!(matches!(g.get(r2), Node::Pow(_)));
        let sq = g.powi(r2, 2);
        assert!(g.is_int(sq, 2));
    }
}
