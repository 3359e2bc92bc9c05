//! [`InterpFibre`]: the fibre part ψ(I4, I5) of a compiled energy
//! ([`ecc_dsl::FibreIr`]) as an [`ecc_runtime::FibreEnergy`], evaluated from
//! its CAS graph at run time.
//!
//! One tape computes [ψ, ψ4, ψ5, ψ44, ψ45, ψ55] and the arguments of ψ's
//! active domain conditions. A fibre graph has no σ, so the tape reads I4,
//! I5 and sign(I4) from the σ input registers (see `tape::lower`). ψ is +∞
//! (with zero derivatives) where it is not finite or a condition fails, as
//! for Ψ ([`crate::InterpEnergy`]). The parameters are the energy's shared
//! ones; the isotropic part Ψ_iso is the [`crate::InterpEnergy`] of the same
//! [`DimIr`].

use ecc_dsl::{DimIr, DomainCond, FibreUses, Module, sign_i4};
use ecc_runtime::{FibreDerivs, FibreEnergy, FibreUse, ParamError};

use crate::error::{BuildError, LoadError};
use crate::load::param_values;
use crate::tape::Tape;

/// A fibre energy ψ(I4, I5) evaluated by interpreting its CAS graph.
#[derive(Clone, Debug)]
pub struct InterpFibre<const D: usize> {
    name: String,
    tape: Tape,
    frozen: Vec<f64>,
    param_names: Vec<String>,
    param_values: Vec<f64>,
    /// The conditions to test: their arguments are outputs 6.. of the tape.
    guards: Vec<DomainCond>,
    uses: FibreUse,
}

/// The runtime's [`FibreUse`] for the compiler's [`FibreUses`].
pub fn fibre_use(u: FibreUses) -> FibreUse {
    match u {
        FibreUses::None => FibreUse::None,
        FibreUses::I4 => FibreUse::I4,
        FibreUses::I5 => FibreUse::I5,
        FibreUses::Both => FibreUse::Both,
    }
}

impl<const D: usize> InterpFibre<D> {
    /// The fibre part of `ir` (for dimension `D`) with parameter values
    /// `params` (by index, as declared); `None` when `ir` has no fibre.
    pub fn new(name: &str, ir: &DimIr, params: &[f64]) -> Result<Option<Self>, BuildError> {
        if usize::from(ir.dim) != D {
            return Err(BuildError::DimMismatch {
                ir: ir.dim,
                requested: D,
            });
        }
        let Some(f) = &ir.fibre else {
            return Ok(None);
        };
        let param_names = f.graph.param_names().to_vec();
        crate::energy::check_params(&param_names, params)?;
        let mut roots = f.roots().to_vec();
        roots.extend(f.active_guards().map(|d| d.arg));
        let tape = Tape::compile(&f.graph, &roots)?;
        Ok(Some(InterpFibre {
            name: name.to_string(),
            frozen: tape.freeze(params),
            tape,
            param_names,
            param_values: params.to_vec(),
            guards: f.active_guards().map(|d| d.cond).collect(),
            uses: fibre_use(f.uses),
        }))
    }

    /// The tape's outputs at (I4, I5): ψ, the five partials, the guards' arguments.
    fn outputs(&self, i4: f64, i5: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.tape.n_outputs()];
        let input = [i4, i5, sign_i4(i4)];
        self.tape.eval(&self.frozen, input, [f64::NAN; 3], &mut out);
        out
    }
}

/// ψ and its partials from the tape's outputs: +∞ and zero derivatives
/// outside the domain.
fn derivs(out: &[f64], guards: &[DomainCond]) -> FibreDerivs {
    let inside = guards.iter().zip(&out[6..]).all(|(c, &x)| c.holds(x));
    if !inside || !out[0].is_finite() {
        return FibreDerivs {
            psi: f64::INFINITY,
            ..FibreDerivs::default()
        };
    }
    FibreDerivs {
        psi: out[0],
        d4: out[1],
        d5: out[2],
        d44: out[3],
        d45: out[4],
        d55: out[5],
    }
}

impl<const D: usize> FibreEnergy<D> for InterpFibre<D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn fibre(&self, i4: f64, i5: f64) -> FibreDerivs {
        derivs(&self.outputs(i4, i5), &self.guards)
    }

    fn uses(&self) -> FibreUse {
        self.uses
    }

    fn fibre_params(&self) -> Vec<(String, f64)> {
        self.param_names
            .iter()
            .cloned()
            .zip(self.param_values.iter().copied())
            .collect()
    }

    fn set_fibre_param(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        let k = crate::energy::param_slot(&self.param_names, name, value)?;
        self.param_values[k] = value;
        self.frozen = self.tape.freeze(&self.param_values);
        Ok(())
    }
}

/// The `D`-dimensional fibre part of a compiled module with parameter
/// overrides; `Ok(None)` when the module has no `fiber` (or not for `D`).
pub fn fibre_from_module<const D: usize>(
    module: &Module,
    file_name: &str,
    params: &[(String, f64)],
) -> Result<Option<InterpFibre<D>>, LoadError> {
    let values = param_values(module, params).map_err(|source| LoadError::Param {
        path: file_name.to_string(),
        source,
    })?;
    let Some(ir) = u8::try_from(D).ok().and_then(|d| module.dim(d)) else {
        return Ok(None);
    };
    InterpFibre::new(&module.name, ir, &values).map_err(|source| LoadError::Build {
        path: file_name.to_string(),
        source,
    })
}
