//! Ψ(σ) in double-double, straight from the CAS graph of a `.psi` source
//! (`ecc_dsl::compile`), with the graph's own real-valued semantics
//! (`ecc_dsl::Node::Pow`): integer exponents are exact powers, p/q with odd
//! q is the real root (defined for negative bases), 1/2 is the square
//! root, anything else is e^(e·ln b) (NaN for a negative base). Only Ψ
//! itself is read from the graph — none of the compiler's derivatives,
//! divided differences, limits or generated code.

use ecc_dsl::{DimIr, Id, Node, Sym};

use super::dd::Dd;

/// An exponent known at compile time: p/q.
#[derive(Clone, Copy)]
struct Ratio {
    p: i64,
    q: i64,
}

/// One energy's Ψ graph for one dimension, with parameter values.
pub struct PsiGraph {
    ir: DimIr,
    order: Vec<Id>,
    params: Vec<Dd>,
    /// Per node: its value if it is a `Num`.
    nums: Vec<Option<Dd>>,
    /// Per node: the exponent as a small fraction if it is a `Num`.
    ratios: Vec<Option<Ratio>>,
}

fn decimal(text: String) -> Dd {
    Dd::from_decimal_integer(&text).unwrap_or(Dd::NAN)
}

impl PsiGraph {
    /// Compile `source` for dimension `dim` with parameter overrides
    /// (`None` if it does not compile there).
    pub fn new(source: &str, dim: u8, overrides: &[(&str, f64)]) -> Option<PsiGraph> {
        let module = ecc_dsl::compile(source, "reference").ok()?;
        let ir = module.dim(dim)?.clone();
        let params = module
            .params
            .iter()
            .map(|p| {
                let v = overrides
                    .iter()
                    .find(|(n, _)| *n == p.name)
                    .map_or(p.default, |(_, v)| *v);
                Dd::from_f64(v)
            })
            .collect();
        let order = ir.graph.reachable(&[ir.psi]);
        let mut nums = vec![None; ir.graph.len()];
        let mut ratios = vec![None; ir.graph.len()];
        for &id in &order {
            if let Node::Num(r) = ir.graph.get(id) {
                let (n, d) = (r.numer().to_string(), r.denom().to_string());
                ratios[id.index()] = n
                    .parse::<i64>()
                    .ok()
                    .zip(d.parse::<i64>().ok())
                    .map(|(p, q)| Ratio { p, q });
                nums[id.index()] = Some(decimal(n) / decimal(d));
            }
        }
        Some(PsiGraph {
            ir,
            order,
            params,
            nums,
            ratios,
        })
    }

    /// The compiled IR (flags such as `sign_symmetric`, `barrier`).
    pub fn ir(&self) -> &DimIr {
        &self.ir
    }

    /// Ψ at the signed singular values σ (`dim` entries). NaN outside the
    /// energy's domain (log of a negative number, …), ±∞ at poles.
    pub fn psi(&self, sigma: &[Dd]) -> Dd {
        let g = &self.ir.graph;
        let i1 = sigma.iter().fold(Dd::ZERO, |s, x| s + *x);
        let i2 = sigma.iter().fold(Dd::ZERO, |s, x| s + *x * *x);
        let i3 = sigma.iter().fold(Dd::ONE, |s, x| s * *x);
        let mut v = vec![Dd::NAN; g.len()];
        for &id in &self.order {
            let x = match g.get(id) {
                Node::Num(_) => self.nums[id.index()].unwrap_or(Dd::NAN),
                Node::Sym(s) => match *s {
                    Sym::I1 => i1,
                    Sym::I2 => i2,
                    Sym::I3 => i3,
                    Sym::Sigma(k) => sigma.get(k as usize).copied().unwrap_or(Dd::NAN),
                    Sym::Param(k) => self.params.get(k as usize).copied().unwrap_or(Dd::NAN),
                    // Isotropic Ψ only: fibre leaves never occur here.
                    Sym::I4 | Sym::I5 | Sym::SignI4 => Dd::NAN,
                },
                Node::Add(c) => c.iter().fold(Dd::ZERO, |s, k| s + v[k.index()]),
                Node::Mul(c) => c.iter().fold(Dd::ONE, |s, k| s * v[k.index()]),
                Node::Pow([b, e]) => pow(v[b.index()], v[e.index()], self.ratios[e.index()]),
                Node::Log(a) => v[a.index()].ln(),
                Node::Exp(a) => v[a.index()].exp(),
            };
            v[id.index()] = x;
        }
        v[self.ir.psi.index()]
    }
}

/// b^e with the graph's semantics.
fn pow(b: Dd, e: Dd, ratio: Option<Ratio>) -> Dd {
    if let Some(Ratio { p, q }) = ratio {
        if q == 1 {
            return b.powi(p);
        }
        if p == 1 && q == 2 {
            return b.sqrt();
        }
        if q % 2 == 1 {
            let r = real_pow(b.abs(), e);
            return if b.hi < 0.0 && p % 2 != 0 { -r } else { r };
        }
    }
    real_pow(b, e)
}

/// b^e for b ≥ 0 (NaN for b < 0), as f64's `powf` at 0.
fn real_pow(b: Dd, e: Dd) -> Dd {
    if b.hi == 0.0 {
        return Dd::from_f64(0f64.powf(e.hi));
    }
    if b.hi < 0.0 {
        return Dd::NAN;
    }
    (e * b.ln()).exp()
}
