//! Between expressions and rational functions in σ.
//!
//! Variables: 0..3 are σ0..σ2, then one per parameter, then one per *atom*:
//! a non-rational subexpression (log, exp, a symbolic power) or the root
//! `b^(1/q)` of a fractional power `b^(p/q)` (so `s^(3/2)` and `s^(1/2)` are
//! related: t³ and t). Atoms are treated as independent variables. That is
//! sound for proving `≡ 0` (a polynomial that vanishes for all values of
//! independent variables vanishes for the actual ones) but not for proving
//! `≢ 0`, which is why results that mention an atom answer `Unknown`.
//!
//! The invariants are substituted on the way in (I1 = Σσ, I2 = Σσ², I3 = Πσ
//! for the dimension), also inside atoms, so `log(I3)` and `log(s1*s2*s3)`
//! are the same atom.

use std::collections::{BTreeMap, HashMap};

use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive};

use super::polynomial::{Poly, TooBig};
use super::ratfun::RatFun;
use crate::cas::{Graph, Id, Node, Sym};

/// Largest |integer exponent| expanded symbolically.
const MAX_EXPAND_POWER: i64 = 64;
/// Nesting depth up to which atoms' arguments are normalised.
const MAX_NORMAL_DEPTH: usize = 32;

/// The answer of an exact identity test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Proof {
    /// Proved identically zero.
    Zero,
    /// Proved not identically zero.
    NonZero,
    /// Could not decide (non-rational, too large, or undefined).
    Unknown,
}

/// What an atom variable stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Atom {
    /// The expression itself (σ-substituted).
    Opaque(Id),
    /// `base^(1/q)`.
    Root(Id, u32),
}

/// Converts expressions of one graph and dimension to rational functions.
pub struct Converter {
    dim: u8,
    nparams: usize,
    atoms: Vec<Atom>,
    atom_index: HashMap<Atom, usize>,
    memo: HashMap<Id, Option<RatFun>>,
    inv: Option<[Id; 3]>,
    /// `to_sigma` of every node substituted so far (shared by all calls:
    /// the derivatives share most of their subexpressions).
    sigma: HashMap<Id, Id>,
    depth: usize,
}

impl Converter {
    /// A converter for expressions of `g` in dimension `dim`. Arms this
    /// thread's polynomial work budget ([`super::WORK_BUDGET`]).
    pub fn new(g: &Graph, dim: u8) -> Self {
        super::set_budget(super::WORK_BUDGET);
        Converter {
            dim,
            nparams: g.param_names().len(),
            atoms: Vec::new(),
            atom_index: HashMap::new(),
            memo: HashMap::new(),
            inv: None,
            sigma: HashMap::new(),
            depth: 0,
        }
    }

    /// Index of the first atom variable.
    fn atom_base(&self) -> usize {
        3 + self.nparams
    }

    /// Bitmask (as used by `Poly::var_mask`) of all atom variables.
    pub fn atom_mask(&self) -> u64 {
        let base = self.atom_base().min(63);
        if self.atoms.is_empty() {
            0
        } else {
            !0u64 << base
        }
    }

    /// Whether a rational function mentions an atom (so it is not rational in σ).
    pub fn has_atoms(&self, r: &RatFun) -> bool {
        r.var_mask() & self.atom_mask() != 0
    }

    /// The invariants as σ-expressions in `g` (built once).
    pub fn sigma_invariants(&mut self, g: &mut Graph) -> [Id; 3] {
        if let Some(i) = self.inv {
            return i;
        }
        let s: Vec<Id> = (0..self.dim).map(|k| g.sym(Sym::Sigma(k))).collect();
        let i1 = g.sum(&s);
        let sq: Vec<Id> = s.iter().map(|&x| g.powi(x, 2)).collect();
        let i2 = g.sum(&sq);
        let i3 = g.product(&s);
        self.inv = Some([i1, i2, i3]);
        [i1, i2, i3]
    }

    /// `id` with I1, I2, I3 replaced by their σ-expressions (what
    /// `Graph::substitute` gives, memoised across calls: only the nodes not
    /// substituted before are visited).
    pub fn to_sigma(&mut self, g: &mut Graph, id: Id) -> Id {
        let [i1, i2, i3] = self.sigma_invariants(g);
        let order = g.reachable_except(&[id], |x| self.sigma.contains_key(&x));
        for x in order {
            let node = g.get(x).clone();
            let new = match node {
                Node::Sym(Sym::I1) => i1,
                Node::Sym(Sym::I2) => i2,
                Node::Sym(Sym::I3) => i3,
                Node::Sym(_) | Node::Num(_) => x,
                ref n => {
                    let sigma = &self.sigma;
                    if n.children().iter().all(|c| sigma[c] == *c) {
                        x
                    } else {
                        g.rebuild(n, &|c| sigma[&c])
                    }
                }
            };
            self.sigma.insert(x, new);
        }
        self.sigma[&id]
    }

    fn atom_var(&mut self, a: Atom) -> usize {
        if let Some(&i) = self.atom_index.get(&a) {
            return i;
        }
        let i = self.atom_base() + self.atoms.len();
        self.atoms.push(a);
        self.atom_index.insert(a, i);
        i
    }

    /// The rational function of `root`; `None` if it is undefined (a
    /// division by something identically 0, a stretch beyond the dimension)
    /// or too large to expand.
    pub fn convert(&mut self, g: &mut Graph, root: Id) -> Option<RatFun> {
        // Iterative post-order that does not descend into atoms.
        let mut stack: Vec<(Id, bool)> = vec![(root, false)];
        while let Some((id, ready)) = stack.pop() {
            if self.memo.contains_key(&id) {
                continue;
            }
            let node = g.get(id).clone();
            let kids: Vec<Id> = match &node {
                Node::Add(c) | Node::Mul(c) => c.clone(),
                Node::Pow([b, e]) if g.as_num(*e).is_some_and(|r| r.is_integer()) => vec![*b],
                _ => Vec::new(),
            };
            if !ready && kids.iter().any(|k| !self.memo.contains_key(k)) {
                stack.push((id, true));
                stack.extend(kids.iter().map(|k| (*k, false)));
                continue;
            }
            let r = self.convert_node(g, id, &node).unwrap_or(None);
            self.memo.insert(id, r);
        }
        self.memo.get(&root).cloned().flatten()
    }

    fn convert_node(
        &mut self,
        g: &mut Graph,
        id: Id,
        node: &Node,
    ) -> Result<Option<RatFun>, TooBig> {
        let child = |c: &Id| self.memo.get(c).cloned().flatten();
        Ok(Some(match node {
            Node::Num(r) => RatFun::constant(r.clone()),
            Node::Sym(Sym::Sigma(k)) if *k < self.dim => RatFun::poly(Poly::var(*k as usize)),
            Node::Sym(Sym::Sigma(_)) => return Ok(None),
            Node::Sym(Sym::Param(k)) => RatFun::poly(Poly::var(3 + *k as usize)),
            // Fibre parts are never converted to σ (they are not functions of σ).
            Node::Sym(Sym::I4 | Sym::I5 | Sym::SignI4) => return Ok(None),
            Node::Sym(inv) => {
                let n = self.dim as usize;
                let s = |k: usize| Poly::var(k);
                let mut p = match inv {
                    Sym::I3 => Poly::one(),
                    _ => Poly::zero(),
                };
                for k in 0..n {
                    p = match inv {
                        Sym::I1 => p.add(&s(k))?,
                        Sym::I2 => p.add(&s(k).mul(&s(k))?)?,
                        _ => p.mul(&s(k))?,
                    };
                }
                RatFun::poly(p)
            }
            Node::Add(c) => {
                let kids: Option<Vec<&RatFun>> = c
                    .iter()
                    .map(|x| self.memo.get(x).and_then(Option::as_ref))
                    .collect();
                // An undefined term makes the sum undefined (no work spent:
                // summing the terms before it was quadratic and discarded).
                let Some(kids) = kids else { return Ok(None) };
                RatFun::sum(&kids)?
            }
            Node::Mul(c) => {
                let mut acc = RatFun::one();
                for x in c {
                    let Some(r) = child(x) else { return Ok(None) };
                    acc = acc.mul(&r)?;
                }
                acc
            }
            Node::Pow([b, e]) => {
                let en = g.as_num(*e).cloned();
                match en {
                    Some(r) if r.is_integer() => {
                        let n = r
                            .to_integer()
                            .to_i64()
                            .filter(|n| n.abs() <= MAX_EXPAND_POWER);
                        match (n, child(b)) {
                            (Some(n), Some(base)) => return base.powi(n),
                            (None, Some(_)) => self.opaque(g, id),
                            _ => return Ok(None),
                        }
                    }
                    Some(r) => {
                        // b^(p/q) = t^p with t = b^(1/q).
                        let q = r.denom().to_u32().filter(|q| *q <= 64);
                        let p = r.numer().to_i64().filter(|p| p.abs() <= MAX_EXPAND_POWER);
                        match (q, p) {
                            (Some(q), Some(p)) => {
                                let bs = self.normal_form(g, *b);
                                let t = self.atom_var(Atom::Root(bs, q));
                                let tp = Poly::monomial(
                                    BigRational::one(),
                                    &Poly::unit_mono(t, p.unsigned_abs() as u32),
                                );
                                if p.is_negative() {
                                    RatFun::from_parts(Poly::one(), vec![(tp, 1)])?
                                } else {
                                    RatFun::poly(tp)
                                }
                            }
                            _ => self.opaque(g, id),
                        }
                    }
                    None => self.opaque(g, id),
                }
            }
            Node::Log(_) | Node::Exp(_) => self.opaque(g, id),
        }))
    }

    fn opaque(&mut self, g: &mut Graph, id: Id) -> RatFun {
        let s = self.normal_form(g, id);
        RatFun::poly(Poly::var(self.atom_var(Atom::Opaque(s))))
    }

    /// A canonical form of `id` modulo rational identities: invariants
    /// substituted, rational parts expanded to numerator/denominator form,
    /// applied recursively inside logs, exps and powers (to a bounded depth).
    /// Two expressions with the same normal form are equal.
    pub fn normal_form(&mut self, g: &mut Graph, id: Id) -> Id {
        let s = self.to_sigma(g, id);
        if self.depth > MAX_NORMAL_DEPTH {
            return s;
        }
        self.depth += 1;
        let out = match g.get(s).clone() {
            Node::Log(x) => {
                let n = self.normal_arg(g, x);
                g.log(n)
            }
            Node::Exp(x) => {
                let n = self.normal_arg(g, x);
                g.exp(n)
            }
            Node::Pow([b, e]) if !g.as_num(e).is_some_and(|r| r.is_integer()) => {
                let (nb, ne) = (self.normal_arg(g, b), self.normal_arg(g, e));
                g.pow(nb, ne)
            }
            _ => self.normal_arg(g, s),
        };
        self.depth -= 1;
        out
    }

    fn normal_arg(&mut self, g: &mut Graph, x: Id) -> Id {
        match self.convert(g, x) {
            Some(r) => self.to_expr_opts(g, &r, false),
            None => x,
        }
    }

    /// Decide `id ≡ 0` (as a function of σ and the parameters).
    pub fn is_zero(&mut self, g: &mut Graph, id: Id) -> Proof {
        if g.is_int(id, 0) {
            return Proof::Zero;
        }
        match self.convert(g, id) {
            Some(r) if r.is_zero() => Proof::Zero,
            Some(r) if !self.has_atoms(&r) => Proof::NonZero,
            _ => Proof::Unknown,
        }
    }

    /// Whether the expression is rational in σ and the parameters.
    pub fn rational(&mut self, g: &mut Graph, id: Id) -> Option<RatFun> {
        self.convert(g, id).filter(|r| !self.has_atoms(r))
    }

    /// Build a compact expression for a rational function: the numerator's
    /// rational and monomial content are factored out and the monomial parts
    /// of numerator and denominator merged into σ powers; a power of
    /// σ0·…·σ_{d−1} common to all of them is written as a power of I3.
    pub fn to_expr(&self, g: &mut Graph, r: &RatFun) -> Id {
        self.to_expr_opts(g, r, true)
    }

    /// [`Converter::to_expr`]; `use_i3` allows writing Π σ powers as I3 powers.
    fn to_expr_opts(&self, g: &mut Graph, r: &RatFun, use_i3: bool) -> Id {
        if r.num.is_zero() {
            return g.zero();
        }
        let m = r.num.monomial_content();
        let rest = r.num.div_mono(&m);
        let c = rest.content();
        // A huge content (e.g. lcm(1…n)⁻¹ for coefficients 1/k) stays inside:
        // factoring it out would make every coefficient huge.
        let c = if c.numer().bits() + c.denom().bits() > crate::cas::MAX_CONTENT_BITS {
            BigRational::from_integer(c.numer().signum())
        } else {
            c
        };
        let rest = rest.scale(&c.recip());
        // Net exponent per variable of the monomial parts (sparse: energies
        // with many atoms have many variables, few of them in any one term).
        let mut net: BTreeMap<usize, i64> = m.iter().map(|(i, e)| (i, e as i64)).collect();
        let mut den_polys: Vec<(Id, u32)> = Vec::new();
        for (f, e) in &r.den {
            let lead = f.leading().map(|(m, _)| m.clone()).unwrap_or_default();
            let single = f.len() == 1 && lead.len() == 1 && lead.iter().all(|(_, x)| x == 1);
            if single && let Some(v) = lead.last_var() {
                *net.entry(v).or_insert(0) -= *e as i64;
            } else {
                let fe = self.poly_to_expr(g, f);
                den_polys.push((fe, *e));
            }
        }
        let mut factors: Vec<Id> = vec![g.num(c)];
        let d = self.dim as usize;
        let k = (0..d)
            .map(|i| net.get(&i).copied().unwrap_or(0))
            .max()
            .unwrap_or(0);
        if k < 0 && use_i3 {
            let i3 = g.sym(Sym::I3);
            factors.push(g.powi(i3, k));
            for i in 0..d {
                *net.entry(i).or_insert(0) -= k;
            }
        }
        for (&i, &e) in &net {
            if e != 0 {
                let v = self.var_expr(g, i);
                factors.push(g.powi(v, e));
            }
        }
        factors.push(self.poly_to_expr(g, &rest));
        for (fe, e) in den_polys {
            factors.push(g.powi(fe, -(e as i64)));
        }
        g.product(&factors)
    }

    fn var_expr(&self, g: &mut Graph, i: usize) -> Id {
        if i < 3 {
            g.sym(Sym::Sigma(i as u8))
        } else if i < self.atom_base() {
            g.sym(Sym::Param((i - 3) as u16))
        } else {
            match self.atoms[i - self.atom_base()] {
                Atom::Opaque(id) => id,
                Atom::Root(b, q) => {
                    let e = g.num(BigRational::new(1.into(), q.into()));
                    g.pow(b, e)
                }
            }
        }
    }

    /// A polynomial as a sum of monomials.
    pub fn poly_to_expr(&self, g: &mut Graph, p: &Poly) -> Id {
        let mut terms = Vec::with_capacity(p.len());
        for (m, c) in p.terms() {
            let mut f = vec![g.num(c.clone())];
            for (i, e) in m.iter() {
                let v = self.var_expr(g, i);
                f.push(g.powi(v, e as i64));
            }
            terms.push(g.product(&f));
        }
        g.sum(&terms)
    }
}

/// Convenience: decide `id ≡ 0` in dimension `dim`.
pub fn is_zero(g: &mut Graph, dim: u8, id: Id) -> Proof {
    Converter::new(g, dim).is_zero(g, id)
}
