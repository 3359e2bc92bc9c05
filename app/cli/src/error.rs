//! The CLI's error type: every failure becomes one clear message on stderr
//! and a non-zero exit status.

use std::fmt;

use ecc_interp::LoadError;

use crate::input::{MatrixError, ParamArgError};

/// Exit status for failures (bad input, failed checks); clap uses 2 for usage errors.
pub const EXIT_FAILURE: i32 = 1;

/// Anything that makes a command fail.
#[derive(Debug)]
pub enum CliError {
    /// Reading or compiling the energy, a parameter override, a missing dimension.
    Load(LoadError),
    /// A malformed `--F`.
    Matrix(MatrixError),
    /// A malformed `--param`.
    Param(ParamArgError),
    /// An output file could not be written.
    Write {
        /// The destination.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// Code generation or the report failed.
    Codegen {
        /// The energy file.
        path: String,
        /// The generator's message.
        message: String,
    },
    /// The command line is incomplete in a way clap cannot express.
    Usage(String),
    /// Standard output could not be written (e.g. a closed pipe).
    Stdout(String),
    /// A scene could not be read, built or run (`ecc sim`); the message
    /// names the file, line and key.
    Scene(String),
    /// `ecc check` found errors above tolerance (the report is already printed).
    CheckFailed {
        /// How many checks failed.
        failures: usize,
    },
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            // Rendered diagnostics already carry `error:` headers and source excerpts.
            CliError::Load(LoadError::Syntax { rendered, .. }) => {
                write!(f, "{}", rendered.trim_end())
            }
            CliError::Load(e) => write!(f, "error: {e}"),
            CliError::Matrix(e) => write!(f, "error: {e}"),
            CliError::Param(e) => write!(f, "error: {e}"),
            CliError::Write { path, message } => {
                write!(f, "error: cannot write `{path}`: {message}")
            }
            CliError::Codegen { path, message } => {
                write!(f, "error: cannot generate code for `{path}`: {message}")
            }
            CliError::Usage(message) => write!(f, "error: {message}"),
            CliError::Scene(message) => write!(f, "error: {message}"),
            CliError::Stdout(message) => {
                write!(f, "error: cannot write to standard output: {message}")
            }
            CliError::CheckFailed { failures } => write!(
                f,
                "error: {failures} check{} exceeded the tolerance (see the table above)",
                if *failures == 1 { "" } else { "s" }
            ),
        }
    }
}

impl std::error::Error for CliError {}

impl From<LoadError> for CliError {
    fn from(e: LoadError) -> Self {
        CliError::Load(e)
    }
}

impl From<MatrixError> for CliError {
    fn from(e: MatrixError) -> Self {
        CliError::Matrix(e)
    }
}

impl From<ParamArgError> for CliError {
    fn from(e: ParamArgError) -> Self {
        CliError::Param(e)
    }
}
