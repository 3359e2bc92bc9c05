//! What can go wrong with a scene, and where.
//!
//! Every error names what is wrong and where: a position `file:line:column`
//! in the scene file when it is known, and the dotted key (`effects.inertia.dt`)
//! whose value is at fault. Failures *during* a solve are not errors: they are
//! Newton statuses recorded per frame in the summary.

use std::fmt;

/// A 1-based position in a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
}

/// Why a file could not be written (the source of [`SceneError::Write`]).
#[derive(Debug, thiserror::Error)]
pub enum WriteFailure {
    /// The operating system's error.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The mesh writer's error.
    #[error("{0}")]
    Mesh(#[from] ecc_mesh::MeshError),
    /// The document could not be encoded.
    #[error("{0}")]
    Json(#[from] serde_json::Error),
}

/// Why the output folder cannot be used (the source of [`SceneError::Output`]).
#[derive(Debug, thiserror::Error)]
pub enum OutputFailure {
    /// The path names something else.
    #[error("it exists and is not a folder")]
    NotAFolder,
    /// The folder (or a parent) could not be created.
    #[error("{0}")]
    Create(#[source] std::io::Error),
    /// The probe file could not be written.
    #[error("cannot write `{path}`: {source}")]
    Probe {
        /// The probe file.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The probe file could not be removed.
    #[error("{0}")]
    RemoveProbe(#[source] std::io::Error),
}

/// Everything that can be wrong with a scene before or while it runs.
#[derive(Debug)]
pub enum SceneError {
    /// The TOML text itself is wrong: syntax, an unknown key, a wrong type,
    /// a missing key. `message` already names the key and its table.
    Parse {
        /// The scene file as shown to the user.
        file: String,
        /// Where the problem is (when toml reports a span).
        at: Option<Location>,
        /// What is wrong.
        message: String,
    },
    /// A value parsed but is not acceptable (negative time step, unknown
    /// energy, missing mesh file, a handle that selects no vertex, …).
    Invalid {
        /// The scene file as shown to the user.
        file: String,
        /// Where the key is written (when it is written in the file).
        at: Option<Location>,
        /// Dotted key path, e.g. `effects.inertia.dt`.
        key: String,
        /// What is wrong with it.
        message: String,
    },
    /// A file could not be read.
    Read {
        /// The path as given.
        path: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The output folder cannot be created or written (checked before any work).
    Output {
        /// The folder.
        path: String,
        /// Why.
        source: OutputFailure,
    },
    /// An output file could not be written.
    Write {
        /// The file.
        path: String,
        /// Why.
        source: WriteFailure,
    },
    /// The solver could not be set up (a bug or an unusable mesh; the
    /// library's error is kept as the source).
    Setup {
        /// What was being built.
        what: String,
        /// The library's error.
        source: ecc_fem::FemError,
    },
}

impl SceneError {
    /// Shorthand for an [`SceneError::Invalid`] without a location (filled in
    /// later by [`crate::spec::SceneFile::locate`]).
    pub fn invalid(key: impl Into<String>, message: impl Into<String>) -> Self {
        SceneError::Invalid {
            file: String::new(),
            at: None,
            key: key.into(),
            message: message.into(),
        }
    }

    /// Shorthand for a [`SceneError::Setup`].
    pub fn setup(what: impl Into<String>, source: ecc_fem::FemError) -> Self {
        SceneError::Setup {
            what: what.into(),
            source,
        }
    }

    /// The dotted key an [`SceneError::Invalid`] is about.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Invalid { key, .. } => Some(key),
            _ => None,
        }
    }

    /// The location in the scene file, if known.
    pub fn location(&self) -> Option<Location> {
        match self {
            SceneError::Parse { at, .. } | SceneError::Invalid { at, .. } => *at,
            _ => None,
        }
    }
}

fn prefix(f: &mut fmt::Formatter<'_>, file: &str, at: &Option<Location>) -> fmt::Result {
    match (file.is_empty(), at) {
        (false, Some(l)) => write!(f, "{file}:{}:{}: ", l.line, l.column),
        (false, None) => write!(f, "{file}: "),
        (true, Some(l)) => write!(f, "{}:{}: ", l.line, l.column),
        (true, None) => Ok(()),
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Parse { file, at, message } => {
                prefix(f, file, at)?;
                write!(f, "{message}")
            }
            SceneError::Invalid {
                file,
                at,
                key,
                message,
            } => {
                prefix(f, file, at)?;
                write!(f, "`{key}`: {message}")
            }
            SceneError::Read { path, source } => write!(f, "cannot read `{path}`: {source}"),
            SceneError::Output { path, source } => {
                write!(f, "output folder `{path}` cannot be written: {source}")
            }
            SceneError::Write { path, source } => write!(f, "cannot write `{path}`: {source}"),
            SceneError::Setup { what, source } => write!(f, "setting up {what}: {source}"),
        }
    }
}

impl std::error::Error for SceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SceneError::Setup { source, .. } => Some(source),
            SceneError::Read { source, .. } => Some(source),
            SceneError::Output { source, .. } => Some(source),
            SceneError::Write { source, .. } => Some(source),
            SceneError::Parse { .. } | SceneError::Invalid { .. } => None,
        }
    }
}
