//! Reading a scene file: TOML → [`Scene`], with errors that name the key,
//! its table and its line.
//!
//! toml/serde report a message and a byte span; the span is turned into
//! `line:column` and the message is rewritten with the table and key found
//! in the text from the parser's spans ([`super::spans`]):
//!
//! * unknown key → "unknown key `gravty` in [effects]; did you mean `gravity`?"
//!   (suggestions by edit distance among the keys serde expected);
//! * wrong type → "wrong type for `dt` in [effects.inertia]: expected a
//!   number, found a string";
//! * unknown value of an enumeration → "`integrator` in [effects.inertia]:
//!   unknown value `bdf3` (expected `euler` or `bdf2`)";
//! * missing key → "missing key `dt` in [effects.inertia]".

use std::path::{Path, PathBuf};

use super::model::Scene;
use super::spans::{Spans, line_col};
use crate::error::{Location, SceneError};

/// A parsed scene with where it came from (for paths and error positions).
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The scene.
    pub scene: Scene,
    /// The file name as shown in messages (`<built-in>` for programmatic scenes).
    pub display: String,
    /// Folder that relative paths in the scene are resolved against.
    pub base_dir: PathBuf,
    /// The TOML text (for error positions), when the scene came from text.
    pub text: Option<String>,
}

impl SceneFile {
    /// Read and parse a scene file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.display().to_string(),
            source,
        })?;
        let base = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        Self::parse(&text, &path.display().to_string(), base)
    }

    /// Parse TOML text; `display` names it in errors, `base_dir` resolves paths.
    pub fn parse(
        text: &str,
        display: &str,
        base_dir: impl Into<PathBuf>,
    ) -> Result<Self, SceneError> {
        let scene: Scene = toml::from_str(text).map_err(|e| map_toml_error(text, display, &e))?;
        Ok(SceneFile {
            scene,
            display: display.to_string(),
            base_dir: base_dir.into(),
            text: Some(text.to_string()),
        })
    }

    /// A scene built in code (no text: errors name keys without positions).
    pub fn from_scene(scene: Scene, base_dir: impl Into<PathBuf>) -> Self {
        SceneFile {
            scene,
            display: "<scene>".to_string(),
            base_dir: base_dir.into(),
            text: None,
        }
    }

    /// The scene's name: `name`, else the file stem, else `scene`.
    pub fn name(&self) -> String {
        if let Some(n) = &self.scene.name {
            return n.clone();
        }
        Path::new(&self.display)
            .file_stem()
            .and_then(|s| s.to_str())
            .filter(|s| !s.starts_with('<') && !s.is_empty())
            .unwrap_or("scene")
            .to_string()
    }

    /// Fill in the file name and the key's position of an
    /// [`SceneError::Invalid`] (other errors pass through).
    pub fn locate(&self, err: SceneError) -> SceneError {
        match err {
            SceneError::Invalid {
                key, message, at, ..
            } => {
                let at = at.or_else(|| self.position_of(&key));
                SceneError::Invalid {
                    file: self.display.clone(),
                    at,
                    key,
                    message,
                }
            }
            other => other,
        }
    }

    /// Where a dotted key is written (best effort: the key's line, else its table's header).
    pub fn position_of(&self, key: &str) -> Option<Location> {
        let text = self.text.as_deref()?;
        Spans::new(text).find(key).map(|o| line_col(text, o))
    }

    /// Resolve a path written in the scene: `data:NAME` → the data folder
    /// (`$ECC_DATA_DIR`, default the repository's `data/`); relative paths →
    /// against the scene file's folder.
    pub fn resolve(&self, written: &str) -> PathBuf {
        if let Some(name) = written.strip_prefix("data:") {
            return data_dir().join(name);
        }
        let p = Path::new(written);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.base_dir.join(p)
        }
    }
}

/// The public mesh folder: `$ECC_DATA_DIR`, default the repository's `data/`
/// (see [`ecc_mesh::data_dir`]).
pub fn data_dir() -> PathBuf {
    ecc_mesh::data_dir()
}

/// The closest candidate under the workspace's one rule ([`ecc_util::suggest`]).
pub(crate) fn suggest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    ecc_util::suggest_among(word, candidates.iter().copied())
}

/// All `` `name` `` items of a serde message.
fn backticked(s: &str) -> Vec<&str> {
    s.split('`').skip(1).step_by(2).collect()
}

/// `[table]` for messages (`the top level` for the root).
fn table_label(table: &str) -> String {
    if table.is_empty() {
        "at the top level".to_string()
    } else {
        format!("in [{table}]")
    }
}

/// The last component of a dotted key.
fn leaf(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

/// serde's "expected f64" etc. in plain words.
fn plain_expected(e: &str) -> String {
    let e = e.trim();
    match e {
        "f64" | "f32" => "a number".into(),
        "usize" | "u64" | "u32" | "u8" => "a non-negative integer".into(),
        "i64" | "i32" => "an integer".into(),
        "a boolean" | "bool" => "true or false".into(),
        "a sequence" => "an array".into(),
        "a string" => "a string".into(),
        e if e.starts_with("struct ") => "a table".into(),
        e if e.starts_with("a map") => "a table".into(),
        _ => e.to_string(),
    }
}

/// Rewrite a toml/serde error (see the module docs).
fn map_toml_error(text: &str, display: &str, e: &toml::de::Error) -> SceneError {
    let raw = e.message().trim().to_string();
    let span = e.span();
    let at = span.as_ref().map(|s| line_col(text, s.start));
    let (table, key) = span
        .as_ref()
        .map(|s| Spans::new(text).context(s.start))
        .unwrap_or_default();
    let message = if let Some(rest) = raw.strip_prefix("unknown field ") {
        let names = backticked(rest);
        let (bad, expected) = names.split_first().map_or(("?", &[][..]), |(b, r)| (*b, r));
        let mut m = format!("unknown key `{bad}` {}", table_label(&table));
        match suggest(bad, expected) {
            Some(s) => m.push_str(&format!("; did you mean `{s}`?")),
            None if !expected.is_empty() => {
                m.push_str(&format!(" (known keys: {})", expected.join(", ")))
            }
            None => {}
        }
        m
    } else if let Some(rest) = raw.strip_prefix("unknown variant ") {
        let names = backticked(rest);
        let (bad, expected) = names.split_first().map_or(("?", &[][..]), |(b, r)| (*b, r));
        let what = key.as_deref().map(leaf).unwrap_or("value");
        let mut m = format!(
            "`{what}` {}: unknown value `{bad}` (expected {})",
            table_label(&table),
            expected
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if let Some(s) = suggest(bad, expected) {
            m.push_str(&format!("; did you mean `{s}`?"));
        }
        m
    } else if let Some(rest) = raw.strip_prefix("invalid type: ") {
        let (found, expected) = rest.split_once(", expected ").unwrap_or((rest, "?"));
        let what = key.as_deref().map(leaf).unwrap_or("value");
        format!(
            "wrong type for `{what}` {}: expected {}, found {found}",
            table_label(&table),
            plain_expected(expected)
        )
    } else if let Some(rest) = raw.strip_prefix("missing field ") {
        let name = backticked(rest).first().copied().unwrap_or(rest);
        // the span covers the table that lacks the key
        let t = match &key {
            Some(k) if span.as_ref().is_some_and(|s| text[s.clone()].contains('{')) => k.clone(),
            _ => table,
        };
        format!("missing key `{name}` {}", table_label(&t))
    } else if let Some(rest) = raw.strip_prefix("invalid value: ") {
        let what = key.as_deref().map(leaf).unwrap_or("value");
        format!("invalid value for `{what}` {}: {rest}", table_label(&table))
    } else {
        raw.replace('\n', "; ")
    };
    SceneError::Parse {
        file: display.to_string(),
        at,
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        assert_eq!(suggest("gravty", &["density", "gravity"]), Some("gravity"));
        assert_eq!(suggest("zzzzzz", &["density", "gravity"]), None);
    }
}
