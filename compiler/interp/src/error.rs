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
         and the library API is ecc_interp::fibre_from_module; scenes, `ecc check` and the Python \
         package take .psi fibre energies in a later release"
    )]
    FibrePart {
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
