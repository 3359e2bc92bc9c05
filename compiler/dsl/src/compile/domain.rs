//! Which domain conditions Ψ's own evaluation already enforces, so that
//! evaluators do not test them twice (a log barrier's `log(J)` is +∞ or NaN
//! for J ≤ 0, which every evaluator reports as Ψ = +∞).
//!
//! IEEE semantics, as every evaluator of the IR computes (tape, generated
//! Rust, C++):
//!
//! * NaN propagates through +, ·, exp, log and powers with a constant
//!   nonzero exponent (the only way back to a number, `powf(NaN, 0) = 1` or
//!   `powf(1, NaN) = 1`, needs a non-constant exponent, whose operands are
//!   therefore not followed);
//! * ±∞ stays non-finite (±∞ or NaN) through +, ·, log and powers with a
//!   positive constant exponent, but not through exp (e^−∞ = 0) or a
//!   negative power (1/∞ = 0).
//!
//! A node reached from Ψ along NaN-propagating edges makes Ψ NaN when it is
//! NaN; one reached along ∞-preserving edges makes Ψ non-finite when it is
//! infinite. So `x > 0` is enforced when Ψ still contains `log(x)` (NaN for
//! x < 0, −∞ at 0) on such paths, `x ≥ 0` when it contains `x^(p/q)` with q
//! even (NaN for x < 0), `x ≠ 0` when it contains `x^e` with e < 0 or
//! `log(x)` on an ∞-preserving path.

use num_traits::{Signed, Zero};

use crate::cas::{Graph, Id, Node};
use crate::ir::{DomainCond, DomainGuard};

/// The nodes reached from `root` along edges that keep the property of
/// `follow(parent, child index)`.
fn reached(g: &Graph, root: Id, follow: impl Fn(&Node, usize) -> bool) -> Vec<bool> {
    let mut seen = vec![false; g.len()];
    let mut stack = vec![root];
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut seen[id.index()], true) {
            continue;
        }
        let node = g.get(id);
        for (k, &c) in node.children().iter().enumerate() {
            if follow(node, k) {
                stack.push(c);
            }
        }
    }
    seen
}

/// The constant exponent of a power node, if any.
fn const_exp<'g>(g: &'g Graph, n: &Node) -> Option<&'g num_rational::BigRational> {
    match n {
        Node::Pow([_, e]) => g.as_num(*e),
        _ => None,
    }
}

/// Mark each guard of `guards` that Ψ = `psi` enforces by itself.
pub fn mark_enforced(g: &Graph, psi: Id, guards: &mut [DomainGuard]) {
    if guards.is_empty() {
        return;
    }
    let nan = reached(g, psi, |n, k| match n {
        Node::Add(_) | Node::Mul(_) | Node::Log(_) | Node::Exp(_) => true,
        Node::Pow(_) => k == 0 && const_exp(g, n).is_some(),
        _ => false,
    });
    let inf = reached(g, psi, |n, k| match n {
        Node::Add(_) | Node::Mul(_) | Node::Log(_) => true,
        Node::Pow(_) => k == 0 && const_exp(g, n).is_some_and(|r| r.is_positive()),
        _ => false,
    });
    // For every argument x: NaN below 0 / non-finite at 0 guaranteed.
    let mut below = vec![false; g.len()];
    let mut at_zero = vec![false; g.len()];
    for (i, n) in g.nodes().iter().enumerate() {
        let (x, nan_below, inf_at_zero) = match n {
            Node::Log(x) => (*x, true, true),
            Node::Pow([b, _]) => match const_exp(g, n) {
                Some(r) => (*b, (r.denom() % 2u8).is_zero(), r.is_negative()),
                None => continue,
            },
            _ => continue,
        };
        below[x.index()] |= nan[i] && nan_below;
        at_zero[x.index()] |= inf[i] && inf_at_zero;
    }
    for d in guards {
        let x = d.arg.index();
        d.enforced_by_psi = match d.cond {
            DomainCond::Positive => below[x] && at_zero[x],
            DomainCond::NonNegative => below[x],
            DomainCond::NonZero => at_zero[x],
        };
    }
}
