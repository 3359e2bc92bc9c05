//! Nodes of the expression DAG.

use num_rational::BigRational;
use num_traits::ToPrimitive;

/// Index of a node in a [`Graph`](super::Graph). Children always have smaller ids
/// than their parents.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

impl Id {
    /// The index as `usize`.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A leaf symbol.
///
/// The derived order (I1 < I2 < I3 < σ0 < σ1 < σ2 < params < I4 < I5 <
/// sign(I4)) is the order the canonical printer uses inside products. The
/// fibre symbols come last so that adding them left every isotropic
/// energy's canonical form unchanged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sym {
    /// I1 = tr S = Σ σi.
    I1,
    /// I2 = ‖F‖² = Σ σi².
    I2,
    /// I3 = det F = Π σi.
    I3,
    /// σ_k, the signed singular value k (0-based; printed `s{k+1}`).
    Sigma(u8),
    /// Parameter number k of the energy (printed by name).
    Param(u16),
    /// I4 = aᵀ S a, the fibre invariant through the polar stretch S
    /// (`ecc_runtime::fibre`); only in a fibre part ψ(I4, I5).
    I4,
    /// I5 = ‖F a‖² = aᵀ C a; only in a fibre part ψ(I4, I5).
    I5,
    /// sign(I4): +1 for I4 > 0, −1 otherwise (HOBAK's convention). A leaf
    /// whose derivative is 0 everywhere: it is piecewise constant, and ψ
    /// jumps where it switches (anisotropic ARAP's published energy does).
    SignI4,
}

/// One node of the DAG. Constructed only through [`Graph`](super::Graph), whose
/// smart constructors keep every node in canonical form:
///
/// * `Add` / `Mul` have at least two children, are flattened (no `Add` child of
///   an `Add`, no `Mul` child of a `Mul`), hold at most one `Num` child (the
///   constant term / coefficient, stored first; never 0 in a sum, never 1 in a
///   product) and the other children sorted by id with like terms / powers
///   already collected;
/// * `Pow([base, exp])` never has exponent 0 or 1, and a `Num` base only when the
///   power is not an exact rational;
/// * `Log` / `Exp` never wrap their inverse.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// An exact rational constant.
    Num(BigRational),
    /// A leaf symbol.
    Sym(Sym),
    /// A sum.
    Add(Vec<Id>),
    /// A product.
    Mul(Vec<Id>),
    /// `[base, exponent]`: base ^ exponent.
    ///
    /// Real-valued semantics (what [`Tape`](super::Tape) implements): an
    /// integer exponent is an exact power (`powi`); a rational exponent p/q
    /// with odd q is the real power, defined for negative bases
    /// (`(-8)^(1/3) = -2`, `(-8)^(2/3) = 4`); `1/2` is `sqrt`; any other
    /// exponent is `powf` (NaN for a negative base).
    Pow([Id; 2]),
    /// Natural logarithm.
    Log(Id),
    /// Exponential.
    Exp(Id),
}

impl Node {
    /// The constant as `f64`, if this is a `Num`.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Node::Num(r) => Some(r.to_f64().unwrap_or(f64::NAN)),
            _ => None,
        }
    }

    /// The children, in storage order.
    pub fn children(&self) -> &[Id] {
        match self {
            Node::Num(_) | Node::Sym(_) => &[],
            Node::Add(c) | Node::Mul(c) => c,
            Node::Pow(be) => be,
            Node::Log(x) | Node::Exp(x) => std::slice::from_ref(x),
        }
    }
}
