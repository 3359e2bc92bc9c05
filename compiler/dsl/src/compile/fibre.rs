//! The fibre part of an energy: splitting Ψ = Ψ_iso(I1, I2, I3 | σ) + ψ(I4, I5)
//! and ψ's exact partials.
//!
//! **Split.** The lowered Ψ is a sum of terms (one term if it is not a
//! sum). Each term reads isotropic leaves (I1, I2, I3, σ), fibre leaves
//! (I4, I5, sign(I4)), or neither (constants and parameters: they stay with
//! Ψ_iso). A product c·(t1 + t2 + …) whose sum mixes both kinds is
//! distributed first (`k*(I2 - d + I5 - 1)` splits). A term that still reads
//! both kinds (`I3*I5`) is a located error: the runtime projects Ψ_iso
//! (stretch-space eigensystem) and ψ (fibre eigensystem) separately, and a
//! coupled energy would need the full d² × d² numeric projection (not
//! supported this round). The domain conditions split the same way.
//!
//! **Partials.** ψ4 = ∂ψ/∂I4, ψ5, ψ44, ψ45, ψ55 by the CAS's exact
//! differentiation; sign(I4) is a leaf with derivative 0 (piecewise
//! constant). ψ reads I4 when I4 or sign(I4) is a leaf of ψ or of an active
//! domain condition; the closed-form eigensystem of I5 applies when
//! ψ4 ≡ ψ44 ≡ ψ45 ≡ 0 (Kim, de Goes & Iben 2019 §4.1 eq. 7 through the chain
//! rule; `ecc_runtime::fibre::point`, eqs. P3–P5), e.g. anisotropic ARAP
//! μ/2 (√I5 − sign(I4))². The partials' negative powers of I5 and I4 are
//! collected (`poles`, eq. P2) so a pole at I5 = 0 or I4 = 0 evaluates to
//! ±∞, not ∞ − ∞ = NaN.

use crate::cas::{Graph, Id, Node, Sym};
use crate::diag::Error;
use crate::front::resolved::{Program, RExpr, Var};
use crate::ir::{DomainGuard, FibreIr, FibreUses};
use crate::span::Span;

/// What a term reads.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Iso,
    Fibre,
    Both,
}

fn kind(g: &Graph, id: Id) -> Kind {
    match (g.uses_sigma(id) || g.uses_invariants(id), g.uses_fibre(id)) {
        (_, false) => Kind::Iso,
        (false, true) => Kind::Fibre,
        (true, true) => Kind::Both,
    }
}

/// Ψ's terms with products over mixed sums distributed (one level deep per
/// product; nested products are distributed recursively).
fn terms(g: &mut Graph, id: Id, out: &mut Vec<Id>) {
    match g.get(id).clone() {
        Node::Add(c) => c.iter().for_each(|&t| terms(g, t, out)),
        Node::Mul(c) if kind(g, id) == Kind::Both => {
            let Some(k) = c.iter().position(|&f| matches!(g.get(f), Node::Add(_))) else {
                out.push(id);
                return;
            };
            let Node::Add(sum) = g.get(c[k]).clone() else {
                out.push(id);
                return;
            };
            let others: Vec<Id> = c
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != k)
                .map(|(_, f)| *f)
                .collect();
            for t in sum {
                let mut f = others.clone();
                f.push(t);
                let p = g.product(&f);
                terms(g, p, out);
            }
        }
        _ => out.push(id),
    }
}

/// Ψ split into its isotropic and fibre parts.
pub struct Split {
    /// Ψ_iso.
    pub iso: Id,
    /// ψ(I4, I5).
    pub fibre: Id,
    /// Ψ_iso's domain conditions.
    pub iso_guards: Vec<DomainGuard>,
    /// ψ's domain conditions.
    pub fibre_guards: Vec<DomainGuard>,
}

/// Split Ψ (see the module docs), or the located coupling errors.
pub fn split(
    g: &mut Graph,
    psi: Id,
    guards: Vec<DomainGuard>,
    prog: &Program,
) -> Result<Split, Vec<Error>> {
    let mut all = Vec::new();
    terms(g, psi, &mut all);
    let (mut iso, mut fib, mut errors) = (Vec::new(), Vec::new(), Vec::new());
    for t in all {
        match kind(g, t) {
            Kind::Iso => iso.push(t),
            Kind::Fibre => fib.push(t),
            Kind::Both => errors.push(coupled(g, t, prog)),
        }
    }
    let (mut iso_guards, mut fib_guards, mut params_only) = (Vec::new(), Vec::new(), Vec::new());
    for d in guards {
        match kind(g, d.arg) {
            Kind::Iso if !g.uses_sigma(d.arg) && !g.uses_invariants(d.arg) => params_only.push(d),
            Kind::Iso => iso_guards.push(d),
            Kind::Fibre => fib_guards.push(d),
            Kind::Both => errors.push(coupled(g, d.arg, prog)),
        }
    }
    if !errors.is_empty() {
        errors.dedup();
        return Err(errors);
    }
    let (iso, fibre) = (g.sum(&iso), g.sum(&fib));
    // A condition on parameters only (`k2 ≠ 0` of k1/(2 k2)) goes with the
    // part that still contains its argument (both if neither does).
    let (in_iso, in_fib) = (g.reachable(&[iso]), g.reachable(&[fibre]));
    for d in params_only {
        let (a, b) = (
            in_iso.binary_search(&d.arg).is_ok(),
            in_fib.binary_search(&d.arg).is_ok(),
        );
        if a || !b {
            iso_guards.push(d);
        }
        if b || !a {
            fib_guards.push(d);
        }
    }
    Ok(Split {
        iso,
        fibre,
        iso_guards,
        fibre_guards: fib_guards,
    })
}

/// The error for a term reading both kinds, at the written summand of psi
/// that reads both (else at the whole psi expression).
fn coupled(g: &Graph, term: Id, prog: &Program) -> Error {
    let span = coupled_span(prog).unwrap_or(prog.psi_span);
    Error::Fibre {
        span,
        message: format!(
            "the term `{}` couples the fibre invariants with the isotropic ones",
            g.to_text(term)
        ),
        label: "reads both I4/I5 and I1/I2/I3 or the stretches".into(),
        notes: vec![
            "note: an energy with a fibre must be a sum psi = Psi_iso(I1, I2, I3 | s) + psi_fibre(I4, I5): the runtime projects the two parts to PSD separately (Kim et al. 2019); a coupled energy would need the full numeric projection, which is not supported yet".into(),
            "help: write the fibre term without I1, I2, I3, J, the stretches or their aliases".into(),
        ],
    }
}

/// The span of the first written summand of psi that mentions both kinds.
fn coupled_span(prog: &Program) -> Option<Span> {
    let lets: Vec<(bool, bool)> = prog.lets.iter().fold(Vec::new(), |mut acc, l| {
        let m = mentions(&l.expr, &acc);
        acc.push(m);
        acc
    });
    let RExpr::Chain(first, rest) = &prog.psi else {
        return None;
    };
    if mentions(first, &lets) == (true, true) {
        return rest
            .first()
            .map(|(_, _, s)| Span::new(prog.psi_span.start, s.start));
    }
    rest.iter()
        .find(|(_, x, _)| mentions(x, &lets) == (true, true))
        .map(|(_, _, s)| *s)
}

/// (mentions an isotropic variable, mentions a fibre variable).
fn mentions(e: &RExpr, lets: &[(bool, bool)]) -> (bool, bool) {
    let or = |a: (bool, bool), b: (bool, bool)| (a.0 || b.0, a.1 || b.1);
    match e {
        RExpr::Var(Var::I4 | Var::I5 | Var::SignI4) => (false, true),
        RExpr::Var(Var::D) => (false, false),
        RExpr::Var(_) => (true, false),
        RExpr::Let(k) => lets.get(*k).copied().unwrap_or((false, false)),
        RExpr::Neg(x) | RExpr::Call(_, x, _) => mentions(x, lets),
        RExpr::Chain(f, rest) => rest
            .iter()
            .fold(mentions(f, lets), |m, (_, x, _)| or(m, mentions(x, lets))),
        RExpr::Pow(b, x, _) => or(mentions(b, lets), mentions(x, lets)),
        RExpr::Num(_) | RExpr::Param(_) | RExpr::Poison => (false, false),
    }
}

/// ψ's partials and properties over a fresh graph holding only ψ's part.
pub fn build(g: &mut Graph, psi: Id, guards: Vec<DomainGuard>, direction: &str) -> FibreIr {
    let d4 = g.diff(psi, Sym::I4);
    let d5 = g.diff(psi, Sym::I5);
    let d44 = g.diff(d4, Sym::I4);
    let d45 = g.diff(d4, Sym::I5);
    let d55 = g.diff(d5, Sym::I5);
    // Poles collected (eq. P2 of `poles`): ∞ − ∞ at I5 = 0 becomes ±∞.
    let mut memo = std::collections::HashMap::new();
    let [d4, d5, d44, d45, d55] =
        [d4, d5, d44, d45, d55].map(|d| super::poles::factor(g, d, &mut memo));
    let mut roots = vec![psi, d4, d5, d44, d45, d55];
    roots.extend(guards.iter().map(|d| d.arg));
    let (graph, new) = g.extract(&roots);
    let mut domain: Vec<DomainGuard> = guards
        .iter()
        .zip(&new[6..])
        .map(|(d, &arg)| DomainGuard { arg, ..*d })
        .collect();
    super::domain::mark_enforced(&graph, new[0], &mut domain);
    let reads = |s: Sym| {
        graph.may_depend(new[0], s)
            || domain
                .iter()
                .any(|d| !d.enforced_by_psi && graph.may_depend(d.arg, s))
    };
    let uses = match (reads(Sym::I4) || reads(Sym::SignI4), reads(Sym::I5)) {
        (false, false) => FibreUses::None,
        (true, false) => FibreUses::I4,
        (false, true) => FibreUses::I5,
        (true, true) => FibreUses::Both,
    };
    let zero = |id: Id| graph.is_int(id, 0);
    let closed_form = zero(new[1]) && zero(new[3]) && zero(new[4]);
    FibreIr {
        direction: direction.to_string(),
        psi: new[0],
        d4: new[1],
        d5: new[2],
        d44: new[3],
        d45: new[4],
        d55: new[5],
        uses,
        closed_form,
        domain,
        graph,
    }
}
