//! Properties of Ψ proved (or, for isotropy, at worst checked numerically)
//! on its σ-form: isotropy, sign symmetry, the barrier property.

use num_traits::Zero;

use crate::cas::{Env, Graph, Id, Node, Sym, Tape};
use crate::diag::Error;
use crate::ir::DomainGuard;
use crate::poly::{Converter, Proof};
use crate::span::Span;

/// The pairs (i, j) of stretches in `dim`.
pub fn pairs(dim: u8) -> Vec<(u8, u8)> {
    if dim == 2 {
        vec![(0, 1)]
    } else {
        vec![(0, 1), (0, 2), (1, 2)]
    }
}

/// Whether the (signed) substitution σi ↦ s·σj, σj ↦ s·σi leaves `psi`
/// unchanged: `Some(true/false)` when decided exactly, `None` otherwise.
///
/// Both sides are converted to rational functions whose variables are σ, the
/// parameters and atoms in normal form (see `Converter::normal_form`); equal
/// rational functions prove equality. A difference proves inequality only
/// when no atom is involved.
fn invariant_under(
    g: &mut Graph,
    conv: &mut Converter,
    psi_s: Id,
    i: u8,
    j: u8,
    negate: bool,
) -> Option<bool> {
    let si = g.sym(Sym::Sigma(i));
    let sj = g.sym(Sym::Sigma(j));
    let (ti, tj) = if negate {
        (g.neg(sj), g.neg(si))
    } else {
        (sj, si)
    };
    let swapped = g.substitute(psi_s, &|s| match s {
        Sym::Sigma(k) if k == i => Some(ti),
        Sym::Sigma(k) if k == j => Some(tj),
        _ => None,
    });
    if swapped == psi_s {
        return Some(true);
    }
    let a = conv.convert(g, psi_s)?;
    let b = conv.convert(g, swapped)?;
    let diff = a.sub(&b).ok()?;
    if diff.is_zero() {
        Some(true)
    } else if !conv.has_atoms(&diff) {
        Some(false)
    } else {
        None
    }
}

/// Deterministic pseudo-random numbers (splitmix64) for numeric checks.
pub struct Rng(u64);

impl Rng {
    /// Seeded generator.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// Check that a stretch energy is symmetric under every swap of stretches.
/// Returns whether the check was only numeric; an error names the swap.
pub fn check_isotropy(
    g: &mut Graph,
    conv: &mut Converter,
    psi_s: Id,
    dim: u8,
    params: &[f64],
    span: Span,
    no_s3: bool,
) -> Result<bool, Error> {
    let mut numeric_only = false;
    let mut failing: Vec<(u8, u8)> = Vec::new();
    for (i, j) in pairs(dim) {
        match invariant_under(g, conv, psi_s, i, j, false) {
            Some(true) => {}
            Some(false) => failing.push((i, j)),
            None => {
                if numerically_differs(g, psi_s, dim, params, i, j) {
                    failing.push((i, j));
                } else {
                    numeric_only = true;
                }
            }
        }
    }
    if let Some(((i, j), rest)) = failing.split_first() {
        let name = |k: u8| format!("s{}", k + 1);
        return Err(Error::NotIsotropic {
            span,
            dim,
            a: name(*i),
            b: name(*j),
            others: rest.iter().map(|(a, b)| (name(*a), name(*b))).collect(),
            no_s3,
        });
    }
    Ok(numeric_only)
}

/// Ψ at random points vs Ψ with σi, σj swapped: true when they clearly differ.
fn numerically_differs(g: &Graph, psi_s: Id, dim: u8, params: &[f64], i: u8, j: u8) -> bool {
    let tape = Tape::new(g, &[psi_s]);
    let mut rng = Rng::new(0x5EED_0000 + u64::from(i) * 7 + u64::from(j));
    for _ in 0..8 {
        let mut s: Vec<f64> = (0..dim).map(|_| rng.uniform(0.4, 2.5)).collect();
        let a = tape.eval(&Env::new(dim, &s, params))[0];
        s.swap(i as usize, j as usize);
        let b = tape.eval(&Env::new(dim, &s, params))[0];
        if a.is_finite() && b.is_finite() && (a - b).abs() > 1e-7 * (1.0 + a.abs() + b.abs()) {
            return true;
        }
    }
    false
}

/// Ψ unchanged by (σi, σj) → (−σj, −σi) for every pair, proved exactly.
pub fn sign_symmetric(g: &mut Graph, conv: &mut Converter, psi_s: Id, dim: u8) -> bool {
    pairs(dim)
        .into_iter()
        .all(|(i, j)| invariant_under(g, conv, psi_s, i, j, true) == Some(true))
}

/// Whether Ψ is a barrier: Ψ → +∞ as det F → 0⁺, so the solver must keep
/// det F > 0.
///
/// Candidates (structural): a log or a negative power of something that
/// vanishes when one σ is 0. A positive fractional power (`I3^(1/3)`,
/// `sqrt(s1^2)`) is finite there and never makes a barrier. A candidate is
/// confirmed by growth (it may be cancelled, e.g. `I3*log(I3)` → 0): Ψ at
/// σ = (b, t) for t = 10⁻⁴, 10⁻⁸, …, 10⁻³² (b two fixed positive
/// stretch sets, parameters at their defaults) must increase strictly at
/// every step (or reach +∞ and stay there) — log growth gives ≈ 9.2 per
/// step, a power far more. Ψ is evaluated as written: +∞ where a
/// condition of its `domain` fails (`log(I3) - log(I3)` is 0 for I3 > 0,
/// not a barrier; the domain alone never makes one, as a candidate is
/// required).
pub fn barrier(
    g: &mut Graph,
    conv: &mut Converter,
    psi_s: Id,
    dim: u8,
    params: &[f64],
    domain: &[DomainGuard],
) -> bool {
    let mut args: Vec<Id> = Vec::new();
    for id in g.reachable(&[psi_s]) {
        match g.get(id) {
            Node::Log(x) => args.push(*x),
            Node::Pow([b, e]) => {
                let negative = match g.as_num(*e) {
                    Some(r) => r < &num_rational::BigRational::zero(),
                    None => true,
                };
                if negative {
                    args.push(*b);
                }
            }
            _ => {}
        }
    }
    let mut candidate = false;
    'found: for a in args {
        for k in 0..dim {
            let zero = g.zero();
            let at = g.substitute(a, &|s| (s == Sym::Sigma(k)).then_some(zero));
            if conv.is_zero(g, at) == Proof::Zero {
                candidate = true;
                break 'found;
            }
        }
    }
    candidate && grows_at_zero_det(g, psi_s, dim, params, domain)
}

/// Ψ grows without bound as the last σ → 0⁺: strictly increasing (or +∞
/// from some step on) with increments that do not die out (the last one at
/// least half the first: constant for a log, growing for a power; a bounded
/// approach such as t·log t has vanishing increments).
fn grows_at_zero_det(
    g: &Graph,
    psi_s: Id,
    dim: u8,
    params: &[f64],
    domain: &[DomainGuard],
) -> bool {
    let mut roots = vec![psi_s];
    roots.extend(domain.iter().map(|d| d.arg));
    let tape = Tape::new(g, &roots);
    let bases: [[f64; 2]; 2] = [[1.3, 0.8], [0.9, 1.1]];
    bases.iter().all(|b| {
        let v: Vec<f64> = (1..=8)
            .map(|n| {
                let mut s = vec![b[0], b[1], 0.0];
                s[dim as usize - 1] = 10f64.powi(-4 * n);
                let out = tape.eval(&Env::new(dim, &s, params));
                let inside = domain.iter().zip(&out[1..]).all(|(d, &x)| d.cond.holds(x));
                if inside { out[0] } else { f64::INFINITY }
            })
            .collect();
        let increasing = v
            .windows(2)
            .all(|w| w[1] > w[0] || (w[0] == f64::INFINITY && w[1] == f64::INFINITY));
        let (first, last) = (v[1] - v[0], v[7] - v[6]);
        increasing && (v[7] == f64::INFINITY || last >= 0.5 * first)
    })
}

/// Distinct denominators (bases of negative powers) and log arguments.
pub fn singularities(g: &Graph, roots: &[Id]) -> Vec<Id> {
    let mut out: Vec<Id> = Vec::new();
    for id in g.reachable(roots) {
        let s = match g.get(id) {
            Node::Log(x) => Some(*x),
            Node::Pow([b, e])
                if g.as_num(*e)
                    .is_some_and(|r| r < &num_rational::BigRational::zero()) =>
            {
                Some(*b)
            }
            _ => None,
        };
        if let Some(s) = s
            && !out.contains(&s)
        {
            out.push(s);
        }
    }
    out
}
