//! Pole factoring of the fibre partials (issue 16).
//!
//! Differentiating ψ(I4, I5) leaves sums of terms with different negative
//! powers of one fibre invariant b ∈ {I5, I4}. Anisotropic ARAP
//! ψ = μ/2 (√I5 − s)², s = sign(I4), t = √I5 − s gives
//!
//! ```text
//! ψ55 = μ/(4 I5) − μ t/(4 I5^{3/2}),                                (P1)
//! ```
//!
//! which at I5 = 0 evaluates to ∞ − ∞ = NaN although its limit is the pole
//! μ s / (4 I5^{3/2}) → ±∞. The rewrite collects the terms with a negative
//! power of b, Σ_k c_k b^{r_k} (r_k < 0, r_min = min r_k), into
//!
//! ```text
//! Σ_k c_k b^{r_k} = b^{r_min} · Σ_k c_k b^{r_k − r_min},               (P2)
//! ```
//!
//! so (P1) becomes I5^{-3/2} (μ √I5/4 − μ t/4) = ±∞ at I5 = 0 with the sign
//! of the limit. (P2) is exact and keeps the domain: b^{r_min} already
//! requires b ≠ 0 (b > 0 for an even-denominator r_min), and every
//! r_k − r_min ≥ 0 has a denominator dividing those of r_k and r_min, so
//! b^{r_k − r_min} is defined wherever b^{r_k} and b^{r_min} are. Terms
//! with a power r ≥ 0 of b stay outside (their values are unchanged and no
//! positive power grows). Only exact rational exponents are collected.
//! The CAS keeps the product b^{r_min} · (sum) as it is: it distributes a
//! sum only over a bare rational coefficient (`cas::build`).

use std::collections::HashMap;

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::cas::{Graph, Id, Node, Sym};

/// `id` with (P2) applied to every sum in it, for b = I5 then b = I4.
pub fn factor(g: &mut Graph, id: Id, memo: &mut HashMap<Id, Id>) -> Id {
    if let Some(&done) = memo.get(&id) {
        return done;
    }
    let node = g.get(id).clone();
    let kids: Vec<Id> = node.children().to_vec();
    let new: Vec<Id> = kids.iter().map(|&c| factor(g, c, memo)).collect();
    let rebuilt = if new == kids {
        id
    } else {
        match node {
            Node::Add(_) => g.sum(&new),
            Node::Mul(_) => g.product(&new),
            Node::Pow(_) => g.pow(new[0], new[1]),
            Node::Log(_) => g.log(new[0]),
            Node::Exp(_) => g.exp(new[0]),
            Node::Num(_) | Node::Sym(_) => id,
        }
    };
    let mut out = rebuilt;
    for b in [Sym::I5, Sym::I4] {
        out = factor_sum(g, out, b);
    }
    memo.insert(id, out);
    out
}

/// (P2) on the sum `id` for the base `b`; `id` itself when it is not a
/// sum or has fewer than two distinct negative powers of `b`.
fn factor_sum(g: &mut Graph, id: Id, b: Sym) -> Id {
    let Node::Add(terms) = g.get(id).clone() else {
        return id;
    };
    let base = g.sym(b);
    let powers: Vec<Option<BigRational>> = terms.iter().map(|&t| power_of(g, t, base)).collect();
    let negative: Vec<&BigRational> = powers
        .iter()
        .flatten()
        .filter(|r| r.is_negative())
        .collect();
    let Some(r_min) = negative.iter().min().map(|r| (*r).clone()) else {
        return id;
    };
    if negative.iter().all(|r| **r == r_min) {
        return id;
    }
    let mut inner = Vec::new();
    let mut outer = Vec::new();
    for (&t, r) in terms.iter().zip(&powers) {
        match r {
            Some(r) if r.is_negative() => {
                let shift = g.num(-r_min.clone());
                let bs = g.pow(base, shift);
                inner.push(g.product(&[t, bs]));
            }
            _ => outer.push(t),
        }
    }
    let inner = g.sum(&inner);
    let min = g.num(r_min);
    let pole = g.pow(base, min);
    outer.push(g.product(&[pole, inner]));
    g.sum(&outer)
}

/// The exact rational power of `base` that the term `t` carries as a
/// direct factor (0 when it has none); `None` when that power is not a
/// rational constant.
fn power_of(g: &Graph, t: Id, base: Id) -> Option<BigRational> {
    let factors: &[Id] = match g.get(t) {
        Node::Mul(c) => c,
        _ => std::slice::from_ref(&t),
    };
    for &f in factors {
        if f == base {
            return Some(BigRational::from_integer(1.into()));
        }
        if let Node::Pow([bb, e]) = g.get(f)
            && *bb == base
        {
            return g.as_num(*e).cloned();
        }
    }
    Some(BigRational::zero())
}
