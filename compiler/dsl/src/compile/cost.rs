//! A simple operation-count cost model, used to pick the most compact of
//! several equivalent forms of an expression.

use std::collections::HashSet;

use crate::cas::rat;
use crate::cas::{Graph, Id, Node};

/// Approximate flops to evaluate `root` (shared subexpressions counted once):
/// +, −, × cost 1; an integer power k costs its square-and-multiply chain
/// (plus a division when negative); sqrt 3; log, exp and general powers 20.
pub fn cost(g: &Graph, root: Id) -> u64 {
    cost_many(g, &[root])
}

/// Joint cost of several roots.
pub fn cost_many(g: &Graph, roots: &[Id]) -> u64 {
    let mut total = 0u64;
    let reach: HashSet<Id> = g.reachable(roots).into_iter().collect();
    for id in &reach {
        total += match g.get(*id) {
            Node::Num(_) | Node::Sym(_) => 0,
            Node::Add(c) | Node::Mul(c) => c.len() as u64 - 1,
            Node::Pow([_, e]) => match g.as_num(*e) {
                Some(r) if r.is_integer() => {
                    let k = rat::as_i64(r).map_or(64, |k| k.unsigned_abs());
                    let chain = (64 - k.leading_zeros() as u64 - 1) + k.count_ones() as u64 - 1;
                    chain + u64::from(r < &num_rational::BigRational::from_integer(0.into()))
                }
                Some(r) if *r == num_rational::BigRational::new(1.into(), 2.into()) => 3,
                _ => 20,
            },
            Node::Log(_) | Node::Exp(_) => 20,
        };
    }
    total
}
