//! [`InterpEnergy`]: an [`Energy`] evaluated from a compiled [`DimIr`] at run time.
//!
//! Per point, one tape evaluates Ψ and the *generic* derivatives of the IR and
//! hands them to the runtime's generic formulas:
//!
//! * invariant path: Ψ, d1 = [Ψ1, Ψ2, Ψ3], d2 = [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23]
//!   → [`spectral_from_invariants`] (Smith et al. 2019 eqs. 22–27, App. D);
//! * stretch path: Ψ, ∂Ψ/∂σ, ∂²Ψ/∂σ² → [`spectral_from_stretch`] (Zhu 2020 §4,
//!   divided differences with the runtime's limit switch).
//!
//! This deliberately bypasses the CAS-specialised [`ecc_dsl::SpectralIr`] that
//! generated code evaluates, so generated code and the interpreter check each
//! other. Only what the CAS *decided* about each twist on σi + σj = 0
//! ([`ecc_dsl::PairKind`]) is taken from it: a pole gives +∞ there, a removable
//! twist its limit — for a sign-symmetric Ψ the runtime's (A_ii + A_jj)/2 + A_ij,
//! otherwise the IR's second-order corrected limit, evaluated by the same tape
//! ([`ecc_runtime::divided::TwistRule`]). Ψ = NaN (e.g. log of a negative
//! number) is reported as +∞: the point is outside the energy's domain, as
//! is every point where a condition of the domain *as written* fails
//! ([`DimIr::active_guards`]: `exp(log(I3))` is +∞ for I3 ≤ 0 although the
//! CAS simplified it to I3). The guards' arguments are extra outputs of the
//! same tapes, so they cost one comparison each on values already computed.

use ecc_dsl::{DimIr, DomainCond, PairIr, PairKind, Path, Sym};
use ecc_runtime::divided::TwistRule;
use ecc_runtime::invariants::spectral_from_invariants_with;
use ecc_runtime::stretch::spectral_from_stretch_with;
use ecc_runtime::{Energy, EnergyInfo, ParamError, Spectral};

use crate::error::BuildError;
use crate::tape::Tape;

/// Outputs of the full tape: Ψ, then 9 invariant derivatives or D + D² stretch
/// ones, then up to 3 removable-twist limits.
const MAX_OUT: usize = 1 + 3 + 9 + 3;

/// Room for that many domain guards' arguments after them on the stack
/// (beyond, a buffer is allocated per call).
const MAX_GUARD_OUT: usize = 16;

/// How the twist of one pair slot is resolved on σi + σj = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
enum TwistSpec {
    /// A fixed rule (regular, sign-symmetric limit, pole).
    Fixed(TwistRule),
    /// Removable without sign symmetry: the limit is tape output `k`.
    LimitAt(usize),
}

/// An energy evaluated by interpreting its CAS graph (no code generation, no rebuild).
#[derive(Clone, Debug)]
pub struct InterpEnergy<const D: usize> {
    name: String,
    path: Path,
    /// Ψ only (`psi`, the line-search path).
    psi_tape: Tape,
    /// Ψ and the generic derivatives (`spectral`).
    full_tape: Tape,
    psi_frozen: Vec<f64>,
    full_frozen: Vec<f64>,
    param_names: Vec<String>,
    param_values: Vec<f64>,
    info: EnergyInfo,
    decoupled: bool,
    twist: [TwistSpec; 3],
    /// The domain conditions to test: the guards' arguments are the last
    /// `guards.len()` outputs of both tapes.
    guards: Vec<DomainCond>,
}

/// Ψ values that mean "outside the domain" — NaN (log of a negative
/// number), ±∞ (a pole such as I2/I3 at I3 = −0, or overflow) — are
/// reported as +∞, as generated code does.
#[inline]
fn domain(psi: f64) -> f64 {
    if psi.is_finite() { psi } else { f64::INFINITY }
}

/// [I1, I2, I3] of the first D entries of σ.
#[inline]
fn invariants<const D: usize>(s: &[f64; D]) -> ([f64; 3], [f64; 3]) {
    let mut s3 = [0.0; 3];
    s3[..D].copy_from_slice(s);
    let i1 = s.iter().sum();
    let i2 = s.iter().map(|x| x * x).sum();
    let i3 = s.iter().product();
    (s3, [i1, i2, i3])
}

impl<const D: usize> InterpEnergy<D> {
    /// Compile `ir` (which must be for dimension `D`) with parameter values
    /// `params` (by index, as declared; see [`ecc_dsl::Module::param_defaults`]).
    pub fn new(name: &str, ir: &DimIr, params: &[f64]) -> Result<Self, BuildError> {
        if D != 2 && D != 3 {
            return Err(BuildError::UnsupportedDim { dim: D });
        }
        if usize::from(ir.dim) != D {
            return Err(BuildError::DimMismatch {
                ir: ir.dim,
                requested: D,
            });
        }
        let g = &ir.graph;
        let param_names = g.param_names().to_vec();
        check_params(&param_names, params)?;
        let mut roots = vec![ir.psi];
        match ir.path {
            Path::Invariant => {
                let d = ir.d_inv.as_ref().ok_or(BuildError::MissingDerivatives {
                    what: "invariant derivatives (d_inv)",
                })?;
                roots.extend_from_slice(&d.d1);
                roots.extend_from_slice(&d.d2);
            }
            Path::Stretch => {
                let rows_ok = ir.h_sigma.len() == D && ir.h_sigma.iter().all(|r| r.len() == D);
                if ir.d_sigma.len() != D || !rows_ok {
                    return Err(BuildError::MissingDerivatives {
                        what: "stretch derivatives (d_sigma, h_sigma)",
                    });
                }
                roots.extend_from_slice(&ir.d_sigma);
                roots.extend(ir.h_sigma.iter().flatten().copied());
            }
        }
        let twist = twist_specs(ir, &mut roots)?;
        let guards: Vec<DomainCond> = ir.active_guards().map(|d| d.cond).collect();
        let args: Vec<ecc_dsl::Id> = ir.active_guards().map(|d| d.arg).collect();
        roots.extend_from_slice(&args);
        let mut psi_roots = vec![ir.psi];
        psi_roots.extend_from_slice(&args);
        // Trust `svd_free` only when Ψ really reads neither I1 nor σ (nor do
        // the domain conditions it tests).
        let svd_free = ir.svd_free
            && [ir.psi]
                .iter()
                .chain(&args)
                .all(|&x| !g.uses_sigma(x) && !g.may_depend(x, Sym::I1));
        let psi_tape = Tape::compile(g, &psi_roots)?;
        let full_tape = Tape::compile(g, &roots)?;
        let psi_frozen = psi_tape.freeze(params);
        let full_frozen = full_tape.freeze(params);
        Ok(InterpEnergy {
            name: name.to_string(),
            path: ir.path,
            psi_tape,
            full_tape,
            psi_frozen,
            full_frozen,
            param_names,
            param_values: params.to_vec(),
            info: EnergyInfo {
                barrier: ir.barrier,
                svd_free_psi: svd_free,
            },
            decoupled: ir.decoupled,
            twist,
            guards,
        })
    }

    /// The differentiation path of the IR this energy was built from.
    pub fn path(&self) -> Path {
        self.path
    }

    /// The per-point tape computing Ψ and the generic derivatives (for cost reports).
    pub fn full_tape(&self) -> &Tape {
        &self.full_tape
    }

    fn psi_at(&self, sigma: [f64; 3], inv: [f64; 3]) -> f64 {
        with_outputs(self.psi_tape.n_outputs(), |out| {
            self.psi_tape.eval(&self.psi_frozen, sigma, inv, out);
            self.checked_psi(out)
        })
    }

    /// The spectral data from the full tape's outputs at σ.
    fn spectral_from(&self, sigma: &[f64; D], out: &[f64]) -> Spectral<D> {
        let psi = self.checked_psi(out);
        if psi == f64::INFINITY {
            return Spectral::infinite();
        }
        let rules = self.twist.map(|t| match t {
            TwistSpec::Fixed(r) => r,
            TwistSpec::LimitAt(k) => TwistRule::Removable(out[k]),
        });
        match self.path {
            Path::Invariant => {
                let d1 = [out[1], out[2], out[3]];
                let d2 = std::array::from_fn(|k| out[4 + k]);
                spectral_from_invariants_with(sigma, psi, d1, d2, self.decoupled, rules)
            }
            Path::Stretch => {
                let grad = std::array::from_fn(|i| out[1 + i]);
                let hess = std::array::from_fn(|i| std::array::from_fn(|j| out[1 + D + i * D + j]));
                spectral_from_stretch_with(sigma, psi, grad, hess, rules)
            }
        }
    }

    /// Ψ = `out[0]` as written: +∞ when it is not finite or a domain
    /// condition on the last outputs fails.
    fn checked_psi(&self, out: &[f64]) -> f64 {
        let args = &out[out.len() - self.guards.len()..];
        if self.guards.iter().zip(args).all(|(c, &x)| c.holds(x)) {
            domain(out[0])
        } else {
            f64::INFINITY
        }
    }
}

/// Run `f` on a zeroed output buffer of length `n`: on the stack, exactly
/// as large as before domain guards existed when there are none.
#[inline]
fn with_outputs<R>(n: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if n == 1 {
        f(&mut [0.0])
    } else if n <= MAX_OUT {
        f(&mut [0.0; MAX_OUT][..n])
    } else if n <= MAX_OUT + MAX_GUARD_OUT {
        f(&mut [0.0; MAX_OUT + MAX_GUARD_OUT][..n])
    } else {
        f(&mut vec![0.0; n])
    }
}

/// The twist rule of each pair slot from the IR's [`PairKind`]s; the limits
/// of removable twists without sign symmetry are appended to `roots` (their
/// tape output index is recorded). Unused slots are [`TwistRule::Regular`].
fn twist_specs(ir: &DimIr, roots: &mut Vec<ecc_dsl::Id>) -> Result<[TwistSpec; 3], BuildError> {
    let sp = &ir.spectral;
    if sp.twist_kind.len() != sp.twist.len() || sp.twist.len() > 3 {
        return Err(BuildError::MissingDerivatives {
            what: "twist kinds (spectral.twist_kind)",
        });
    }
    let mut specs = [TwistSpec::Fixed(TwistRule::Regular); 3];
    for (k, (pair, kind)) in sp.twist.iter().zip(&sp.twist_kind).enumerate() {
        specs[k] = match kind {
            PairKind::Regular => TwistSpec::Fixed(TwistRule::Regular),
            PairKind::Pole => TwistSpec::Fixed(TwistRule::Pole),
            PairKind::Removable if ir.sign_symmetric => TwistSpec::Fixed(TwistRule::SignSymmetric),
            PairKind::Removable => {
                let limit = match *pair {
                    PairIr::Guarded { limit, .. } => limit,
                    PairIr::Exact(q) => q,
                };
                roots.push(limit);
                TwistSpec::LimitAt(roots.len() - 1)
            }
        };
    }
    Ok(specs)
}

impl<const D: usize> Energy<D> for InterpEnergy<D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn psi(&self, sigma: &[f64; D]) -> f64 {
        let (s, inv) = invariants(sigma);
        self.psi_at(s, inv)
    }

    fn spectral(&self, sigma: &[f64; D]) -> Spectral<D> {
        let (s, inv) = invariants(sigma);
        with_outputs(self.full_tape.n_outputs(), |out| {
            self.full_tape.eval(&self.full_frozen, s, inv, out);
            self.spectral_from(sigma, out)
        })
    }

    fn info(&self) -> EnergyInfo {
        self.info
    }

    fn psi_i2_i3(&self, i2: f64, i3: f64) -> Option<f64> {
        if !self.info.svd_free_psi {
            return None;
        }
        Some(self.psi_at([f64::NAN; 3], [f64::NAN, i2, i3]))
    }

    fn params(&self) -> Vec<(String, f64)> {
        self.param_names
            .iter()
            .cloned()
            .zip(self.param_values.iter().copied())
            .collect()
    }

    fn set_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        let k = param_slot(&self.param_names, name, value)?;
        self.param_values[k] = value;
        self.psi_frozen = self.psi_tape.freeze(&self.param_values);
        self.full_frozen = self.full_tape.freeze(&self.param_values);
        Ok(())
    }
}

/// The slot of parameter `name` among `names` for a new `value`: unknown
/// names and non-finite values are [`ParamError`]s (shared by the isotropic
/// and the fibre energies' setters).
pub(crate) fn param_slot(names: &[String], name: &str, value: f64) -> Result<usize, ParamError> {
    let Some(k) = names.iter().position(|n| n == name) else {
        return Err(ParamError::Unknown {
            name: name.to_string(),
            known: names.to_vec(),
        });
    };
    if !value.is_finite() {
        return Err(ParamError::NotFinite {
            name: name.to_string(),
            value,
        });
    }
    Ok(k)
}

/// The parameter values a tape is built with: one per declared name, all
/// finite (shared by [`InterpEnergy`] and the fibre part's constructor).
pub(crate) fn check_params(param_names: &[String], params: &[f64]) -> Result<(), BuildError> {
    if params.len() != param_names.len() {
        return Err(BuildError::ParamCount {
            expected: param_names.len(),
            found: params.len(),
        });
    }
    if let Some((k, &v)) = params.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(BuildError::Param(ParamError::NotFinite {
            name: param_names[k].clone(),
            value: v,
        }));
    }
    Ok(())
}
