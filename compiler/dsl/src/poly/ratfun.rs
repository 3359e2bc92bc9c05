//! Rational functions N / Π fₖ^eₖ with a factored denominator.
//!
//! Keeping the denominator as a product of normalised factors (single
//! variables, or primitive non-monomial polynomials with positive leading
//! coefficient) makes sums cheap (the common denominator is the factorwise
//! maximum, never a blind product) and keeps the result readable: SD's
//! denominators stay powers of σ's instead of expanded products.

use std::collections::{BTreeMap, HashMap};

use num_rational::BigRational;
use num_traits::{One, Zero};

use super::polynomial::{Mono, Poly, TooBig};

/// A rational function `num / Π den[k].0 ^ den[k].1`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RatFun {
    /// The numerator.
    pub num: Poly,
    /// Distinct normalised denominator factors with positive exponents.
    pub den: Vec<(Poly, u32)>,
}

/// Split `p` (non-zero) into `c · x^m · rest` with `rest` primitive with
/// positive leading coefficient.
fn normalise(p: &Poly) -> (BigRational, Mono, Poly) {
    let m = p.monomial_content();
    let rest = p.div_mono(&m);
    let c = rest.content();
    let rest = rest.scale(&c.recip());
    (c, m, rest)
}

impl RatFun {
    /// A polynomial as a rational function.
    pub fn poly(p: Poly) -> Self {
        RatFun {
            num: p,
            den: Vec::new(),
        }
    }

    /// A constant.
    pub fn constant(c: BigRational) -> Self {
        RatFun::poly(Poly::constant(c))
    }

    /// Whether the function is identically zero.
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// Bitmask of variables occurring anywhere.
    pub fn var_mask(&self) -> u64 {
        self.den
            .iter()
            .fold(self.num.var_mask(), |m, (f, _)| m | f.var_mask())
    }

    /// Build from a numerator and arbitrary (non-zero) denominator factors,
    /// normalising the factors and cancelling what divides exactly.
    pub fn from_parts(num: Poly, den: Vec<(Poly, u32)>) -> Result<Self, TooBig> {
        let mut r = RatFun {
            num,
            den: Vec::new(),
        };
        for (f, e) in den {
            if e == 0 {
                continue;
            }
            let (c, m, rest) = normalise(&f);
            r.num = r.num.scale(&num_traits::pow(c.recip(), e as usize));
            for (i, me) in m.iter() {
                r.push_den(Poly::var(i), me * e);
            }
            if rest.as_constant().is_none() {
                r.push_den(rest, e);
            }
        }
        r.cancel()?;
        Ok(r)
    }

    fn push_den(&mut self, f: Poly, e: u32) {
        match self.den.iter_mut().find(|(g, _)| *g == f) {
            Some((_, ge)) => *ge += e,
            None => self.den.push((f, e)),
        }
    }

    /// Cancel denominator factors that divide the numerator exactly.
    fn cancel(&mut self) -> Result<(), TooBig> {
        if self.num.is_zero() {
            self.den.clear();
            return Ok(());
        }
        let content = self.num.monomial_content();
        for k in 0..self.den.len() {
            let (f, e) = &mut self.den[k];
            if f.len() == 1 {
                // A single variable x: cancel min(e, power of x in the numerator's content).
                let var = f
                    .leading()
                    .and_then(|(m, _)| m.iter().next().map(|(v, _)| v));
                if let Some(v) = var {
                    let c = content.get(v).min(*e);
                    if c > 0 {
                        *e -= c;
                        self.num = self.num.div_mono(&Poly::unit_mono(v, c));
                    }
                }
                continue;
            }
            while *e > 0 {
                match self.num.div_exact(f) {
                    Some(q) => {
                        self.num = q;
                        *e -= 1;
                    }
                    None => break,
                }
            }
        }
        self.den.retain(|(_, e)| *e > 0);
        self.den.sort_by(|a, b| {
            a.0.leading()
                .map(|t| t.0)
                .cmp(&b.0.leading().map(|t| t.0))
                .then(a.1.cmp(&b.1))
        });
        Ok(())
    }

    /// Π over `den` of f^(target - own), for the factors of a common denominator.
    fn lift(&self, common: &[(Poly, u32)]) -> Result<Poly, TooBig> {
        let mut p = self.num.clone();
        for (f, e) in common {
            let own = self
                .den
                .iter()
                .find(|(g, _)| g == f)
                .map_or(0, |(_, ge)| *ge);
            if *e > own {
                p = p.mul(&f.pow(e - own)?)?;
            }
        }
        Ok(p)
    }

    /// `self + other`.
    pub fn add(&self, other: &RatFun) -> Result<RatFun, TooBig> {
        let mut common = self.den.clone();
        for (f, e) in &other.den {
            match common.iter_mut().find(|(g, _)| g == f) {
                Some((_, ce)) => *ce = (*ce).max(*e),
                None => common.push((f.clone(), *e)),
            }
        }
        let num = self.lift(&common)?.add(&other.lift(&common)?)?;
        let mut r = RatFun { num, den: common };
        r.cancel()?;
        Ok(r)
    }

    /// Σ `terms`: the same function, in the same form, as folding
    /// [`RatFun::add`] from 0 left to right, but in linear time.
    ///
    /// The terms are grouped by the non-monomial factors of their
    /// denominators (in order of first appearance; usually there is one
    /// group, e.g. all terms over σ powers, or all over (σ0 + σ1)). Within a
    /// group every numerator is lifted to the group's common denominator
    /// D = Π x^(max exponent) · (the shared factors) by a monomial shift and
    /// accumulated in place: linear in the total size, where the fold copies
    /// the growing sum at every step (quadratic in the number of terms). The
    /// groups' sums are then folded. The results agree: once cancelled, a
    /// factor f keeps the least exponent a with (sum)·f^a a polynomial
    /// whatever common denominator the sum was formed over, so the form
    /// N / Π f^e depends only on the function (for pairwise coprime factors,
    /// which normalised factors of distinct singular sets are). The budget
    /// charges and size checks are made on the in-place sums.
    pub fn sum(terms: &[&RatFun]) -> Result<RatFun, TooBig> {
        type Key = Vec<(Poly, u32)>;
        let mut groups: Vec<(Key, Vec<&RatFun>)> = Vec::new();
        let mut index: HashMap<Key, usize> = HashMap::new();
        for t in terms {
            let key: Key = t
                .den
                .iter()
                .filter(|(f, _)| f.len() != 1)
                .cloned()
                .collect();
            let i = *index.entry(key.clone()).or_insert_with(|| {
                groups.push((key, Vec::new()));
                groups.len() - 1
            });
            groups[i].1.push(t);
        }
        let mut acc: Option<RatFun> = None;
        for (key, members) in groups {
            let s = RatFun::sum_group(key, &members)?;
            acc = Some(match acc {
                None => s,
                Some(a) => a.add(&s)?,
            });
        }
        Ok(acc.unwrap_or_else(RatFun::zero))
    }

    /// Σ `terms`, all of whose denominators are `shared` times single
    /// variables' powers: numerators shifted to the common denominator and
    /// added in place, then cancelled once.
    fn sum_group(shared: Vec<(Poly, u32)>, terms: &[&RatFun]) -> Result<RatFun, TooBig> {
        // The common monomial part: per variable, the largest exponent.
        let var_of = |f: &Poly| f.leading().and_then(|(m, _)| m.last_var()).unwrap_or(0);
        let monomial = |t: &RatFun| -> Vec<(usize, u32)> {
            t.den
                .iter()
                .filter(|(f, _)| f.len() == 1)
                .map(|(f, e)| (var_of(f), *e))
                .collect()
        };
        let mut common: BTreeMap<usize, u32> = BTreeMap::new();
        for t in terms {
            for (v, e) in monomial(t) {
                let c = common.entry(v).or_insert(0);
                *c = (*c).max(e);
            }
        }
        let d = Mono::from_pairs(common.iter().map(|(v, e)| (*v, *e)).collect());
        let mut num = Poly::zero();
        for t in terms {
            // num += t.num · D / t.den.
            let shift = d.div(&Mono::from_pairs(monomial(t))).ok_or(TooBig)?;
            num.add_shifted(&t.num, &shift)?;
        }
        let mut den: Vec<(Poly, u32)> = common
            .into_iter()
            .filter(|(_, e)| *e > 0)
            .map(|(v, e)| (Poly::var(v), e))
            .collect();
        den.extend(shared);
        let mut r = RatFun { num, den };
        r.cancel()?;
        Ok(r)
    }

    /// `self - other`.
    pub fn sub(&self, other: &RatFun) -> Result<RatFun, TooBig> {
        self.add(&other.neg())
    }

    /// `-self`.
    pub fn neg(&self) -> RatFun {
        RatFun {
            num: self.num.neg(),
            den: self.den.clone(),
        }
    }

    /// `self · other`.
    pub fn mul(&self, other: &RatFun) -> Result<RatFun, TooBig> {
        let mut r = RatFun {
            num: self.num.mul(&other.num)?,
            den: self.den.clone(),
        };
        for (f, e) in &other.den {
            r.push_den(f.clone(), *e);
        }
        r.cancel()?;
        Ok(r)
    }

    /// `1 / self`; `None` when `self` is identically 0.
    pub fn inv(&self) -> Result<Option<RatFun>, TooBig> {
        if self.num.is_zero() {
            return Ok(None);
        }
        let mut num = Poly::one();
        for (f, e) in &self.den {
            num = num.mul(&f.pow(*e)?)?;
        }
        RatFun::from_parts(num, vec![(self.num.clone(), 1)]).map(Some)
    }

    /// `self^n` for an integer n; `None` for a negative power of 0.
    pub fn powi(&self, n: i64) -> Result<Option<RatFun>, TooBig> {
        let base = if n < 0 {
            match self.inv()? {
                Some(b) => b,
                None => return Ok(None),
            }
        } else {
            self.clone()
        };
        let k = u32::try_from(n.unsigned_abs()).map_err(|_| TooBig)?;
        let num = base.num.pow(k)?;
        let den = base.den.iter().map(|(f, e)| (f.clone(), e * k)).collect();
        Ok(Some(RatFun { num, den }))
    }

    /// Apply a signed permutation of the variables (x_i ↦ ±x_j).
    pub fn signed_permute(&self, perm: &dyn Fn(usize) -> (usize, bool)) -> Result<RatFun, TooBig> {
        let den = self
            .den
            .iter()
            .map(|(f, e)| (f.signed_permute(perm), *e))
            .collect();
        RatFun::from_parts(self.num.signed_permute(perm), den)
    }

    /// Substitute x_var = 0; `None` when a denominator factor vanishes there.
    pub fn set_zero(&self, var: usize) -> Result<Option<RatFun>, TooBig> {
        let mut den = Vec::new();
        for (f, e) in &self.den {
            let g = f.set_zero(var);
            if g.is_zero() {
                return Ok(None);
            }
            den.push((g, *e));
        }
        RatFun::from_parts(self.num.set_zero(var), den).map(Some)
    }

    /// The exact quotient `self / (x_i + s·x_j)` (s = ±1) when the numerator
    /// vanishes on the hyperplane x_i = −s·x_j; `None` otherwise.
    pub fn div_linear(&self, i: usize, j: usize, s: i64) -> Result<Option<RatFun>, TooBig> {
        // x_i + s x_j = x_i - c with c = -s x_j.
        let c = Poly::var(j).scale(&BigRational::from_integer((-s).into()));
        match super::polynomial::div_linear(&self.num, i, &c)? {
            Some(q) => {
                let mut r = RatFun {
                    num: q,
                    den: self.den.clone(),
                };
                r.cancel()?;
                Ok(Some(r))
            }
            None => Ok(None),
        }
    }

    /// The constant value, if the function is constant.
    pub fn as_constant(&self) -> Option<BigRational> {
        if self.den.is_empty() {
            self.num.as_constant()
        } else {
            None
        }
    }

    /// 1.
    pub fn one() -> Self {
        RatFun::constant(BigRational::one())
    }

    /// 0.
    pub fn zero() -> Self {
        RatFun::constant(BigRational::zero())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int(n: i64) -> BigRational {
        BigRational::from_integer(n.into())
    }

    /// c · x0^a x1^b + d · x2 (+ 1) over the given denominator factors.
    fn term(c: i64, a: u32, b: u32, d: i64, den: Vec<(Poly, u32)>) -> RatFun {
        let num = Poly::monomial(int(c), &Mono::from_dense(&[a, b]))
            .add(&Poly::monomial(int(d), &Mono::var(2, 1)))
            .and_then(|p| p.add(&Poly::one()))
            .unwrap_or_default();
        RatFun::from_parts(num, den).unwrap_or_else(|_| RatFun::zero())
    }

    fn fold(terms: &[&RatFun]) -> RatFun {
        let mut acc = RatFun::zero();
        for t in terms {
            acc = acc.add(t).unwrap_or_else(|_| RatFun::zero());
        }
        acc
    }

    #[test]
    fn sum_is_the_fold_of_add() {
        let (x0, x1) = (Poly::var(0), Poly::var(1));
        let x0_plus_x1 = x0.add(&x1).unwrap_or_default();
        let mut terms: Vec<RatFun> = Vec::new();
        for k in 0..40i64 {
            let a = (k % 4) as u32;
            let b = (k % 3) as u32;
            let den = match k % 5 {
                0 => vec![],
                1 => vec![(x0.clone(), 1 + (k % 3) as u32)],
                2 => vec![(x1.clone(), 2), (x0.clone(), 1)],
                3 => vec![(Poly::var(2), 1)],
                _ => vec![(x0.scale(&int(3)), 2)],
            };
            terms.push(term(k - 20, a, b, 7 - k, den));
        }
        // Terms that cancel exactly, and one equal to minus the rest.
        terms.push(term(1, 1, 0, 0, vec![(x0.clone(), 3)]).neg());
        let refs: Vec<&RatFun> = terms.iter().collect();
        for n in [0, 1, 2, 5, 17, refs.len()] {
            assert_eq!(RatFun::sum(&refs[..n]), Ok(fold(&refs[..n])), "{n}");
        }
        let total = fold(&refs);
        let mut with_neg = refs.clone();
        let neg = total.neg();
        with_neg.push(&neg);
        assert!(RatFun::sum(&with_neg).is_ok_and(|r| r.is_zero() && r.den.is_empty()));
        // Non-monomial denominators: grouped by their shared factors, summed
        // in place, the groups folded — the fold's result still.
        let x0_x2_1 = x0.add(&Poly::var(2)).and_then(|p| p.add(&Poly::one()));
        let x0_x2_1 = x0_x2_1.unwrap_or_default();
        let mut poly_dens: Vec<RatFun> = Vec::new();
        for k in 0..30i64 {
            let den = match k % 4 {
                0 => vec![(x0_plus_x1.clone(), 1)],
                1 => vec![(x0_plus_x1.clone(), 1), (x1.clone(), 2)],
                2 => vec![(x0_x2_1.clone(), 1 + (k % 3) as u32)],
                _ => vec![(x0_plus_x1.clone(), 2), (x0_x2_1.clone(), 1)],
            };
            poly_dens.push(term(k - 11, (k % 3) as u32, (k % 2) as u32, 3 - k, den));
        }
        // A term that cancels a factor of the group's sum.
        let cancel = term(1, 1, 0, 0, vec![(x0_plus_x1.clone(), 1)]).neg();
        poly_dens.push(cancel);
        let mut mixed = refs.clone();
        for (k, t) in poly_dens.iter().enumerate() {
            mixed.insert((7 * k) % mixed.len(), t);
        }
        assert_eq!(RatFun::sum(&mixed), Ok(fold(&mixed)));
        let only: Vec<&RatFun> = poly_dens.iter().collect();
        assert_eq!(RatFun::sum(&only), Ok(fold(&only)));
        let same: Vec<&RatFun> = poly_dens.iter().step_by(4).collect();
        assert_eq!(RatFun::sum(&same), Ok(fold(&same)));
    }
}
