//! From a lowered Ψ to a complete [`DimIr`] for one dimension.

use crate::cas::{Graph, Id, Sym};
use crate::diag::Error;
use crate::ir::{DimIr, DomainGuard, InvariantDerivs, PairIr, PairKind, Path, ScaleIr, SpectralIr};
use crate::poly::{Converter, Proof};
use crate::span::Span;

use super::checks;
use super::cost::cost;
use super::derivs;

/// The pair of each slot: 2D slot 0 = (0, 1); 3D slot k = (1, 2), (2, 0), (0, 1).
pub fn slot_pairs(dim: u8) -> Vec<(usize, usize)> {
    if dim == 2 {
        vec![(0, 1)]
    } else {
        vec![(1, 2), (2, 0), (0, 1)]
    }
}

/// What the dimension build needs besides the graph.
pub struct DimInput<'a> {
    /// 2 or 3.
    pub dim: u8,
    /// Parameter defaults (for numeric checks).
    pub params: &'a [f64],
    /// The domain of Ψ as written (ids in the lowering graph).
    pub domain: &'a [DomainGuard],
    /// Span of psi's definition (for errors).
    pub psi_span: Span,
    /// The source never mentions s3.
    pub no_s3: bool,
}

/// Ψ's proved properties (the flags of [`DimIr`]).
struct Flags {
    path: Path,
    isotropy_numeric_only: bool,
    rational: bool,
    sign_symmetric: bool,
    barrier: bool,
    svd_free: bool,
}

/// Everything built for one dimension, before garbage collection.
struct Parts {
    psi: Id,
    d_inv: Option<InvariantDerivs>,
    grad: Vec<Id>,
    a: Vec<Vec<Id>>,
    decoupled: bool,
    twist: Vec<(PairIr, PairKind)>,
    flip: Vec<(PairIr, PairKind)>,
    domain: Vec<DomainGuard>,
}

/// Build the IR of Ψ = `psi` (an expression in I's, σ's and params of `g`).
pub fn build_dim(mut g: Graph, psi: Id, input: &DimInput) -> Result<DimIr, Error> {
    let dim = input.dim;
    let mut conv = Converter::new(&g, dim);
    let psi_s = conv.to_sigma(&mut g, psi);
    let flags = analyse(&mut g, &mut conv, psi, psi_s, input)?;
    let (d_inv, grad_raw, a_raw) = match flags.path {
        Path::Invariant => {
            let d = derivs::invariant_derivs(&mut g, psi);
            let (gr, a) = derivs::invariant_chain(&mut g, dim, &d);
            (Some(d), gr, a)
        }
        Path::Stretch => {
            let (gr, a) = derivs::stretch_derivs(&mut g, dim, psi_s);
            (None, gr, a)
        }
    };
    let (mut a, decoupled) = prove_off_diagonals(&mut g, &mut conv, &a_raw);
    let grad: Vec<Id> = grad_raw
        .iter()
        .map(|&x| compact(&mut g, &mut conv, x))
        .collect();
    compact_block(&mut g, &mut conv, &mut a);
    let mut twist = Vec::new();
    let mut flip = Vec::new();
    for (slot, (i, j)) in slot_pairs(dim).into_iter().enumerate() {
        let ctx = PairCtx {
            i,
            j,
            slot,
            dim,
            rational: flags.rational,
            sign_symmetric: flags.sign_symmetric,
        };
        let d = d_inv.as_ref();
        flip.push(flip_ir(&mut g, &mut conv, &ctx, &grad_raw, &a, d));
        twist.push(twist_ir(&mut g, &mut conv, &ctx, &grad_raw, &a, d));
    }
    let parts = Parts {
        psi,
        d_inv,
        grad,
        a,
        decoupled,
        twist,
        flip,
        domain: input.domain.to_vec(),
    };
    Ok(finish(&g, dim, parts, flags))
}

/// Path, isotropy, rationality, sign symmetry, barrier and SVD-freeness of Ψ.
fn analyse(
    g: &mut Graph,
    conv: &mut Converter,
    psi: Id,
    psi_s: Id,
    input: &DimInput,
) -> Result<Flags, Error> {
    let dim = input.dim;
    let path = if g.uses_sigma(psi) {
        Path::Stretch
    } else {
        Path::Invariant
    };
    let isotropy_numeric_only = match path {
        Path::Stretch => checks::check_isotropy(
            g,
            conv,
            psi_s,
            dim,
            input.params,
            input.psi_span,
            input.no_s3,
        )?,
        Path::Invariant => false,
    };
    Ok(Flags {
        path,
        isotropy_numeric_only,
        rational: conv.rational(g, psi_s).is_some(),
        sign_symmetric: checks::sign_symmetric(g, conv, psi_s, dim),
        barrier: checks::barrier(g, conv, psi_s, dim, input.params, input.domain),
        svd_free: std::iter::once(psi)
            .chain(
                input
                    .domain
                    .iter()
                    .filter(|d| !d.enforced_by_psi)
                    .map(|d| d.arg),
            )
            .all(|x| !g.may_depend(x, Sym::I1) && !g.uses_sigma(x)),
    })
}

/// A = ∂²Ψ/∂σ² with the off-diagonals proved ≡ 0 replaced by 0, and whether
/// every off-diagonal was proved ≡ 0.
#[allow(clippy::needless_range_loop)] // symmetric matrices read best with indices
fn prove_off_diagonals(
    g: &mut Graph,
    conv: &mut Converter,
    a_raw: &[Vec<Id>],
) -> (Vec<Vec<Id>>, bool) {
    let n = a_raw.len();
    let mut decoupled = true;
    let mut a = a_raw.to_vec();
    for i in 0..n {
        for j in (i + 1)..n {
            if conv.is_zero(g, a_raw[i][j]) == Proof::Zero {
                let z = g.zero();
                a[i][j] = z;
                a[j][i] = z;
            } else {
                decoupled = false;
            }
        }
    }
    (a, decoupled)
}

/// Compact the upper triangle of the symmetric `a` and mirror it.
#[allow(clippy::needless_range_loop)] // symmetric matrices read best with indices
fn compact_block(g: &mut Graph, conv: &mut Converter, a: &mut [Vec<Id>]) {
    let n = a.len();
    for i in 0..n {
        for j in i..n {
            let v = compact(g, conv, a[i][j]);
            a[i][j] = v;
            a[j][i] = v;
        }
    }
}

/// The ids a pair needs, in a fixed order (for extraction and remapping).
fn pair_roots(p: &PairIr) -> Vec<Id> {
    match p {
        PairIr::Exact(x) => vec![*x],
        PairIr::Guarded { direct, limit, den } => vec![*direct, *limit, *den],
    }
}

/// Collect the roots, find the singular sets, garbage-collect the graph and
/// assemble the [`DimIr`] over the new graph.
fn finish(g: &Graph, dim: u8, p: Parts, flags: Flags) -> DimIr {
    let n = dim as usize;
    let mut roots: Vec<Id> = vec![p.psi];
    if let Some(d) = &p.d_inv {
        roots.extend(d.d1);
        roots.extend(d.d2);
    }
    roots.extend(&p.grad);
    for row in &p.a {
        roots.extend(row);
    }
    for (pr, _) in p.twist.iter().chain(p.flip.iter()) {
        roots.extend(pair_roots(pr));
    }
    let singular = checks::singularities(g, &roots);
    roots.extend(&singular);
    roots.extend(p.domain.iter().map(|d| d.arg));
    let (graph, new) = g.extract(&roots);
    let mut it = new.into_iter();
    let mut next = || it.next().unwrap_or(Id(0));
    let psi = next();
    let d_inv = p.d_inv.map(|_| InvariantDerivs {
        d1: [next(), next(), next()],
        d2: [next(), next(), next(), next(), next(), next()],
    });
    let grad: Vec<Id> = (0..n).map(|_| next()).collect();
    let a: Vec<Vec<Id>> = (0..n).map(|_| (0..n).map(|_| next()).collect()).collect();
    let mut remap_pair = |(pr, _): &(PairIr, PairKind)| match pr {
        PairIr::Exact(_) => PairIr::Exact(next()),
        PairIr::Guarded { .. } => PairIr::Guarded {
            direct: next(),
            limit: next(),
            den: next(),
        },
    };
    let twist: Vec<PairIr> = p.twist.iter().map(&mut remap_pair).collect();
    let flip: Vec<PairIr> = p.flip.iter().map(&mut remap_pair).collect();
    let singularities: Vec<Id> = singular.iter().map(|_| next()).collect();
    let domain: Vec<DomainGuard> = p
        .domain
        .iter()
        .map(|d| DomainGuard { arg: next(), ..*d })
        .collect();
    let scale = if p.decoupled {
        ScaleIr::Diagonal((0..n).map(|i| a[i][i]).collect())
    } else {
        ScaleIr::Full(a.clone())
    };
    DimIr {
        dim,
        graph,
        path: flags.path,
        psi,
        d_inv,
        d_sigma: grad.clone(),
        h_sigma: a,
        spectral: SpectralIr {
            grad,
            scale,
            twist,
            flip,
            twist_kind: p.twist.iter().map(|(_, k)| *k).collect(),
            flip_kind: p.flip.iter().map(|(_, k)| *k).collect(),
        },
        barrier: flags.barrier,
        svd_free: flags.svd_free,
        sign_symmetric: flags.sign_symmetric,
        decoupled: p.decoupled,
        isotropy_numeric_only: flags.isotropy_numeric_only,
        singularities,
        fibre: None,
        domain,
    }
}

struct PairCtx {
    i: usize,
    j: usize,
    slot: usize,
    dim: u8,
    rational: bool,
    sign_symmetric: bool,
}

/// The most compact of: `x` as built, its σ-form, and (when rational) the
/// factored rational-function form.
pub fn compact(g: &mut Graph, conv: &mut Converter, x: Id) -> Id {
    let mut best = (cost(g, x), x);
    let xs = conv.to_sigma(g, x);
    let c = cost(g, xs);
    if c < best.0 {
        best = (c, xs);
    }
    if let Some(r) = conv.rational(g, x) {
        let e = conv.to_expr(g, &r);
        let c = cost(g, e);
        if c < best.0 {
            best = (c, e);
        }
    }
    best.1
}

/// (A_ii + A_jj)/2 + s·A_ij.
fn limit(g: &mut Graph, conv: &mut Converter, a: &[Vec<Id>], i: usize, j: usize, s: i64) -> Id {
    let half = g.num(num_rational::BigRational::new(1.into(), 2.into()));
    let d = g.add2(a[i][i], a[j][j]);
    let m = g.mul2(half, d);
    let sc = g.int(s);
    let off = g.mul2(sc, a[i][j]);
    let l = g.add2(m, off);
    compact(g, conv, l)
}

/// σi + s·σj.
fn den(g: &mut Graph, i: usize, j: usize, s: i64) -> Id {
    let si = g.sym(Sym::Sigma(i as u8));
    let sj = g.sym(Sym::Sigma(j as u8));
    let sc = g.int(s);
    let t = g.mul2(sc, sj);
    g.add2(si, t)
}

/// (Ψi + s·Ψj) / (σi + s·σj) exactly, when the energy is rational and the
/// numerator vanishes on the hyperplane.
fn exact_quotient(
    g: &mut Graph,
    conv: &mut Converter,
    grad: &[Id],
    i: usize,
    j: usize,
    s: i64,
) -> Option<Id> {
    let sc = g.int(s);
    let t = g.mul2(sc, grad[j]);
    let num = g.add2(grad[i], t);
    let r = conv.rational(g, num)?;
    let q = r.div_linear(i, j, s).ok()??;
    Some(conv.to_expr(g, &q))
}

/// The c_ij = ∂²I3/∂σi∂σj factor of the invariant-path twist/flip: σ_k in 3D, 1 in 2D.
fn c_ij(g: &mut Graph, ctx: &PairCtx) -> Id {
    if ctx.dim == 2 {
        g.one()
    } else {
        g.sym(Sym::Sigma(ctx.slot as u8))
    }
}

/// λ_flip for one pair. Invariant path: 2Ψ2 − c_ij Ψ3 (eqs. 22b, 23b), no
/// division. Stretch path: removable by isotropy (Ψ is symmetric in σi, σj,
/// so Ψi = Ψj on σi = σj and the numerator vanishes there); an exact quotient
/// when the energy is rational, else guarded with the limit
/// (A_ii + A_jj)/2 − A_ij, whose error is O((σi − σj)²) because Ψi − Ψj is odd
/// about the plane.
fn flip_ir(
    g: &mut Graph,
    conv: &mut Converter,
    ctx: &PairCtx,
    grad: &[Id],
    a: &[Vec<Id>],
    d: Option<&InvariantDerivs>,
) -> (PairIr, PairKind) {
    let (i, j) = (ctx.i, ctx.j);
    if let Some(d) = d {
        let two = g.int(2);
        let t = g.mul2(two, d.d1[1]);
        let c = c_ij(g, ctx);
        let u = g.mul2(c, d.d1[2]);
        let v = g.sub(t, u);
        return (PairIr::Exact(compact(g, conv, v)), PairKind::Regular);
    }
    if ctx.rational
        && let Some(q) = exact_quotient(g, conv, grad, i, j, -1)
    {
        return (PairIr::Exact(q), PairKind::Removable);
    }
    let dn = den(g, i, j, -1);
    let nu = g.sub(grad[i], grad[j]);
    let direct = g.div(nu, dn);
    let direct = compact(g, conv, direct);
    let pair = PairIr::Guarded {
        direct,
        limit: limit(g, conv, a, i, j, -1),
        den: dn,
    };
    (pair, PairKind::Removable)
}

/// Whether `num` (in I's, σ's and parameters) vanishes identically on
/// σj = t·σi: σj := t·σi is substituted into its σ-form and the result is
/// decided ≡ 0 exactly (rational arithmetic; non-rational parts as atoms in
/// normal form, which is sound for proving ≡ 0).
fn vanishes_on(g: &mut Graph, conv: &mut Converter, num: Id, i: usize, j: usize, t: i64) -> bool {
    let ns = conv.to_sigma(g, num);
    let si = g.sym(Sym::Sigma(i as u8));
    let on_plane = if t == 1 { si } else { g.neg(si) };
    let at = g.substitute(ns, &|s| (s == Sym::Sigma(j as u8)).then_some(on_plane));
    conv.is_zero(g, at) == Proof::Zero
}

/// The removable twist's limit `lim` = (A_ii + A_jj)/2 + A_ij corrected to
/// second order off the plane when Ψ is not sign-symmetric
/// (`ecc_runtime::divided`): lim − (∂i + ∂j)(A_ii + 2A_ij + A_jj)·(σi + σj)/8.
fn corrected_limit(
    g: &mut Graph,
    conv: &mut Converter,
    a: &[Vec<Id>],
    (i, j): (usize, usize),
    lim: Id,
    dn: Id,
) -> Id {
    let two = g.int(2);
    let aij2 = g.mul2(two, a[i][j]);
    let m = g.sum(&[a[i][i], aij2, a[j][j]]);
    let ms = conv.to_sigma(g, m);
    let di = g.diff(ms, Sym::Sigma(i as u8));
    let dj = g.diff(ms, Sym::Sigma(j as u8));
    let dm = g.add2(di, dj);
    let eighth = g.num(num_rational::BigRational::new(1.into(), 8.into()));
    let corr = g.product(&[eighth, dm, dn]);
    let v = g.sub(lim, corr);
    compact(g, conv, v)
}

/// λ_twist for one pair and what it does on σi + σj = 0.
///
/// Invariant path: 2Ψ1/(σi+σj) + 2Ψ2 + c_ij Ψ3 (eqs. 22a, 23a), regular when
/// Ψ1 ≡ 0; stretch path: (Ψi + Ψj)/(σi + σj). The singular numerator (Ψ1, or
/// Ψi + Ψj) is tested on σj = −σi ([`vanishes_on`]; sign symmetry implies it):
/// removable → exact quotient (rational Ψ) or guarded with the (corrected)
/// limit; otherwise a pole.
fn twist_ir(
    g: &mut Graph,
    conv: &mut Converter,
    ctx: &PairCtx,
    grad: &[Id],
    a: &[Vec<Id>],
    d: Option<&InvariantDerivs>,
) -> (PairIr, PairKind) {
    let (i, j) = (ctx.i, ctx.j);
    let dn = den(g, i, j, 1);
    let (direct, num) = match d {
        Some(d) => {
            let two = g.int(2);
            let t2 = g.mul2(two, d.d1[1]);
            let c = c_ij(g, ctx);
            let t3 = g.mul2(c, d.d1[2]);
            if conv.is_zero(g, d.d1[0]) == Proof::Zero {
                let v = g.add2(t2, t3);
                return (PairIr::Exact(compact(g, conv, v)), PairKind::Regular);
            }
            let q = g.div(d.d1[0], dn);
            let t1 = g.mul2(two, q);
            (g.sum(&[t1, t2, t3]), d.d1[0])
        }
        None => {
            let nu = g.add2(grad[i], grad[j]);
            (g.div(nu, dn), nu)
        }
    };
    if ctx.rational
        && let Some(q) = exact_quotient(g, conv, grad, i, j, 1)
    {
        return (PairIr::Exact(q), PairKind::Removable);
    }
    let direct = compact(g, conv, direct);
    if !ctx.sign_symmetric && !vanishes_on(g, conv, num, i, j, -1) {
        return (PairIr::Exact(direct), PairKind::Pole);
    }
    let mut lim = limit(g, conv, a, i, j, 1);
    if !ctx.sign_symmetric {
        lim = corrected_limit(g, conv, a, (i, j), lim, dn);
    }
    let pair = PairIr::Guarded {
        direct,
        limit: lim,
        den: dn,
    };
    (pair, PairKind::Removable)
}
