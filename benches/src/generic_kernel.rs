//! A precision-generic copy of the analytic element kernel, for the
//! **f32 vs f64** comparison (the runtime itself is f64-only).
//!
//! Clearly a *separate* implementation, written for this report: the same
//! mathematics as `ecc_runtime::element_eval` but simpler code.
//!
//! 1. F = Ds Dm⁻¹ and the signed SVD ([`crate::linalg::signed_svd`], Jacobi on FᵀF);
//! 2. Ψ, ∂Ψ/∂σ and A = ∂²Ψ/∂σ² by walking the energy's CAS graph
//!    ([`crate::graph_eval`], the stretch-space derivatives the DSL derives for every energy);
//! 3. eigenvalues: the d eigenpairs of A (Jacobi), and per pair (i, j)
//!    λ_flip = (Ψ_i − Ψ_j)/(σ_i − σ_j), λ_twist = (Ψ_i + Ψ_j)/(σ_i + σ_j) (Zhu 2020
//!    eq. 28). Near σ_i = σ_j (gap ≤ u^{1/3}·max|σ|) the flip uses the symmetric
//!    limit (A_ii + A_jj)/2 − A_ij, accurate to O(gap²); near σ_i = −σ_j the
//!    twist uses (A_ii + A_jj)/2 + A_ij, but only for energies the DSL proved
//!    sign-symmetric (elsewhere, e.g. ARAP, that value is a genuine pole);
//! 4. the filtered F-space Hessian Σ filter(λ) e eᵀ over the orthonormal modes
//!    (scaling U diag(a) Vᵀ, twist U(e_j e_iᵀ − e_i e_jᵀ)Vᵀ/√2, flip the same with +),
//!    then the dense chain rule H_e = |q| Bᵀ H B, g_e = |q| Bᵀ vec(∂Ψ/∂F).
//!
//! Vectors are column-major vec(F)[c·d + r] = F_rc and node-major x, as in the runtime.

use ecc_dsl::{DimIr, Graph};
use ecc_runtime::Filter;

use crate::graph_eval::{GraphEval, StretchRoots};
use crate::linalg::{signed_svd, sym_eigen};
use ecc_tests::real::Real;

/// An energy evaluated from its CAS graph in any precision.
pub struct GenericEnergy {
    graph: Graph,
    eval: GraphEval,
    roots: StretchRoots,
    params: Vec<f64>,
    sign_symmetric: bool,
    dim: usize,
}

/// Ψ, ∂Ψ/∂σ and ∂²Ψ/∂σ² at one σ.
pub struct StretchData<R> {
    pub psi: R,
    pub grad: Vec<R>,
    /// row-major d×d
    pub hess: Vec<R>,
}

/// The result of one element evaluation (already × rest measure).
#[derive(Clone, Debug)]
pub struct GenericEval<R> {
    pub psi: R,
    pub grad: Vec<R>,
    /// row-major N×N, N = d(d+1)
    pub hess: Vec<R>,
}

/// Filter an eigenvalue in any precision (non-finite → the filter's floor, as the runtime).
pub fn filter_value<R: Real>(filter: Filter, l: R) -> R {
    match filter {
        Filter::None => l,
        _ if !l.is_finite() => R::from_f64(filter.floor()),
        Filter::Clamp => {
            if l > R::zero() {
                l
            } else {
                R::zero()
            }
        }
        Filter::ClampEps(_) => {
            let f = R::from_f64(filter.floor());
            if l > f { l } else { f }
        }
        Filter::Abs => l.abs(),
    }
}

/// The chain-rule weights of an element: w\[n\]\[c\] = ∂F_rc/∂x_{n,r}
/// (w_n = row n−1 of Dm⁻¹ for n ≥ 1, w_0 = −Σ w_n).
pub fn chain_weights<R: Real>(dm_inv: &[f64], d: usize) -> Vec<Vec<R>> {
    let mut w: Vec<Vec<R>> = vec![vec![R::zero(); d]; d + 1];
    for n in 1..=d {
        for c in 0..d {
            w[n][c] = R::from_f64(dm_inv[(n - 1) * d + c]);
            w[0][c] = w[0][c] - w[n][c];
        }
    }
    w
}

/// F = Ds Dm⁻¹ (row-major d×d) from node positions x (node-major, d per node).
pub fn deformation<R: Real>(x: &[R], w: &[Vec<R>], d: usize) -> Vec<R> {
    let mut f = vec![R::zero(); d * d];
    for r in 0..d {
        for c in 0..d {
            let mut acc = R::zero();
            for (n, wn) in w.iter().enumerate() {
                acc = acc + x[n * d + r] * wn[c];
            }
            f[r * d + c] = acc;
        }
    }
    f
}

/// g_e = m Bᵀ g_F and, if given, H_e = m Bᵀ H_F B (vec(F) column-major, x node-major).
pub fn chain_rule<R: Real>(
    w: &[Vec<R>],
    d: usize,
    measure: R,
    g_f: &[R],
    h_f: Option<&[R]>,
) -> (Vec<R>, Vec<R>) {
    let k = w.len();
    let n = k * d;
    let r2 = d * d;
    // B[(c·d + r), (node·d + r)] = w[node][c]
    let b_entry = |row: usize, col: usize| -> R {
        let (c, r) = (row / d, row % d);
        let (node, rr) = (col / d, col % d);
        if r == rr { w[node][c] } else { R::zero() }
    };
    let grad: Vec<R> = (0..n)
        .map(|col| (0..r2).fold(R::zero(), |a, row| a + b_entry(row, col) * g_f[row]) * measure)
        .collect();
    let hess = match h_f {
        None => Vec::new(),
        Some(h) => {
            // HB (r2 × n), then Bᵀ(HB)
            let mut hb = vec![R::zero(); r2 * n];
            for i in 0..r2 {
                for col in 0..n {
                    let mut acc = R::zero();
                    for j in 0..r2 {
                        let b = b_entry(j, col);
                        if b != R::zero() {
                            acc = acc + h[i * r2 + j] * b;
                        }
                    }
                    hb[i * n + col] = acc;
                }
            }
            let mut out = vec![R::zero(); n * n];
            for a in 0..n {
                for col in 0..n {
                    let mut acc = R::zero();
                    for i in 0..r2 {
                        let b = b_entry(i, a);
                        if b != R::zero() {
                            acc = acc + b * hb[i * n + col];
                        }
                    }
                    out[a * n + col] = acc * measure;
                }
            }
            out
        }
    };
    (grad, hess)
}

impl GenericEnergy {
    /// From a compiled IR and its parameter values (by index).
    pub fn new(ir: &DimIr, params: &[f64]) -> Self {
        let (eval, roots) = GraphEval::stretch(ir);
        GenericEnergy {
            graph: ir.graph.clone(),
            eval,
            roots,
            params: params.to_vec(),
            sign_symmetric: ir.sign_symmetric,
            dim: ir.dim as usize,
        }
    }

    /// The dimension (2 or 3).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Ψ(σ) only (`+∞` outside the domain).
    pub fn psi<R: Real>(&self, sigma: &[R], work: &mut Vec<R>) -> R {
        let mut out = vec![R::zero(); 1 + self.dim + self.dim * self.dim];
        self.eval
            .eval(&self.graph, sigma, &self.params, work, &mut out);
        let p = out[self.roots.psi];
        if p.to_f64().is_nan() {
            R::from_f64(f64::INFINITY)
        } else {
            p
        }
    }

    /// Ψ, ∂Ψ/∂σ and ∂²Ψ/∂σ².
    pub fn stretch<R: Real>(&self, sigma: &[R], work: &mut Vec<R>) -> StretchData<R> {
        let d = self.dim;
        let mut out = vec![R::zero(); 1 + d + d * d];
        self.eval
            .eval(&self.graph, sigma, &self.params, work, &mut out);
        StretchData {
            psi: out[self.roots.psi],
            grad: self.roots.grad.iter().map(|&k| out[k]).collect(),
            hess: self.roots.hess.iter().flatten().map(|&k| out[k]).collect(),
        }
    }

    /// Ψ(F) for a row-major d×d F (through the signed SVD).
    pub fn psi_f<R: Real>(&self, f: &[R], work: &mut Vec<R>) -> R {
        let (sigma, _, _) = signed_svd(f, self.dim);
        self.psi(&sigma, work)
    }

    /// Element energy, gradient and filtered Hessian (× measure) at node
    /// positions `x` (node-major) for rest data `dm_inv` (row-major d×d).
    pub fn element<R: Real>(
        &self,
        dm_inv: &[f64],
        measure: f64,
        x: &[R],
        filter: Filter,
    ) -> GenericEval<R> {
        let d = self.dim;
        let w = chain_weights::<R>(dm_inv, d);
        let f = deformation(x, &w, d);
        let (sigma, u, v) = signed_svd(&f, d);
        let mut work = Vec::new();
        let s = self.stretch(&sigma, &mut work);
        let m = R::from_f64(measure);
        let r2 = d * d;
        let n = (d + 1) * d;
        if !s.psi.is_finite() || s.psi.to_f64().is_nan() {
            return GenericEval {
                psi: R::from_f64(f64::INFINITY),
                grad: vec![R::zero(); n],
                hess: vec![R::zero(); n * n],
            };
        }
        // mode matrix U M Vᵀ as column-major vec, for M given by (row, col, value) entries
        let mode = |entries: &[(usize, usize, R)]| -> Vec<R> {
            let mut e = vec![R::zero(); r2];
            for c in 0..d {
                for r in 0..d {
                    let mut acc = R::zero();
                    for &(i, j, val) in entries {
                        acc = acc + u[r * d + i] * val * v[c * d + j];
                    }
                    e[c * d + r] = acc;
                }
            }
            e
        };
        // gradient: U diag(Ψ_σ) Vᵀ
        let diag: Vec<(usize, usize, R)> = (0..d).map(|i| (i, i, s.grad[i])).collect();
        let g_f = mode(&diag);
        // Hessian modes
        let mut h = vec![R::zero(); r2 * r2];
        let mut add = |lam: R, e: &[R]| {
            let l = filter_value(filter, lam);
            if l == R::zero() {
                return;
            }
            for i in 0..r2 {
                let li = l * e[i];
                for j in 0..r2 {
                    h[i * r2 + j] = h[i * r2 + j] + li * e[j];
                }
            }
        };
        let (avals, avecs) = sym_eigen(&s.hess, d);
        for k in 0..d {
            let ent: Vec<(usize, usize, R)> = (0..d).map(|i| (i, i, avecs[i * d + k])).collect();
            add(avals[k], &mode(&ent));
        }
        let tau = R::from_f64(R::EPS.cbrt());
        let half = R::from_f64(0.5);
        let rs = R::from_f64(std::f64::consts::FRAC_1_SQRT_2);
        let pairs: &[(usize, usize)] = if d == 2 {
            &[(0, 1)]
        } else {
            &[(1, 2), (2, 0), (0, 1)]
        };
        for &(i, j) in pairs {
            let (si, sj) = (sigma[i], sigma[j]);
            let big = if si.abs() > sj.abs() {
                si.abs()
            } else {
                sj.abs()
            };
            let (aii, ajj, aij) = (s.hess[i * d + i], s.hess[j * d + j], s.hess[i * d + j]);
            let flip = if (si - sj).abs() <= tau * big {
                half * (aii + ajj) - aij
            } else {
                (s.grad[i] - s.grad[j]) / (si - sj)
            };
            let twist = if self.sign_symmetric && (si + sj).abs() <= tau * big {
                half * (aii + ajj) + aij
            } else {
                (s.grad[i] + s.grad[j]) / (si + sj)
            };
            add(twist, &mode(&[(j, i, rs), (i, j, -rs)]));
            add(flip, &mode(&[(j, i, rs), (i, j, rs)]));
        }
        let (grad, hess) = chain_rule(&w, d, m, &g_f, Some(&h));
        GenericEval {
            psi: s.psi * m,
            grad,
            hess,
        }
    }
}
