//! Loading a `.psi` file: read it, compile it, and render every diagnostic
//! against the file name — the one loader behind `ecc eval/check/emit`, the
//! interpreter (`ecc_interp::load_psi`) and `.psi` energies in scenes.

use std::path::Path;

use crate::ir::Module;

/// A `.psi` file (or text) that could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read (or is not UTF-8).
    #[error("cannot read `{path}`: {source}")]
    Io {
        /// The path as shown in messages.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The energy language rejected the text; `rendered` shows every error
    /// with its file, line, column and the offending source.
    #[error("{rendered}")]
    Syntax {
        /// The file name used in the rendering.
        path: String,
        /// Compiler-style report of all errors (codespan-reporting).
        rendered: String,
    },
}

/// A compiled energy file.
#[derive(Clone, Debug)]
pub struct Source {
    /// The path (or file name) as shown in messages.
    pub shown: String,
    /// The energy's name: the file stem (`energies/psi/snh.psi` → `snh`).
    pub name: String,
    /// The text.
    pub text: String,
    /// The compiled module.
    pub module: Module,
}

/// Read and compile the `.psi` file at `path` (see [`load_text`]).
pub fn load_file(path: impl AsRef<Path>) -> Result<Source, LoadError> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| LoadError::Io {
        path: shown.clone(),
        source,
    })?;
    load_text(text, &shown)
}

/// Compile `text`, named `file_name` in diagnostics; the energy is named
/// after the file stem ([`energy_name`]).
pub fn load_text(text: impl Into<String>, file_name: &str) -> Result<Source, LoadError> {
    let text = text.into();
    let name = energy_name(file_name);
    let module = compile_text(&text, file_name, &name)?;
    Ok(Source {
        shown: file_name.to_string(),
        name,
        text,
        module,
    })
}

/// Compile `text` as the energy `name`, every diagnostic rendered against
/// `file_name`.
pub fn compile_text(text: &str, file_name: &str, name: &str) -> Result<Module, LoadError> {
    crate::compile(text, name).map_err(|d| LoadError::Syntax {
        path: file_name.to_string(),
        rendered: d.render(file_name, text),
    })
}

/// The energy name for a file: its stem (`energies/psi/snh.psi` → `snh`),
/// `energy` when there is none.
pub fn energy_name(file_name: &str) -> String {
    Path::new(file_name)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("energy")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_come_from_the_stem() {
        assert_eq!(energy_name("energies/psi/snh.psi"), "snh");
        assert_eq!(energy_name("x"), "x");
        assert_eq!(energy_name(""), "energy");
    }

    #[test]
    fn text_compiles_and_errors_are_rendered_with_the_file_name() {
        let s = load_text("param mu = 1\npsi = mu*(I2 - d)", "dir/quad.psi").unwrap();
        assert_eq!(
            (s.name.as_str(), s.shown.as_str()),
            ("quad", "dir/quad.psi")
        );
        assert!(s.module.dim(2).is_some());
        let e = load_text("psi = mu*I2", "bad.psi").unwrap_err();
        let LoadError::Syntax { rendered, .. } = &e else {
            panic!("{e:?}")
        };
        assert!(rendered.contains("bad.psi:1:7"), "{rendered}");
        assert!(rendered.contains("unknown identifier `mu`"), "{rendered}");
    }

    #[test]
    fn a_missing_file_is_an_io_error_naming_it() {
        let e = load_file("/no/such/file.psi").unwrap_err();
        assert!(matches!(e, LoadError::Io { .. }), "{e:?}");
        assert!(
            e.to_string()
                .starts_with("cannot read `/no/such/file.psi`: "),
            "{e}"
        );
        assert!(std::error::Error::source(&e).is_some());
    }
}
