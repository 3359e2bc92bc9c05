//! Options of the code generator.

/// Visibility of the generated struct.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Visibility {
    /// `pub struct …` (the default).
    #[default]
    Public,
    /// `pub(crate) struct …`.
    Crate,
    /// `struct …` (private to the enclosing module or block; used by the
    /// expression form of `energy!`).
    Private,
}

/// What to generate and how to name it.
///
/// ```
/// let opts = ecc_codegen::GenOptions::named("Snh");
/// assert_eq!(opts.runtime_path, "::ecc_runtime");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GenOptions {
    /// Name of the generated struct (a Rust identifier, e.g. `Snh`).
    pub type_name: String,
    /// Visibility of the struct.
    pub vis: Visibility,
    /// Path of the runtime crate as seen from the generated code
    /// (default `::ecc_runtime`; `crate` inside ecc-runtime itself).
    pub runtime_path: String,
    /// Extra documentation placed on the struct (before the generated
    /// description of the formula).
    pub doc: Option<String>,
    /// What `Energy::name()` returns; `None` uses the module's name.
    pub energy_name: Option<String>,
}

impl Default for GenOptions {
    fn default() -> Self {
        GenOptions {
            type_name: "GeneratedEnergy".to_string(),
            vis: Visibility::Public,
            runtime_path: "::ecc_runtime".to_string(),
            doc: None,
            energy_name: None,
        }
    }
}

impl GenOptions {
    /// Default options with the struct named `type_name`.
    pub fn named(type_name: impl Into<String>) -> Self {
        GenOptions {
            type_name: type_name.into(),
            ..Default::default()
        }
    }
}

/// `snake_case`, `kebab-case` or `lower` file stems to a Rust type name:
/// `stable_neo_hookean` → `StableNeoHookean`, `sd3` → `Sd3`. Characters that
/// cannot appear in an identifier are dropped; a leading digit gets an `E`
/// prefix; an empty result becomes `GeneratedEnergy`.
pub fn type_name_from_stem(stem: &str) -> String {
    let mut out = String::new();
    for part in stem.split(|c: char| !c.is_ascii_alphanumeric()) {
        let mut chars = part.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.extend(chars);
        }
    }
    if out.is_empty() {
        return "GeneratedEnergy".to_string();
    }
    if out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, 'E');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_names_from_stems() {
        assert_eq!(
            type_name_from_stem("stable_neo_hookean"),
            "StableNeoHookean"
        );
        assert_eq!(type_name_from_stem("sd3"), "Sd3");
        assert_eq!(type_name_from_stem("my-energy.v2"), "MyEnergyV2");
        assert_eq!(type_name_from_stem("2d"), "E2d");
        assert_eq!(type_name_from_stem("__"), "GeneratedEnergy");
    }
}
