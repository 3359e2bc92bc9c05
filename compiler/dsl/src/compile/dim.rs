//! From a lowered Ψ to a complete [`DimIr`] for one dimension.

use crate::cas::{Graph, Id, Sym};
use crate::diag::Error;
use crate::ir::{DimIr, InvariantDerivs, PairIr, Path, ScaleIr, SpectralIr};
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
    /// Span of psi's definition (for errors).
    pub psi_span: Span,
    /// The source never mentions s3.
    pub no_s3: bool,
}

/// Build the IR of Ψ = `psi` (an expression in I's, σ's and params of `g`).
#[allow(clippy::needless_range_loop)] // symmetric matrices read best with indices
pub fn build_dim(mut g: Graph, psi: Id, input: &DimInput) -> Result<DimIr, Error> {
    let dim = input.dim;
    let n = dim as usize;
    let mut conv = Converter::new(&g, dim);
    let psi_s = conv.to_sigma(&mut g, psi);
    let path = if g.uses_sigma(psi) {
        Path::Stretch
    } else {
        Path::Invariant
    };
    let isotropy_numeric_only = match path {
        Path::Stretch => checks::check_isotropy(
            &mut g,
            &mut conv,
            psi_s,
            dim,
            input.params,
            input.psi_span,
            input.no_s3,
        )?,
        Path::Invariant => false,
    };
    let rational = conv.rational(&mut g, psi_s).is_some();
    let sign_symmetric = checks::sign_symmetric(&mut g, &mut conv, psi_s, dim);
    let barrier = checks::barrier(&mut g, &mut conv, psi_s, dim);
    let svd_free = !g.may_depend(psi, Sym::I1) && !g.uses_sigma(psi);

    let (d_inv, grad_raw, a_raw) = match path {
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

    // Off-diagonals of A: prove ≡ 0 where possible.
    let mut decoupled = true;
    let mut a = a_raw.clone();
    for i in 0..n {
        for j in (i + 1)..n {
            if conv.is_zero(&mut g, a_raw[i][j]) == Proof::Zero {
                let z = g.zero();
                a[i][j] = z;
                a[j][i] = z;
            } else {
                decoupled = false;
            }
        }
    }
    let grad: Vec<Id> = grad_raw
        .iter()
        .map(|&x| compact(&mut g, &mut conv, x))
        .collect();
    for i in 0..n {
        for j in i..n {
            let v = compact(&mut g, &mut conv, a[i][j]);
            a[i][j] = v;
            a[j][i] = v;
        }
    }

    let mut twist = Vec::new();
    let mut flip = Vec::new();
    for (slot, (i, j)) in slot_pairs(dim).into_iter().enumerate() {
        let ctx = PairCtx {
            i,
            j,
            slot,
            dim,
            rational,
            sign_symmetric,
        };
        flip.push(flip_ir(
            &mut g,
            &mut conv,
            &ctx,
            &grad_raw,
            &a,
            d_inv.as_ref(),
        ));
        twist.push(twist_ir(
            &mut g,
            &mut conv,
            &ctx,
            &grad_raw,
            &a,
            d_inv.as_ref(),
        ));
    }

    let scale = if decoupled {
        ScaleIr::Diagonal((0..n).map(|i| a[i][i]).collect())
    } else {
        ScaleIr::Full(a.clone())
    };

    // Collect the roots, find the singular sets, then garbage-collect the graph.
    let mut roots: Vec<Id> = vec![psi];
    if let Some(d) = &d_inv {
        roots.extend(d.d1);
        roots.extend(d.d2);
    }
    roots.extend(&grad);
    for row in &a {
        roots.extend(row);
    }
    for p in twist.iter().chain(flip.iter()) {
        match p {
            PairIr::Exact(x) => roots.push(*x),
            PairIr::Guarded { direct, limit, den } => roots.extend([*direct, *limit, *den]),
        }
    }
    let singular = checks::singularities(&g, &roots);
    roots.extend(&singular);
    let (graph, new) = g.extract(&roots);
    let mut it = new.into_iter();
    let mut next = || it.next().unwrap_or(Id(0));
    let psi = next();
    let d_inv = d_inv.map(|_| InvariantDerivs {
        d1: [next(), next(), next()],
        d2: [next(), next(), next(), next(), next(), next()],
    });
    let grad: Vec<Id> = (0..n).map(|_| next()).collect();
    let a: Vec<Vec<Id>> = (0..n).map(|_| (0..n).map(|_| next()).collect()).collect();
    let mut remap_pair = |p: &PairIr| match p {
        PairIr::Exact(_) => PairIr::Exact(next()),
        PairIr::Guarded { .. } => PairIr::Guarded {
            direct: next(),
            limit: next(),
            den: next(),
        },
    };
    let twist: Vec<PairIr> = twist.iter().map(&mut remap_pair).collect();
    let flip: Vec<PairIr> = flip.iter().map(&mut remap_pair).collect();
    let singularities: Vec<Id> = singular.iter().map(|_| next()).collect();
    let scale = match scale {
        ScaleIr::Diagonal(_) => ScaleIr::Diagonal((0..n).map(|i| a[i][i]).collect()),
        ScaleIr::Full(_) => ScaleIr::Full(a.clone()),
    };
    Ok(DimIr {
        dim,
        graph,
        path,
        psi,
        d_inv,
        d_sigma: grad.clone(),
        h_sigma: a,
        spectral: SpectralIr {
            grad,
            scale,
            twist,
            flip,
        },
        barrier,
        svd_free,
        sign_symmetric,
        decoupled,
        isotropy_numeric_only,
        singularities,
    })
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

fn flip_ir(
    g: &mut Graph,
    conv: &mut Converter,
    ctx: &PairCtx,
    grad: &[Id],
    a: &[Vec<Id>],
    d: Option<&InvariantDerivs>,
) -> PairIr {
    let (i, j) = (ctx.i, ctx.j);
    if let Some(d) = d {
        // 2Ψ2 − c_ij Ψ3 (eqs. 22b, 23b): division-free.
        let two = g.int(2);
        let t = g.mul2(two, d.d1[1]);
        let c = c_ij(g, ctx);
        let u = g.mul2(c, d.d1[2]);
        let v = g.sub(t, u);
        return PairIr::Exact(compact(g, conv, v));
    }
    if ctx.rational
        && let Some(q) = exact_quotient(g, conv, grad, i, j, -1)
    {
        return PairIr::Exact(q);
    }
    let dn = den(g, i, j, -1);
    let nu = g.sub(grad[i], grad[j]);
    let direct = g.div(nu, dn);
    let direct = compact(g, conv, direct);
    PairIr::Guarded {
        direct,
        limit: limit(g, conv, a, i, j, -1),
        den: dn,
    }
}

fn twist_ir(
    g: &mut Graph,
    conv: &mut Converter,
    ctx: &PairCtx,
    grad: &[Id],
    a: &[Vec<Id>],
    d: Option<&InvariantDerivs>,
) -> PairIr {
    let (i, j) = (ctx.i, ctx.j);
    let dn = den(g, i, j, 1);
    let direct = match d {
        Some(d) => {
            // 2Ψ1/(σi+σj) + 2Ψ2 + c_ij Ψ3 (eqs. 22a, 23a).
            let two = g.int(2);
            let t2 = g.mul2(two, d.d1[1]);
            let c = c_ij(g, ctx);
            let t3 = g.mul2(c, d.d1[2]);
            if conv.is_zero(g, d.d1[0]) == Proof::Zero {
                let v = g.add2(t2, t3);
                return PairIr::Exact(compact(g, conv, v));
            }
            let q = g.div(d.d1[0], dn);
            let t1 = g.mul2(two, q);
            g.sum(&[t1, t2, t3])
        }
        None => {
            let nu = g.add2(grad[i], grad[j]);
            g.div(nu, dn)
        }
    };
    if ctx.rational
        && let Some(q) = exact_quotient(g, conv, grad, i, j, 1)
    {
        return PairIr::Exact(q);
    }
    let direct = compact(g, conv, direct);
    if ctx.sign_symmetric {
        PairIr::Guarded {
            direct,
            limit: limit(g, conv, a, i, j, 1),
            den: dn,
        }
    } else {
        PairIr::Exact(direct)
    }
}
