//! `ecc FILE.psi --emit rs [-o out.rs] [--name TypeName]`,
//! `ecc FILE.psi --emit cpp [-o out.hpp] [--name TypeName]` and
//! `ecc FILE.psi --emit report [-o out.md]`.
//!
//! `rs`: a Rust file (ecc-codegen's `generate_pretty`) defining one struct
//! that implements `ecc_runtime::Energy<2>` and/or `<3>`; it compiles in any
//! crate that depends on ecc-runtime. `cpp`: a self-contained C++17 header
//! (ecc-codegen's `generate_cpp`, runtime inlined behind its include guard)
//! defining `ecc::energies::TypeName` with `psi`, `spectral`, `eval` and
//! `eval_tri`/`eval_tet`. `report`: Markdown (ecc-codegen's
//! `report_markdown`) with the derivatives, every eigenvalue expression, which
//! modes are closed-form and the singularities found. With `-o` the output is
//! written atomically (temporary file + rename).

use std::path::PathBuf;

use ecc_codegen::{
    CppOptions, GenOptions, generate_cpp, generate_pretty, report_markdown, type_name_from_stem,
};

use crate::error::CliError;
use crate::output::emit;
use crate::source::load;

/// What `--emit` produces.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmitKind {
    /// Rust source implementing `ecc_runtime::Energy`.
    Rs,
    /// A self-contained C++17 header (`ecc::energies::TypeName`).
    Cpp,
    /// A Markdown report of the derivatives, eigenvalues and singularities.
    Report,
}

/// Arguments of the top-level `ecc FILE.psi --emit …` form.
#[derive(clap::Args, Debug)]
pub struct EmitArgs {
    /// The energy: a `.psi` file.
    #[arg(required = true)]
    pub file: Option<PathBuf>,
    /// What to generate.
    #[arg(long, value_enum, required = true)]
    pub emit: Option<EmitKind>,
    /// Write to this file (atomically) instead of standard output.
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub output: Option<PathBuf>,
    /// Name of the generated Rust or C++ type (default: from the file name, e.g. `snh.psi` → `Snh`).
    #[arg(long, value_name = "TypeName")]
    pub name: Option<String>,
}

/// Run the emit form (both `file` and `emit` are present: clap requires them).
pub fn run(args: &EmitArgs) -> Result<(), CliError> {
    let (Some(file), Some(kind)) = (&args.file, args.emit) else {
        return Err(CliError::Usage(
            "expected `ecc FILE.psi --emit rs|cpp|report` or a subcommand (see `ecc --help`)"
                .into(),
        ));
    };
    let loaded = load(file)?;
    let text = match kind {
        EmitKind::Rs => {
            let type_name = args
                .name
                .clone()
                .unwrap_or_else(|| type_name_from_stem(&loaded.name));
            let opts = GenOptions::named(type_name);
            generate_pretty(&loaded.module, &opts).map_err(|source| CliError::Codegen {
                path: loaded.shown.clone(),
                source,
            })?
        }
        EmitKind::Cpp => {
            let type_name = args
                .name
                .clone()
                .unwrap_or_else(|| type_name_from_stem(&loaded.name));
            generate_cpp(&loaded.module, &CppOptions::named(type_name)).map_err(|source| {
                CliError::Codegen {
                    path: loaded.shown.clone(),
                    source,
                }
            })?
        }
        EmitKind::Report => report_markdown(&loaded.module, &loaded.name),
    };
    emit(args.output.as_deref(), &text)
}
