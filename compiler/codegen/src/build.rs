//! The build-script helper: compile `.psi` files into Rust at build time.
//!
//! ```no_run
//! // build.rs of a user crate that depends on ecc-runtime (and has
//! // ecc-codegen as a build-dependency). On errors the diagnostics are
//! // printed to stderr and the build fails.
//! if let Err(e) = ecc_codegen::build::compile_file("energies/snh.psi") {
//!     panic!("{e}");
//! }
//! ```
//!
//! and in the crate, `include!(concat!(env!("OUT_DIR"), "/snh.rs"));` defines
//! `pub struct Snh` implementing `ecc_runtime::Energy<2>`/`<3>`.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::error::CodegenError;
use crate::options::{GenOptions, type_name_from_stem};

/// Why a `.psi` file could not be turned into Rust.
#[derive(Debug)]
pub enum BuildError {
    /// The file could not be read or the output not written.
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The I/O error.
        message: String,
    },
    /// The energy has errors; `rendered` is the compiler-style report
    /// (already printed to stderr).
    Compile {
        /// The `.psi` file.
        path: PathBuf,
        /// The rendered diagnostics.
        rendered: String,
    },
    /// Code generation failed.
    Codegen {
        /// The `.psi` file.
        path: PathBuf,
        /// The generator's error.
        error: CodegenError,
    },
    /// `OUT_DIR` is not set (not running inside a build script).
    NoOutDir,
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Io { path, message } => write!(f, "{}: {message}", path.display()),
            BuildError::Compile { path, rendered } => {
                write!(f, "{}: the energy has errors\n{rendered}", path.display())
            }
            BuildError::Codegen { path, error } => write!(f, "{}: {error}", path.display()),
            BuildError::NoOutDir => write!(
                f,
                "OUT_DIR is not set: compile_file must run inside a build script"
            ),
        }
    }
}

impl std::error::Error for BuildError {}

/// Compile `path` (a `.psi` file) into `$OUT_DIR/<stem>.rs` defining
/// `pub struct <Stem>` (`snh.psi` → `Snh`, `stable_neo_hookean.psi` →
/// `StableNeoHookean`). Prints `cargo:rerun-if-changed=<path>`; on errors
/// renders the diagnostics to stderr and returns them.
pub fn compile_file(path: impl AsRef<Path>) -> Result<PathBuf, BuildError> {
    let path = path.as_ref();
    let opts = GenOptions::named(type_name_from_stem(&stem(path)));
    compile_file_with(path, &opts)
}

/// [`compile_file`] with explicit generator options (type name, docs, …).
pub fn compile_file_with(path: impl AsRef<Path>, opts: &GenOptions) -> Result<PathBuf, BuildError> {
    let out_dir = std::env::var_os("OUT_DIR").ok_or(BuildError::NoOutDir)?;
    let path = path.as_ref();
    println!("cargo:rerun-if-changed={}", path.display());
    compile_file_to(path, Path::new(&out_dir), opts)
}

/// Compile `path` into `<out_dir>/<stem>.rs` (no environment, no cargo
/// output except diagnostics on stderr). The file is only rewritten when its
/// contents change, so dependants are not rebuilt needlessly.
pub fn compile_file_to(
    path: &Path,
    out_dir: &Path,
    opts: &GenOptions,
) -> Result<PathBuf, BuildError> {
    let io = |p: &Path, e: std::io::Error| BuildError::Io {
        path: p.to_path_buf(),
        message: e.to_string(),
    };
    let source = std::fs::read_to_string(path).map_err(|e| io(path, e))?;
    let name = stem(path);
    let module = ecc_dsl::compile(&source, &name).map_err(|diags| {
        let rendered = diags.render(&path.display().to_string(), &source);
        eprintln!("{rendered}");
        BuildError::Compile {
            path: path.to_path_buf(),
            rendered,
        }
    })?;
    let text = crate::generate_pretty(&module, opts).map_err(|error| BuildError::Codegen {
        path: path.to_path_buf(),
        error,
    })?;
    let out = out_dir.join(format!("{name}.rs"));
    if std::fs::read_to_string(&out).ok().as_deref() != Some(text.as_str()) {
        std::fs::write(&out, text).map_err(|e| io(&out, e))?;
    }
    Ok(out)
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "energy".to_string())
}
