//! Gradients and Hessians in stretch space.
//!
//! Invariant path (Smith et al. 2019): with gᵢ = ∂I/∂σᵢ = (1, 2σᵢ, pᵢ),
//! pᵢ = Π_{l≠i} σ_l, and the invariant Hessians ∂²I2/∂σᵢ∂σⱼ = 2δᵢⱼ,
//! ∂²I3/∂σᵢ∂σⱼ = cᵢⱼ = Π_{l≠i,j} σ_l (i ≠ j; 1 in 2D, σ_k in 3D):
//!
//! Ψ_σᵢ = Ψ1 + 2σᵢΨ2 + pᵢΨ3,
//! A_ii = 2Ψ2 + Ψ11 + 4σᵢ²Ψ22 + pᵢ²Ψ33 + 4σᵢΨ12 + 4 I3 Ψ23 + 2pᵢΨ13,
//! A_ij = cᵢⱼΨ3 + Ψ11 + 4σᵢσⱼΨ22 + pᵢpⱼΨ33 + 2(σᵢ+σⱼ)Ψ12
//!        + 2(σᵢpⱼ + σⱼpᵢ)Ψ23 + (pᵢ+pⱼ)Ψ13,
//!
//! which is Appendix D (pᵢpⱼ = cᵢⱼ I3). The tests check A = ∂²Ψ/∂σ² after
//! substituting the invariants.
//!
//! Stretch path (Zhu 2020): the invariants are substituted first and Ψ is
//! differentiated in σ directly.

use crate::cas::{Graph, Id, Sym};
use crate::ir::InvariantDerivs;

/// Ψ's invariant derivatives: [Ψ1, Ψ2, Ψ3] and [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23].
pub fn invariant_derivs(g: &mut Graph, psi: Id) -> InvariantDerivs {
    let inv = [Sym::I1, Sym::I2, Sym::I3];
    let d1 = inv.map(|s| g.diff(psi, s));
    let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
    let d2 = pairs.map(|(a, b)| g.diff(d1[a], inv[b]));
    InvariantDerivs { d1, d2 }
}

fn sigmas(g: &mut Graph, dim: u8) -> Vec<Id> {
    (0..dim).map(|k| g.sym(Sym::Sigma(k))).collect()
}

/// Π_{l ∉ skip} σ_l.
fn prod_except(g: &mut Graph, s: &[Id], skip: &[usize]) -> Id {
    let f: Vec<Id> = s
        .iter()
        .enumerate()
        .filter(|(l, _)| !skip.contains(l))
        .map(|(_, x)| *x)
        .collect();
    g.product(&f)
}

/// Chain rule: (Ψ_σ, A) from the invariant derivatives.
#[allow(clippy::needless_range_loop)] // symmetric matrices read best with indices
pub fn invariant_chain(g: &mut Graph, dim: u8, d: &InvariantDerivs) -> (Vec<Id>, Vec<Vec<Id>>) {
    let s = sigmas(g, dim);
    let n = dim as usize;
    let [p1, p2, p3] = d.d1;
    let [p11, p22, p33, p12, p13, p23] = d.d2;
    let i3 = g.sym(Sym::I3);
    let p: Vec<Id> = (0..n).map(|i| prod_except(g, &s, &[i])).collect();
    let c = |g: &mut Graph, a: f64| g.int(a as i64);
    let mut grad = Vec::with_capacity(n);
    for i in 0..n {
        let two = c(g, 2.0);
        let t2 = g.product(&[two, s[i], p2]);
        let t3 = g.product(&[p[i], p3]);
        grad.push(g.sum(&[p1, t2, t3]));
    }
    let mut a = vec![vec![g.zero(); n]; n];
    for i in 0..n {
        for j in i..n {
            let v = if i == j {
                let two = c(g, 2.0);
                let four = c(g, 4.0);
                let t0 = g.product(&[two, p2]);
                let si2 = g.powi(s[i], 2);
                let t1 = g.product(&[four, si2, p22]);
                let pi2 = g.powi(p[i], 2);
                let t2 = g.product(&[pi2, p33]);
                let t3 = g.product(&[four, s[i], p12]);
                let t4 = g.product(&[four, i3, p23]);
                let t5 = g.product(&[two, p[i], p13]);
                g.sum(&[t0, p11, t1, t2, t3, t4, t5])
            } else {
                let cij = prod_except(g, &s, &[i, j]);
                let two = c(g, 2.0);
                let four = c(g, 4.0);
                let t0 = g.product(&[cij, p3]);
                let t1 = g.product(&[four, s[i], s[j], p22]);
                let t2 = g.product(&[cij, i3, p33]);
                let sij = g.add2(s[i], s[j]);
                let t3 = g.product(&[two, sij, p12]);
                let a1 = g.mul2(s[i], p[j]);
                let a2 = g.mul2(s[j], p[i]);
                let mix = g.add2(a1, a2);
                let t4 = g.product(&[two, mix, p23]);
                let pp = g.add2(p[i], p[j]);
                let t5 = g.product(&[pp, p13]);
                g.sum(&[t0, p11, t1, t2, t3, t4, t5])
            };
            a[i][j] = v;
            a[j][i] = v;
        }
    }
    (grad, a)
}

/// Direct differentiation of the σ-form: (Ψ_σ, ∂²Ψ/∂σ²).
#[allow(clippy::needless_range_loop)] // symmetric matrices read best with indices
pub fn stretch_derivs(g: &mut Graph, dim: u8, psi_s: Id) -> (Vec<Id>, Vec<Vec<Id>>) {
    let n = dim as usize;
    let grad: Vec<Id> = (0..dim).map(|i| g.diff(psi_s, Sym::Sigma(i))).collect();
    let mut a = vec![vec![g.zero(); n]; n];
    for i in 0..n {
        for j in i..n {
            let v = g.diff(grad[i], Sym::Sigma(j as u8));
            a[i][j] = v;
            a[j][i] = v;
        }
    }
    (grad, a)
}
