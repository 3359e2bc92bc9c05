//! Sparse multivariate polynomials over ℚ.
//!
//! A monomial is a sparse [`Mono`] (its non-zero exponents), ordered
//! lexicographically (variable 0 most significant). The leading term is the
//! largest key.

use std::collections::BTreeMap;

use crate::cas::rat;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

pub use super::mono::Mono;

/// Largest number of terms any intermediate polynomial may have; beyond it
/// the polynomial machinery gives up (answers "unknown"), which keeps every
/// compile bounded in time.
pub const MAX_TERMS: usize = 6000;

/// Largest coefficient (numerator + denominator bits) any polynomial may have.
pub const MAX_COEFF_BITS: u64 = 1024;

/// The polynomial exceeded [`MAX_TERMS`] or `MAX_COEFF_BITS`, or the work
/// budget ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooBig;

/// Coefficient operations allowed per [`set_budget`] (one compile of one
/// dimension arms it once): beyond it every polynomial operation answers
/// [`TooBig`], i.e. "unknown", which keeps adversarial inputs bounded in time
/// (the standard library uses well under 1% of it).
pub const WORK_BUDGET: u64 = 400_000;

thread_local! {
    static BUDGET: std::cell::Cell<u64> = const { std::cell::Cell::new(u64::MAX) };
}

/// Arm the per-thread work budget with `ops` coefficient operations.
pub fn set_budget(ops: u64) {
    BUDGET.with(|b| b.set(ops));
}

/// The remaining per-thread work budget.
pub fn budget_left() -> u64 {
    BUDGET.with(|b| b.get())
}

fn charge(ops: u64) -> Result<(), TooBig> {
    BUDGET.with(|b| {
        let left = b.get();
        if left < ops {
            b.set(0);
            Err(TooBig)
        } else {
            b.set(left - ops);
            Ok(())
        }
    })
}

/// A polynomial Σ c_m x^m with exact rational coefficients (never storing 0).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Poly {
    terms: BTreeMap<Mono, BigRational>,
}

/// Size of a coefficient in bits (numerator + denominator).
fn coeff_bits(c: &BigRational) -> u64 {
    c.numer().bits() + c.denom().bits()
}

impl Poly {
    /// 0.
    pub fn zero() -> Self {
        Poly::default()
    }

    /// A constant.
    pub fn constant(c: BigRational) -> Self {
        let mut p = Poly::zero();
        if !c.is_zero() {
            p.terms.insert(Mono::one(), c);
        }
        p
    }

    /// 1.
    pub fn one() -> Self {
        Poly::constant(BigRational::one())
    }

    /// The variable x_i.
    pub fn var(i: usize) -> Self {
        Poly::monomial(BigRational::one(), &Poly::unit_mono(i, 1))
    }

    /// c · x^m.
    pub fn monomial(c: BigRational, m: &Mono) -> Self {
        let mut p = Poly::zero();
        if !c.is_zero() {
            p.terms.insert(m.clone(), c);
        }
        p
    }

    /// The monomial x_i^e.
    pub fn unit_mono(i: usize, e: u32) -> Mono {
        Mono::var(i, e)
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value if the polynomial is constant.
    pub fn as_constant(&self) -> Option<BigRational> {
        match self.terms.len() {
            0 => Some(BigRational::zero()),
            1 => self.terms.get(&Mono::one()).cloned(),
            _ => None,
        }
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there is no term (the zero polynomial).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The terms, in increasing lexicographic order.
    pub fn terms(&self) -> impl Iterator<Item = (&Mono, &BigRational)> {
        self.terms.iter()
    }

    /// The leading (lexicographically largest) term.
    pub fn leading(&self) -> Option<(&Mono, &BigRational)> {
        self.terms.iter().next_back()
    }

    /// Bitmask of the variables that occur (variables ≥ 64 share bit 63).
    pub fn var_mask(&self) -> u64 {
        let mut mask = 0;
        for m in self.terms.keys() {
            for (i, _) in m.iter() {
                mask |= 1u64 << i.min(63);
            }
        }
        mask
    }

    fn add_term(&mut self, m: Mono, c: BigRational) {
        if c.is_zero() {
            return;
        }
        match self.terms.entry(m) {
            std::collections::btree_map::Entry::Vacant(v) => {
                v.insert(c);
            }
            std::collections::btree_map::Entry::Occupied(mut o) => {
                *o.get_mut() += c;
                if o.get().is_zero() {
                    o.remove();
                }
            }
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Result<Poly, TooBig> {
        charge(other.terms.len() as u64)?;
        crate::cas::count_work((self.terms.len() + other.terms.len()) as u64);
        let mut r = self.clone();
        for (m, c) in &other.terms {
            r.add_term(m.clone(), c.clone());
        }
        r.check()
    }

    /// `self += other · x^shift`, in place (no copy of `self`: summing n
    /// polynomials this way is linear in their total size, where folding
    /// [`Poly::add`] copies the growing sum every time).
    ///
    /// Charged and bounded exactly like `self.add(&other.mul_mono(shift))`:
    /// `other.len()` operations, then [`TooBig`] when the sum has more than
    /// [`MAX_TERMS`] terms or a coefficient it changed exceeds
    /// `MAX_COEFF_BITS` (the others were checked when they were made).
    /// After an error `self` is partly updated and must be discarded.
    pub fn add_shifted(&mut self, other: &Poly, shift: &Mono) -> Result<(), TooBig> {
        charge(other.terms.len() as u64)?;
        crate::cas::count_work(other.terms.len() as u64);
        for (m, c) in &other.terms {
            let key = m.mul(shift);
            match self.terms.entry(key) {
                std::collections::btree_map::Entry::Vacant(v) => {
                    if coeff_bits(c) > MAX_COEFF_BITS {
                        return Err(TooBig);
                    }
                    v.insert(c.clone());
                }
                std::collections::btree_map::Entry::Occupied(mut o) => {
                    *o.get_mut() += c;
                    if o.get().is_zero() {
                        o.remove();
                    } else if coeff_bits(o.get()) > MAX_COEFF_BITS {
                        return Err(TooBig);
                    }
                }
            }
        }
        if self.terms.len() > MAX_TERMS {
            return Err(TooBig);
        }
        Ok(())
    }

    /// `self - other`.
    pub fn sub(&self, other: &Poly) -> Result<Poly, TooBig> {
        self.add(&other.neg())
    }

    /// `-self`.
    pub fn neg(&self) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| (m.clone(), -c.clone()))
                .collect(),
        }
    }

    /// `c · self`.
    pub fn scale(&self, c: &BigRational) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, x)| (m.clone(), x * c)).collect(),
        }
    }

    /// `self · x^m`.
    pub fn mul_mono(&self, m: &Mono) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(k, c)| (k.mul(m), c.clone()))
                .collect(),
        }
    }

    /// `self · other`.
    pub fn mul(&self, other: &Poly) -> Result<Poly, TooBig> {
        let work = self.terms.len().saturating_mul(other.terms.len());
        if work > MAX_TERMS * 64 {
            return Err(TooBig);
        }
        // Big coefficients cost more (products and gcd reductions grow with size).
        let words = 1 + (self.coeff_bits() + other.coeff_bits()) / 64;
        charge((work as u64).saturating_mul(words * words))?;
        crate::cas::count_work(work as u64);
        let mut r = Poly::zero();
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                r.add_term(ma.mul(mb), ca * cb);
            }
        }
        r.check()
    }

    /// `self^n`.
    pub fn pow(&self, n: u32) -> Result<Poly, TooBig> {
        let mut result = Poly::one();
        let mut base = self.clone();
        let mut n = n;
        while n > 0 {
            if n & 1 == 1 {
                result = result.mul(&base)?;
            }
            n >>= 1;
            if n > 0 {
                base = base.mul(&base)?;
            }
        }
        Ok(result)
    }

    /// The largest coefficient size in bits (numerator + denominator).
    pub fn coeff_bits(&self) -> u64 {
        self.terms.values().map(coeff_bits).max().unwrap_or(0)
    }

    fn check(self) -> Result<Poly, TooBig> {
        if self.terms.len() > MAX_TERMS || self.coeff_bits() > MAX_COEFF_BITS {
            Err(TooBig)
        } else {
            Ok(self)
        }
    }

    /// The largest monomial dividing every term (componentwise minimum).
    pub fn monomial_content(&self) -> Mono {
        let mut it = self.terms.keys();
        let Some(first) = it.next() else {
            return Mono::one();
        };
        let mut m = first.clone();
        for k in it {
            if m.is_one() {
                break;
            }
            m = m.gcd(k);
        }
        m
    }

    /// `self / x^m`, assuming `x^m` divides every term.
    pub fn div_mono(&self, m: &Mono) -> Poly {
        if m.is_one() {
            return self.clone();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .filter_map(|(k, c)| Some((k.div(m)?, c.clone())))
                .collect(),
        }
    }

    /// The rational content c with sign, such that `self / c` has coprime
    /// integer coefficients and a positive leading coefficient.
    pub fn content(&self) -> BigRational {
        let mut num = BigInt::zero();
        let mut den = BigInt::one();
        for c in self.terms.values() {
            num = rat::gcd(&num, c.numer());
            den = rat::lcm(&den, c.denom());
        }
        if num.is_zero() {
            return BigRational::one();
        }
        // Coprime: a prime dividing every numerator divides no denominator.
        let c = BigRational::new_raw(num, den);
        match self.leading() {
            Some((_, lc)) if lc.is_negative() => -c,
            _ => c,
        }
    }

    /// Exact division `self / d`; `None` if `d` does not divide `self`
    /// (or `d` is 0). For a single divisor the lexicographic division
    /// algorithm leaves remainder 0 exactly when `d | self`.
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        let (dm, dc) = d.leading()?;
        let (dm, dc) = (dm.clone(), dc.clone());
        // A monomial divisor: divisible iff it divides every term.
        if d.len() == 1 {
            if self.terms.keys().any(|m| m.div(&dm).is_none()) {
                return None;
            }
            let inv = dc.recip();
            return Some(Poly {
                terms: self
                    .terms
                    .iter()
                    .filter_map(|(m, c)| Some((m.div(&dm)?, c * &inv)))
                    .collect(),
            });
        }
        let mut rem = self.clone();
        let mut q = Poly::zero();
        while let Some((m, c)) = rem.leading() {
            let qm = m.div(&dm)?;
            let qc = c / &dc;
            charge(d.len() as u64).ok()?;
            // rem -= qc·x^qm·d, in place.
            for (k, x) in &d.terms {
                rem.add_term(k.mul(&qm), -(x * &qc));
            }
            if rem.len() > MAX_TERMS * 4 {
                return None;
            }
            q.add_term(qm, qc);
        }
        Some(q)
    }

    /// Coefficients of `self` as a polynomial in x_var: entry k multiplies x_var^k.
    pub fn coeffs_in(&self, var: usize) -> Vec<Poly> {
        let mut out: Vec<Poly> = Vec::new();
        for (m, c) in &self.terms {
            let k = m.get(var) as usize;
            if out.len() <= k {
                out.resize(k + 1, Poly::zero());
            }
            let rest = if k == 0 { m.clone() } else { m.without(var) };
            out[k].add_term(rest, c.clone());
        }
        out
    }

    /// Apply a signed permutation of variables: x_i ↦ sign_i · x_{perm_i}.
    pub fn signed_permute(&self, perm: &dyn Fn(usize) -> (usize, bool)) -> Poly {
        let mut r = Poly::zero();
        for (m, c) in &self.terms {
            let mut pairs: Vec<(usize, u32)> = Vec::with_capacity(m.len());
            let mut negate = false;
            for (i, e) in m.iter() {
                let (j, neg) = perm(i);
                pairs.push((j, e));
                negate ^= neg && e % 2 == 1;
            }
            let nm = Mono::from_pairs(pairs);
            r.add_term(nm, if negate { -c.clone() } else { c.clone() });
        }
        r
    }

    /// Substitute x_var = 0.
    pub fn set_zero(&self, var: usize) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .filter(|(m, _)| m.get(var) == 0)
                .map(|(m, c)| (m.clone(), c.clone()))
                .collect(),
        }
    }
}

/// Divide `p` by the linear polynomial `(x_var - c)` (synthetic division in
/// x_var; `c` free of x_var). `Some(quotient)` iff the remainder
/// p|_{x_var = c} vanishes identically.
pub fn div_linear(p: &Poly, var: usize, c: &Poly) -> Result<Option<Poly>, TooBig> {
    let a = p.coeffs_in(var);
    if a.is_empty() {
        return Ok(Some(Poly::zero()));
    }
    // q_{n-1} = a_n; q_{k-1} = a_k + c q_k; remainder = a_0 + c q_0.
    let n = a.len() - 1;
    let mut q: Vec<Poly> = vec![Poly::zero(); n];
    let mut carry = Poly::zero();
    for k in (1..=n).rev() {
        let qk = a[k].add(&c.mul(&carry)?)?;
        q[k - 1] = qk.clone();
        carry = qk;
    }
    let rem = a[0].add(&c.mul(&carry)?)?;
    if !rem.is_zero() {
        return Ok(None);
    }
    let mut out = Poly::zero();
    for (k, qk) in q.into_iter().enumerate() {
        let t = qk.mul_mono(&Poly::unit_mono(var, k as u32));
        out = out.add(&t)?;
    }
    Ok(Some(out))
}
