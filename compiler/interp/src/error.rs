//! Errors of building and loading interpreted energies.

use ecc_runtime::ParamError;

/// An [`InterpEnergy`](crate::InterpEnergy) could not be built from an IR.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// The energy type's dimension is not 2 or 3.
    #[error("dimension {dim} is not supported (only 2 and 3)")]
    UnsupportedDim {
        /// The requested dimension.
        dim: usize,
    },
    /// The IR was compiled for another dimension.
    #[error("the IR is for {ir}D but a {requested}D energy was requested")]
    DimMismatch {
        /// The IR's dimension.
        ir: u8,
        /// The requested dimension.
        requested: usize,
    },
    /// Wrong number of parameter values.
    #[error("the energy has {expected} parameter(s) but {found} value(s) were given")]
    ParamCount {
        /// Declared parameters.
        expected: usize,
        /// Values given.
        found: usize,
    },
    /// A parameter value is rejected.
    #[error("{0}")]
    Param(ParamError),
    /// The IR lacks the derivatives its path needs.
    #[error("malformed IR: missing {what}")]
    MissingDerivatives {
        /// What is missing.
        what: &'static str,
    },
    /// The IR refers to a node outside its graph.
    #[error("malformed IR: node id {id} is outside the graph")]
    BadId {
        /// The offending id.
        id: u32,
    },
}

/// A `.psi` file could not be turned into an energy.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read `{path}`: {message}")]
    Io {
        /// The path as given.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The energy language rejected the text; `rendered` shows every error
    /// with its line, column and the offending source.
    #[error("{rendered}")]
    Syntax {
        /// The file name used in the rendering.
        path: String,
        /// Compiler-style report of all errors.
        rendered: String,
    },
    /// The energy does not exist in the requested dimension.
    #[error("`{path}` has no {dim}D energy: {reason}")]
    NoSuchDim {
        /// The file name.
        path: String,
        /// The requested dimension.
        dim: usize,
        /// Why the DSL skipped that dimension.
        reason: String,
    },
    /// A parameter override names an unknown parameter or is not finite.
    #[error("`{path}`: {source}")]
    Param {
        /// The file name.
        path: String,
        /// What is wrong with the parameter.
        source: ParamError,
    },
    /// The energy declares `fiber a`: its second part ψ(I4, I5) would be
    /// dropped by an entry point that evaluates isotropic energies, so the
    /// load is refused instead of silently evaluating Ψ_iso alone.
    #[error(
        "`{path}` declares `fiber {direction}`: its fibre part ψ(I4, I5) cannot be evaluated here \
         (only the isotropic part would be, a different energy); `ecc eval --fiber` evaluates it, \
         and the library API is ecc_interp::fibre_from_module; a scene takes it as `[energy] psi` \
         with a `[fibers]` section giving the directions; `ecc check` verifies both parts; the Python \
         package's Energy does not take .psi fibre energies yet"
    )]
    FibrePart {
        /// The file name.
        path: String,
        /// The declared direction's name.
        direction: String,
    },
    /// A fibre energy was asked of a file without a fibre part
    /// ([`crate::load_fibre_part`]).
    #[error(
        "`{path}` has no fibre part in {dim}D: a fibre energy needs a `fiber a` statement and a ψ \
         of I4/I5 (an isotropic file belongs in `[energy]`)"
    )]
    NoFibrePart {
        /// The file name.
        path: String,
        /// The requested dimension.
        dim: usize,
    },
    /// The fibre part alone was asked of a file whose isotropic part Ψ_iso
    /// is not 0 ([`crate::load_fibre_part`]): taking ψ would drop Ψ_iso.
    #[error(
        "`{path}` has an isotropic part besides its fibre part (`fiber {direction}`), and a fibre \
         energy is ψ(I4, I5) alone: in a scene, give the file as `[energy] psi` (its isotropic part \
         is then the body's energy and its fibre part the `[fibers]` term, `[fibers]` giving only \
         the directions), or keep only the fibre terms in the file"
    )]
    IsoBesideFibre {
        /// The file name.
        path: String,
        /// The declared direction's name.
        direction: String,
    },
    /// The compiled IR could not be interpreted (a compiler bug).
    #[error("`{path}`: {source}")]
    Build {
        /// The file name.
        path: String,
        /// The underlying error.
        source: BuildError,
    },
}
