//! Errors of the code generator.

use std::fmt;

/// Why code could not be generated for a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CodegenError {
    /// `GenOptions::type_name` is not a usable Rust identifier.
    InvalidTypeName {
        /// The name given.
        name: String,
    },
    /// `CppOptions::type_name` is not a C++ identifier, or is a keyword or
    /// reserved name.
    InvalidCppTypeName {
        /// The name given.
        name: String,
    },
    /// `GenOptions::runtime_path` does not parse as a Rust path.
    InvalidRuntimePath {
        /// The path given.
        path: String,
    },
    /// The module compiled for no dimension at all.
    NoDimensions {
        /// The reasons each dimension was skipped.
        skipped: Vec<(u8, String)>,
    },
    /// The IR is inconsistent (a bug in the producer of the IR).
    MalformedIr {
        /// The dimension whose IR is wrong.
        dim: u8,
        /// What is wrong.
        what: String,
    },
    /// The generated tokens did not parse back as a Rust file (a bug in the
    /// generator; the message says where).
    Format {
        /// The parser's message.
        message: String,
    },
}

impl fmt::Display for CodegenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CodegenError::InvalidTypeName { name } => {
                write!(f, "`{name}` is not a valid Rust type name")
            }
            CodegenError::InvalidCppTypeName { name } => write!(
                f,
                "`{name}` is not a valid C++ type name (an ASCII identifier that is not a keyword)"
            ),
            CodegenError::InvalidRuntimePath { path } => {
                write!(f, "runtime path `{path}` is not a valid Rust path")
            }
            CodegenError::NoDimensions { skipped } => {
                write!(f, "the energy compiled for no dimension")?;
                for (d, why) in skipped {
                    write!(f, "; {d}D skipped: {why}")?;
                }
                Ok(())
            }
            CodegenError::MalformedIr { dim, what } => {
                write!(f, "malformed {dim}D IR: {what}")
            }
            CodegenError::Format { message } => {
                write!(f, "generated code does not parse: {message}")
            }
        }
    }
}

impl std::error::Error for CodegenError {}
