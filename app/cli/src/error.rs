//! The CLI's error type: every failure stays typed (with its source) up to
//! here and becomes one clear message on stderr, rendered once by `main`,
//! and a non-zero exit status.

use ecc_interp::LoadError;
use ecc_scene::SceneError;

use crate::input::{MatrixError, ParamArgError};

/// Exit status for failures (bad input, failed checks); clap uses 2 for usage errors.
pub const EXIT_FAILURE: i32 = 1;
/// Exit status of an `ecc sim` run whose frames did not all converge
/// (without `--allow-unconverged`).
pub const EXIT_UNCONVERGED: i32 = 3;

impl CliError {
    /// The process exit status for this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Unconverged { .. } => EXIT_UNCONVERGED,
            _ => EXIT_FAILURE,
        }
    }
}

/// Anything that makes a command fail.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Reading or compiling the energy, a parameter override, a missing
    /// dimension. Rendered diagnostics already carry `error:` headers and
    /// source excerpts.
    #[error("{}", load_message(.0))]
    Load(#[from] LoadError),
    /// A malformed `--F`.
    #[error("error: {0}")]
    Matrix(#[from] MatrixError),
    /// A malformed `--param`.
    #[error("error: {0}")]
    Param(#[from] ParamArgError),
    /// An output file could not be written.
    #[error("error: cannot write `{path}`: {source}")]
    Write {
        /// The destination.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// Code generation failed.
    #[error("error: cannot generate code for `{path}`: {source}")]
    Codegen {
        /// The energy file.
        path: String,
        /// The generator's error.
        #[source]
        source: ecc_codegen::CodegenError,
    },
    /// The command line is incomplete in a way clap cannot express.
    #[error("error: {0}")]
    Usage(String),
    /// Standard output could not be written (a closed pipe is not an error).
    #[error("error: cannot write to standard output: {0}")]
    Stdout(#[source] std::io::Error),
    /// A JSON document could not be encoded.
    #[error("error: cannot encode the JSON output: {0}")]
    Json(#[from] serde_json::Error),
    /// A scene could not be read, built or run (`ecc sim`); the message
    /// names the file, line and key.
    #[error("error: {0}")]
    Scene(#[from] SceneError),
    /// The compiled-in demo scene does not parse (a build defect).
    #[error("error: the built-in demo scene is invalid: {0}")]
    DemoScene(#[source] SceneError),
    /// A scene run stopped before its last frame (the summary says why).
    #[error("error: the run stopped early: {why}")]
    Stopped {
        /// The reason and the frame, as recorded in the summary.
        why: String,
    },
    /// A scene run reached its last frame but some frames did not converge
    /// (exit status [`EXIT_UNCONVERGED`]; every file was written).
    #[error(
        "error: {frames} of {total} frame(s) did not converge (see the warning above): raise \
         `[solver] max_iters` (or loosen `[solver] tol`) in the scene, or pass \
         --allow-unconverged to accept the result; all files were written"
    )]
    Unconverged {
        /// Frames that did not converge.
        frames: usize,
        /// Frames run.
        total: usize,
    },
    /// `ecc check` found errors above tolerance (the report is already printed).
    #[error(
        "error: {failures} check{} exceeded the tolerance (see the table above)",
        if *failures == 1 { "" } else { "s" }
    )]
    CheckFailed {
        /// How many checks failed.
        failures: usize,
    },
}

/// A load error as shown: rendered diagnostics as they are, the rest
/// behind `error: `.
fn load_message(e: &LoadError) -> String {
    match e {
        LoadError::Syntax { rendered, .. } => rendered.trim_end().to_string(),
        e => format!("error: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_and_sources() {
        let e = CliError::Write {
            path: "out.rs".into(),
            source: std::io::Error::other("disk full"),
        };
        assert_eq!(e.to_string(), "error: cannot write `out.rs`: disk full");
        assert!(std::error::Error::source(&e).is_some());
        let e = CliError::CheckFailed { failures: 1 };
        assert_eq!(
            e.to_string(),
            "error: 1 check exceeded the tolerance (see the table above)"
        );
        let e = CliError::Load(LoadError::Syntax {
            path: "a.psi".into(),
            rendered: "error: x\n".into(),
        });
        assert_eq!(e.to_string(), "error: x");
    }
}
