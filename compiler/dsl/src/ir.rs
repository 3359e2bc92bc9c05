//! The IR contract: what compiling an energy produces (`ecc_dsl::compile(source, name)
//! -> Result<Module, Diagnostics>` for every dimension that applies,
//! `ecc_dsl::compile_dim(source, name, dim) -> Result<DimIr, Diagnostics>` for one), for code generation,
//! the run-time interpreter and reports.
//!
//! All [`Id`]s in a [`DimIr`] index into that `DimIr`'s own [`Graph`]. Leaves
//! are `Num` (exact rationals) and `Sym` (`Sigma(k)`, `I1`, `I2`, `I3`,
//! `Param(k)`); a consumer computes I1 = Σσ, I2 = Σσ², I3 = Πσ from the signed
//! singular values σ first, then evaluates the graph.
//!
//! Pair slots follow `ecc_runtime::spectral`: 2D slot 0 = (0, 1); 3D slot k is
//! the twist/flip about axis k, i.e. pair (1, 2), (2, 0), (0, 1).

use crate::cas::{Graph, Id};
use crate::span::Span;

/// The result of compiling one source text.
#[derive(Clone, Debug)]
pub struct Module {
    /// The formula text as given.
    pub source: String,
    /// The name given to `compile` (used in reports).
    pub name: String,
    /// Declared parameters in declaration order; `Sym::Param(k)` is `params[k]`.
    pub params: Vec<ParamDecl>,
    /// One entry per dimension the energy compiles for (2 and/or 3), ascending.
    pub dims: Vec<DimIr>,
    /// Dimensions not compiled and why (e.g. "uses s3", "declared dim 3").
    pub skipped: Vec<(u8, String)>,
}

impl Module {
    /// The IR for dimension `dim`, if the energy was compiled for it.
    pub fn dim(&self, dim: u8) -> Option<&DimIr> {
        self.dims.iter().find(|d| d.dim == dim)
    }

    /// Parameter defaults in index order.
    pub fn param_defaults(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.default).collect()
    }
}

/// A `param name = default` declaration.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamDecl {
    /// The parameter name.
    pub name: String,
    /// Its default value (the constant expression evaluated in f64).
    pub default: f64,
    /// The declaration's span.
    pub span: Span,
}

/// How the energy is differentiated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Path {
    /// Ψ is a function of I1, I2, I3 only: Smith et al. 2019 (eqs. 22–27, App. D).
    Invariant,
    /// Ψ uses a stretch s1..s3 somewhere: Zhu 2020 (divided differences).
    Stretch,
}

/// Derivatives of Ψ with respect to the invariants (invariant path only).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InvariantDerivs {
    /// [Ψ1, Ψ2, Ψ3] = [∂Ψ/∂I1, ∂Ψ/∂I2, ∂Ψ/∂I3].
    pub d1: [Id; 3],
    /// [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23].
    pub d2: [Id; 6],
}

/// The compiled energy for one dimension.
#[derive(Clone, Debug)]
pub struct DimIr {
    /// 2 or 3.
    pub dim: u8,
    /// The expression DAG all ids below index into.
    pub graph: Graph,
    /// Invariant or stretch path.
    pub path: Path,
    /// Ψ.
    pub psi: Id,
    /// Invariant path: Ψ's derivatives in I1, I2, I3 (expressions in I's, σ's, params).
    pub d_inv: Option<InvariantDerivs>,
    /// ∂Ψ/∂σ_i (`dim` entries), both paths.
    pub d_sigma: Vec<Id>,
    /// ∂²Ψ/∂σ_i∂σ_j (`dim × dim`, symmetric; Appendix D's A on the invariant path).
    pub h_sigma: Vec<Vec<Id>>,
    /// What generated code computes, specialised from what the CAS proved.
    pub spectral: SpectralIr,
    /// Ψ → +∞ as det F → 0⁺ (a log or a negative power of something that
    /// vanishes there, not cancelled; checked by growth): the solver must
    /// keep det F > 0. Finite powers such as `I3^(1/3)` are not barriers.
    pub barrier: bool,
    /// Ψ and its active domain conditions depend only on I2 and I3 (no I1,
    /// no stretch): computable without an SVD.
    pub svd_free: bool,
    /// Ψ is unchanged by (σi, σj) → (−σj, −σi) for every pair (proved; false if unknown).
    pub sign_symmetric: bool,
    /// Every off-diagonal of A is proved ≡ 0: `spectral.scale` is `Diagonal`.
    pub decoupled: bool,
    /// Isotropy of a stretch energy was only checked numerically (not proved).
    pub isotropy_numeric_only: bool,
    /// Distinct denominators and log arguments found in the spectral
    /// expressions (σi+σj, I3, σi, …), for reports.
    pub singularities: Vec<Id>,
    /// The domain of Ψ *as written*, recorded while lowering before any
    /// simplification (`exp(log(I3))` is `I3` only where I3 > 0): Ψ = +∞
    /// wherever a condition fails. Deduplicated; conditions the CAS proves
    /// always true (`exp(x) > 0`, `I2 + 1 > 0`) are not listed.
    pub domain: Vec<DomainGuard>,
    /// The fibre part ψ(I4, I5) of an energy with `fiber a` (Ψ = Ψ_iso + ψ;
    /// everything above describes Ψ_iso); `None` without `fiber`.
    pub fibre: Option<FibreIr>,
}

/// Which fibre invariants ψ reads, decided symbolically (mirrors
/// `ecc_runtime::FibreUse`, which this crate does not depend on).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FibreUses {
    /// ψ is constant.
    None,
    /// ψ reads I4 (or sign(I4)) only.
    I4,
    /// ψ reads I5 only.
    I5,
    /// ψ reads both.
    Both,
}

/// The fibre part ψ(I4, I5) of one dimension: its own graph, whose leaves
/// are `Num`, `Sym::I4`, `Sym::I5`, `Sym::SignI4` and `Sym::Param(k)` (the
/// energy's shared parameters).
#[derive(Clone, Debug)]
pub struct FibreIr {
    /// The direction's name as declared (`fiber a`).
    pub direction: String,
    /// The expression DAG the ids below index into.
    pub graph: Graph,
    /// ψ.
    pub psi: Id,
    /// ∂ψ/∂I4 (sign(I4) has derivative 0).
    pub d4: Id,
    /// ∂ψ/∂I5.
    pub d5: Id,
    /// ∂²ψ/∂I4².
    pub d44: Id,
    /// ∂²ψ/∂I4∂I5.
    pub d45: Id,
    /// ∂²ψ/∂I5².
    pub d55: Id,
    /// Which invariants ψ reads.
    pub uses: FibreUses,
    /// d4, d44 and d45 are identically 0: the closed-form eigensystem of
    /// I5 (Kim, de Goes & Iben 2019 §4.1 eq. 7 through the chain rule;
    /// `ecc_runtime::fibre::point`, P3–P5)
    /// applies everywhere, even if ψ reads sign(I4).
    pub closed_form: bool,
    /// ψ's domain as written (same rules as [`DimIr::domain`]): ψ = +∞
    /// wherever an active condition fails.
    pub domain: Vec<DomainGuard>,
}

impl FibreIr {
    /// The domain conditions every evaluator must test.
    pub fn active_guards(&self) -> impl Iterator<Item = &DomainGuard> {
        self.domain.iter().filter(|g| !g.enforced_by_psi)
    }

    /// [ψ, d4, d5, d44, d45, d55].
    pub fn roots(&self) -> [Id; 6] {
        [self.psi, self.d4, self.d5, self.d44, self.d45, self.d55]
    }
}

impl DimIr {
    /// The domain conditions every evaluator must test (those Ψ's own
    /// evaluation does not already turn into a non-finite value).
    pub fn active_guards(&self) -> impl Iterator<Item = &DomainGuard> {
        self.domain.iter().filter(|g| !g.enforced_by_psi)
    }
}

/// What a written operation needs of its argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DomainCond {
    /// `x > 0`: `log(x)`, `x^e` with a non-constant exponent, `x^(p/q)` with
    /// q even and p < 0.
    Positive,
    /// `x ≥ 0`: `sqrt(x)`, `x^(p/q)` with q even and p > 0.
    NonNegative,
    /// `x ≠ 0`: a division by x, `x^(p/q)` with p < 0 and q odd.
    NonZero,
}

impl DomainCond {
    /// Whether `x` satisfies the condition (NaN never does).
    #[inline]
    pub fn holds(self, x: f64) -> bool {
        match self {
            DomainCond::Positive => x > 0.0,
            DomainCond::NonNegative => x >= 0.0,
            DomainCond::NonZero => x.abs() > 0.0,
        }
    }

    /// The relation in mathematical notation: `>`, `≥` or `≠` (against 0).
    pub fn relation(self) -> &'static str {
        match self {
            DomainCond::Positive => ">",
            DomainCond::NonNegative => "≥",
            DomainCond::NonZero => "≠",
        }
    }
}

/// One condition of Ψ's domain: `cond` holds for the value of `arg`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DomainGuard {
    /// The argument (an expression in I's, σ's and parameters).
    pub arg: Id,
    /// What it must satisfy.
    pub cond: DomainCond,
    /// Proved redundant for evaluators: the node that needs the condition
    /// (`log(arg)`, `arg^e`) is still part of Ψ, so Ψ evaluates to NaN or
    /// ±∞ (reported +∞) wherever it fails (a log barrier's `log(J)`).
    /// Such conditions are listed in reports but not re-tested.
    pub enforced_by_psi: bool,
}

/// The stretch-space eigen data that generated code evaluates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpectralIr {
    /// Ψ_σi.
    pub grad: Vec<Id>,
    /// The scaling block A.
    pub scale: ScaleIr,
    /// λ_twist = (Ψi + Ψj)/(σi + σj), one per pair slot.
    pub twist: Vec<PairIr>,
    /// λ_flip = (Ψi − Ψj)/(σi − σj), one per pair slot.
    pub flip: Vec<PairIr>,
    /// What each twist does on σi + σj = 0, one per pair slot.
    pub twist_kind: Vec<PairKind>,
    /// What each flip does on σi = σj, one per pair slot.
    pub flip_kind: Vec<PairKind>,
}

/// What a divided difference does on its singular set (σi = σj for a flip,
/// σi = −σj for a twist), decided by the CAS at compile time: the numerator
/// (Ψi ∓ Ψj, or Ψ1 for the invariant-path twist) with σj := ±σi substituted
/// is simplified exactly; ≡ 0 proves the singularity removable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PairKind {
    /// No division at all (invariant-path flips 2Ψ2 ∓ c_ij Ψ3; twists with Ψ1 ≡ 0).
    Regular,
    /// The numerator vanishes identically on the set: 0/0 with a finite limit,
    /// which every back end uses there (`PairIr::Guarded`, or an exact
    /// quotient when the energy is rational).
    Removable,
    /// The numerator does not vanish identically there (or that could not be
    /// decided): a genuine pole of the energy. Every back end gives +∞ exactly
    /// on the set (never NaN) and the quotient elsewhere.
    Pole,
}

/// The scaling block A = ∂²Ψ/∂σ².
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScaleIr {
    /// Off-diagonals proved ≡ 0: A = diag(a).
    Diagonal(Vec<Id>),
    /// A general symmetric A, row-major (`a[i][j] == a[j][i]`).
    Full(Vec<Vec<Id>>),
}

/// A twist or flip eigenvalue expression for one pair slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairIr {
    /// Singularity-free after exact division, or a genuine singularity of the
    /// energy left visible (ARAP's 2Ψ1/(σi+σj); see [`PairKind::Pole`]).
    Exact(Id),
    /// Use `direct` unless |den| is tiny, then `limit`
    /// ((A_ii + A_jj)/2 ∓ A_ij); `den` is σi − σj (flip) or σi + σj (twist).
    ///
    /// `limit` is exact on the hyperplane and off by O(|den|²) near it (for a
    /// twist without sign symmetry it carries the first-order correction
    /// −(∂i + ∂j)(A_ii + 2A_ij + A_jj)·den/8, see `ecc_runtime::divided`), while
    /// `direct` loses about ε·|Ψ_σ|/|den| to cancellation, so a switch at
    /// |den| ≈ ε^{1/3}·max(|σi|, |σj|) balances the two errors.
    Guarded {
        /// The divided difference as written.
        direct: Id,
        /// Its limit on the hyperplane `den = 0` (corrected to second order off it).
        limit: Id,
        /// The denominator.
        den: Id,
    },
}
