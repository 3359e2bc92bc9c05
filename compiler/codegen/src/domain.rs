//! The domain conditions of Ψ as written ([`DimIr::active_guards`]) in
//! generated code: their arguments are roots of Ψ's region (computed with Ψ,
//! shared subexpressions once), and Ψ is +∞ wherever one fails (issue 12,
//! item 2: `exp(log(I3))` is I3 only where I3 > 0). Energies without
//! active conditions get no extra code at all.

use ecc_dsl::{DimIr, DomainCond};

use crate::plan::{Plan, Region, Root};
use crate::render::Ex;

/// One root per active condition, in Ψ's region.
pub(crate) fn roots(d: &DimIr) -> Vec<Root> {
    d.active_guards()
        .map(|g| Root {
            id: g.arg,
            region: Region::Psi,
            name: "domain_arg".into(),
            bind: false,
        })
        .collect()
}

/// Each active condition as (argument, relation against 0): the argument
/// must be `> 0`, `>= 0`, or, for ≠ 0, its `abs()` must be `> 0` (so that a
/// NaN argument fails every test).
pub(crate) fn tests(d: &DimIr, plan: &Plan) -> Vec<(Ex, &'static str)> {
    d.active_guards()
        .map(|g| {
            let v = plan.value_ex(g.arg);
            match g.cond {
                DomainCond::Positive => (v, ">"),
                DomainCond::NonNegative => (v, ">="),
                DomainCond::NonZero => (Ex::Method(Box::new(v), "abs", vec![]), ">"),
            }
        })
        .collect()
}
