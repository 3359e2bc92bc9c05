//! Sparse monomials: x^m stored as its non-zero (variable, exponent) pairs.
//!
//! The compiler gives every distinct transcendental subterm (an `exp`, a
//! `log`, a symbolic power) its own polynomial variable, so an energy with n
//! such subterms has polynomials in n + 3 + #params variables. A dense
//! exponent vector would make every monomial operation O(n) and a sum of n
//! terms O(n²); the sparse form costs O(number of variables that occur).
//!
//! The order is the lexicographic order of the (zero-padded) exponent
//! vectors, variable 0 most significant — exactly the order of the trimmed
//! dense `Vec<u32>` this type replaced, so polynomials iterate their terms,
//! and pick their leading term, as before.

use std::cmp::Ordering;

/// A monomial Π x_v^e: pairs (v, e) with v strictly increasing and e > 0.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Mono(Vec<(u32, u32)>);

impl Mono {
    /// The monomial 1.
    pub fn one() -> Self {
        Mono(Vec::new())
    }

    /// x_var^e (1 when e = 0).
    pub fn var(var: usize, e: u32) -> Self {
        if e == 0 {
            Mono::one()
        } else {
            Mono(vec![(var_u32(var), e)])
        }
    }

    /// From a dense exponent vector (entry i is the exponent of x_i).
    pub fn from_dense(exps: &[u32]) -> Self {
        Mono(
            exps.iter()
                .enumerate()
                .filter(|(_, e)| **e > 0)
                .map(|(v, e)| (var_u32(v), *e))
                .collect(),
        )
    }

    /// From (variable, exponent) pairs in any order, repeated variables
    /// multiplied (exponents added), zero exponents dropped.
    pub fn from_pairs(mut pairs: Vec<(usize, u32)>) -> Self {
        pairs.sort_unstable_by_key(|p| p.0);
        let mut out: Vec<(u32, u32)> = Vec::with_capacity(pairs.len());
        for (v, e) in pairs {
            if e == 0 {
                continue;
            }
            match out.last_mut() {
                Some(last) if last.0 as usize == v => last.1 += e,
                _ => out.push((var_u32(v), e)),
            }
        }
        Mono(out)
    }

    /// Whether this is the monomial 1.
    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// The exponent of x_var.
    pub fn get(&self, var: usize) -> u32 {
        match self.0.binary_search_by_key(&var, |p| p.0 as usize) {
            Ok(i) => self.0[i].1,
            Err(_) => 0,
        }
    }

    /// The (variable, exponent) pairs with exponent > 0, variables increasing.
    pub fn iter(&self) -> impl Iterator<Item = (usize, u32)> + '_ {
        self.0.iter().map(|&(v, e)| (v as usize, e))
    }

    /// Number of variables that occur.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether no variable occurs (the monomial 1).
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The largest variable that occurs.
    pub fn last_var(&self) -> Option<usize> {
        self.0.last().map(|p| p.0 as usize)
    }

    /// `self · other`.
    pub fn mul(&self, other: &Mono) -> Mono {
        if other.is_one() {
            return self.clone();
        }
        if self.is_one() {
            return other.clone();
        }
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                Ordering::Equal => {
                    out.push((a[i].0, a[i].1 + b[j].1));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Mono(out)
    }

    /// `self / other` if `other` divides `self`.
    pub fn div(&self, other: &Mono) -> Option<Mono> {
        if other.is_one() {
            return Some(self.clone());
        }
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::with_capacity(a.len());
        let mut i = 0;
        for &(v, e) in b {
            while i < a.len() && a[i].0 < v {
                out.push(a[i]);
                i += 1;
            }
            let (av, ae) = *a.get(i)?;
            if av != v || ae < e {
                return None;
            }
            if ae > e {
                out.push((v, ae - e));
            }
            i += 1;
        }
        out.extend_from_slice(&a[i..]);
        Some(Mono(out))
    }

    /// The greatest common divisor (componentwise minimum of the exponents).
    pub fn gcd(&self, other: &Mono) -> Mono {
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::new();
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Less => i += 1,
                Ordering::Greater => j += 1,
                Ordering::Equal => {
                    out.push((a[i].0, a[i].1.min(b[j].1)));
                    i += 1;
                    j += 1;
                }
            }
        }
        Mono(out)
    }

    /// `self` with x_var set to 1 (its exponent dropped).
    pub fn without(&self, var: usize) -> Mono {
        Mono(
            self.0
                .iter()
                .filter(|p| p.0 as usize != var)
                .copied()
                .collect(),
        )
    }
}

fn var_u32(v: usize) -> u32 {
    u32::try_from(v).expect("more than 2^32 polynomial variables")
}

impl Ord for Mono {
    /// Lexicographic on the zero-padded exponent vectors (x_0 most
    /// significant): at the first variable where the exponents differ, the
    /// larger exponent wins; a variable present in only one monomial is a
    /// positive exponent against 0.
    fn cmp(&self, other: &Mono) -> Ordering {
        for (x, y) in self.0.iter().zip(&other.0) {
            let o = match x.0.cmp(&y.0) {
                // `self` has x.0 where `other` has 0 (and vice versa).
                Ordering::Less => Ordering::Greater,
                Ordering::Greater => Ordering::Less,
                Ordering::Equal => x.1.cmp(&y.1),
            };
            if o != Ordering::Equal {
                return o;
            }
        }
        self.0.len().cmp(&other.0.len())
    }
}

impl PartialOrd for Mono {
    fn partial_cmp(&self, other: &Mono) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The trimmed dense vector the sparse form replaced.
    fn dense(m: &Mono) -> Vec<u32> {
        let n = m.last_var().map_or(0, |v| v + 1);
        (0..n).map(|v| m.get(v)).collect()
    }

    /// Deterministic pseudo-random exponent vectors with many zeros.
    fn samples() -> Vec<Vec<u32>> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        (0..300)
            .map(|_| {
                let len = (next() % 7) as usize;
                (0..len)
                    .map(|_| {
                        let r = next() % 10;
                        if r < 5 { 0 } else { (r - 4) as u32 % 3 }
                    })
                    .collect()
            })
            .collect()
    }

    fn trimmed(mut v: Vec<u32>) -> Vec<u32> {
        while v.last() == Some(&0) {
            v.pop();
        }
        v
    }

    #[test]
    fn order_and_arithmetic_are_those_of_trimmed_dense_vectors() {
        let s = samples();
        for a in &s {
            let ma = Mono::from_dense(a);
            assert_eq!(dense(&ma), trimmed(a.clone()));
            for b in &s {
                let mb = Mono::from_dense(b);
                let (da, db) = (trimmed(a.clone()), trimmed(b.clone()));
                assert_eq!(ma.cmp(&mb), da.cmp(&db), "{a:?} vs {b:?}");
                assert_eq!(ma == mb, da == db);
                let n = da.len().max(db.len());
                let at = |v: &Vec<u32>, i: usize| v.get(i).copied().unwrap_or(0);
                let prod: Vec<u32> = (0..n).map(|i| at(&da, i) + at(&db, i)).collect();
                assert_eq!(dense(&ma.mul(&mb)), trimmed(prod));
                let gcd: Vec<u32> = (0..n).map(|i| at(&da, i).min(at(&db, i))).collect();
                assert_eq!(dense(&ma.gcd(&mb)), trimmed(gcd));
                let divides = (0..n).all(|i| at(&db, i) <= at(&da, i));
                let quot = ma.div(&mb).map(|q| dense(&q));
                let expect =
                    divides.then(|| trimmed((0..n).map(|i| at(&da, i) - at(&db, i)).collect()));
                assert_eq!(quot, expect, "{a:?} / {b:?}");
            }
        }
    }

    #[test]
    fn pairs_merge_and_drop_zeros() {
        let m = Mono::from_pairs(vec![(5, 1), (2, 0), (0, 2), (5, 2)]);
        assert_eq!(dense(&m), vec![2, 0, 0, 0, 0, 3]);
        assert_eq!(m.without(5), Mono::var(0, 2));
        assert!(Mono::var(7, 0).is_one());
        assert_eq!(m.last_var(), Some(5));
    }
}
