//! Reading and compiling a `.psi` file, with diagnostics rendered against its path.

use std::path::Path;

use ecc_dsl::Module;

use crate::error::CliError;

/// A compiled energy file.
pub struct Loaded {
    /// The path as shown in messages.
    pub shown: String,
    /// The energy's name (the file stem).
    pub name: String,
    /// The compiled module.
    pub module: Module,
}

/// Read and compile `path`.
pub fn load(path: &Path) -> Result<Loaded, CliError> {
    let shown = path.display().to_string();
    let text = ecc_interp::read_source(path)?;
    let name = ecc_interp::energy_name(&shown);
    let module = ecc_interp::compile_module(&text, &shown, &name)?;
    Ok(Loaded {
        shown,
        name,
        module,
    })
}
