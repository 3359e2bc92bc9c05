//! Reading and compiling a `.psi` file: [`ecc_dsl::load_file`], the one
//! loader (diagnostics rendered against the path).

use std::path::Path;

pub use ecc_dsl::Source as Loaded;

use crate::error::CliError;

/// Read and compile `path`.
pub fn load(path: &Path) -> Result<Loaded, CliError> {
    Ok(ecc_dsl::load_file(path).map_err(ecc_interp::LoadError::from)?)
}
