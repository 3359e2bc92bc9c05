//! The domain of Ψ as written (issue 12, item 2).
//!
//! The CAS simplifies while it builds (`exp(log(x)) = x`, `sqrt(x)^2 = x`,
//! `x/x = 1`, `log(x) − log(x) = 0`, see `cas::build`), which is valid only
//! where the written formula is defined. So lowering records, for every
//! written operation that restricts its argument, one condition *before*
//! the simplified result replaces it:
//!
//! | written | condition |
//! |---|---|
//! | `log(x)` | x > 0 |
//! | `sqrt(x)`, `x^(p/q)` with q even, p > 0 | x ≥ 0 |
//! | `x^(p/q)` with q even, p < 0 | x > 0 |
//! | `a/x`, `x^n` with n < 0, `x^(p/q)` with q odd, p < 0 | x ≠ 0 |
//! | `x^y` with a non-constant exponent y (= exp(y·log x)) | x > 0 |
//! | `exp(x)`, `x^n` with n ≥ 0 (integer), `x^(p/q)` with q odd, p > 0 | none |
//!
//! `x ≠ 0` is split over products and positive powers
//! (x·y ≠ 0 ⇔ x ≠ 0 ∧ y ≠ 0, y^k ≠ 0 ⇔ y ≠ 0). A condition is dropped only
//! when [`sign`] proves it for every real input (a positive constant,
//! `exp(..) > 0`, `I2 ≥ 0`, `I5 ≥ 0`, sums and products of such, even powers ≥ 0);
//! conditions on the same argument are merged (x ≥ 0 ∧ x ≠ 0 is x > 0).

use num_traits::{Signed, Zero};

use crate::cas::{Graph, Id, Node, Sym};
use crate::ir::{DomainCond, DomainGuard};

/// A proved sign of an expression wherever it is defined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sign {
    /// > 0.
    Positive,
    /// ≥ 0.
    NonNegative,
    /// Not proved.
    Unknown,
}

/// Nodes [`sign`] may visit per question (bounds the cost on huge sums).
const SIGN_BUDGET: usize = 256;

/// The sign of `x` proved structurally, or [`Sign::Unknown`].
pub fn sign(g: &Graph, x: Id) -> Sign {
    let mut budget = SIGN_BUDGET;
    sign_in(g, x, &mut budget)
}

fn sign_in(g: &Graph, x: Id, budget: &mut usize) -> Sign {
    if *budget == 0 {
        return Sign::Unknown;
    }
    *budget -= 1;
    match g.get(x) {
        Node::Num(r) if r.is_positive() => Sign::Positive,
        Node::Num(r) if r.is_zero() => Sign::NonNegative,
        // I2 = ‖F‖², I5 = ‖F a‖².
        Node::Sym(Sym::I2 | Sym::I5) => Sign::NonNegative,
        Node::Exp(_) => Sign::Positive,
        Node::Add(c) => combine(g, c, budget, |a| a.contains(&Sign::Positive)),
        Node::Mul(c) => combine(g, c, budget, |a| a.iter().all(|s| *s == Sign::Positive)),
        Node::Pow([b, e]) => pow_sign(g, *b, *e, budget),
        _ => Sign::Unknown,
    }
}

/// All children ≥ 0: the node is ≥ 0, and > 0 when `strict` says so.
fn combine(
    g: &Graph,
    children: &[Id],
    budget: &mut usize,
    strict: impl Fn(&[Sign]) -> bool,
) -> Sign {
    let mut signs = Vec::with_capacity(children.len());
    for &c in children {
        let s = sign_in(g, c, budget);
        if s == Sign::Unknown {
            return Sign::Unknown;
        }
        signs.push(s);
    }
    if strict(&signs) {
        Sign::Positive
    } else {
        Sign::NonNegative
    }
}

/// b^e: positive for a positive base; ≥ 0 for an exponent p/q with p even
/// (q odd: the real power of a negative base) or q even (a root, defined
/// only for b ≥ 0), or for a base ≥ 0.
fn pow_sign(g: &Graph, b: Id, e: Id, budget: &mut usize) -> Sign {
    let base = sign_in(g, b, budget);
    if base == Sign::Positive {
        return Sign::Positive;
    }
    let Some(r) = g.as_num(e) else {
        return Sign::Unknown;
    };
    let even = |n: &num_bigint::BigInt| (n % 2u8).is_zero();
    if even(r.numer()) || even(r.denom()) || base == Sign::NonNegative {
        Sign::NonNegative
    } else {
        Sign::Unknown
    }
}

/// Whether the sign proves `cond` for every input where `x` is defined.
fn proved(g: &Graph, x: Id, cond: DomainCond) -> bool {
    matches!(
        (sign(g, x), cond),
        (Sign::Positive, _) | (Sign::NonNegative, DomainCond::NonNegative)
    )
}

/// Add `cond` on `x` to `out` unless proved; merged with an existing
/// condition on the same argument.
pub fn push(g: &Graph, out: &mut Vec<DomainGuard>, x: Id, cond: DomainCond) {
    if proved(g, x, cond) {
        return;
    }
    if let Some(old) = out.iter_mut().find(|d| d.arg == x) {
        old.cond = merge(old.cond, cond);
        return;
    }
    out.push(DomainGuard {
        arg: x,
        cond,
        enforced_by_psi: false,
    });
}

/// Both conditions at once.
fn merge(a: DomainCond, b: DomainCond) -> DomainCond {
    use DomainCond::*;
    match (a, b) {
        (x, y) if x == y => x,
        _ => Positive,
    }
}

/// Append every condition of `more` (a `let` used here) to `out`.
pub fn extend(g: &Graph, out: &mut Vec<DomainGuard>, more: &[DomainGuard]) {
    for d in more {
        push(g, out, d.arg, d.cond);
    }
}

/// `log(x)` was written: x > 0.
pub fn log(g: &Graph, out: &mut Vec<DomainGuard>, x: Id) {
    push(g, out, x, DomainCond::Positive);
}

/// A division by `x` was written: x ≠ 0, split over products and positive
/// powers.
pub fn nonzero(g: &Graph, out: &mut Vec<DomainGuard>, x: Id) {
    match g.get(x) {
        Node::Num(_) | Node::Exp(_) => {}
        Node::Mul(c) => {
            for &f in c {
                nonzero(g, out, f);
            }
        }
        Node::Pow([b, e]) if g.as_num(*e).is_some_and(|r| r.is_positive()) => {
            nonzero(g, out, *b);
        }
        _ => push(g, out, x, DomainCond::NonZero),
    }
}

/// `b^e` was written (also `sqrt(b)` = b^(1/2)); see the module table.
pub fn pow(g: &Graph, out: &mut Vec<DomainGuard>, b: Id, e: Id) {
    let Some(r) = g.as_num(e) else {
        push(g, out, b, DomainCond::Positive);
        return;
    };
    let negative = r.is_negative();
    let even_root = (r.denom() % 2u8).is_zero();
    match (even_root, negative) {
        (true, false) => push(g, out, b, DomainCond::NonNegative),
        (true, true) => push(g, out, b, DomainCond::Positive),
        (false, true) => nonzero(g, out, b),
        (false, false) => {}
    }
}
