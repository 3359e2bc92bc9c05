//! Where keys are written in a scene's TOML text, from the parser's own
//! spans (`toml_edit`'s [`ImDocument`] keeps the byte range of every key,
//! value and table header): a key path such as
//! `effects.handles[1].keys[0].frame` maps to the position of its key, and
//! a byte offset from a serde error maps back to the table and key that
//! hold it. A key that is not written (a missing key, a default) maps to
//! the closest written enclosing key or table header, and to `None` when
//! even that is absent.

use std::ops::Range;

use toml_edit::{ImDocument, Item, Table, Value};

use crate::error::Location;

/// A written `key = value` (also inside inline tables and arrays, whose
/// elements are entries `key[i]` spanning the element).
#[derive(Debug)]
struct Entry {
    /// Absolute path with array indices, e.g. `effects.handles[0].ids`.
    path: String,
    /// Where the key (or array element) starts.
    key: usize,
    /// The key and its value.
    span: Range<usize>,
    /// The inline table or array holding the entry, if any.
    inline_parent: Option<String>,
}

/// Table headers and entries of a TOML text, with their spans.
#[derive(Debug, Default)]
pub(crate) struct Spans {
    headers: Vec<(String, usize)>,
    entries: Vec<Entry>,
}

fn join(parent: &str, key: &str) -> String {
    if parent.is_empty() {
        key.to_string()
    } else {
        format!("{parent}.{key}")
    }
}

impl Spans {
    /// Parse `text` (a text that is not valid TOML has no spans).
    pub(crate) fn new(text: &str) -> Self {
        let mut s = Spans::default();
        if let Ok(doc) = ImDocument::parse(text) {
            s.table(doc.as_table(), "");
            s.headers.sort_by_key(|h| h.1);
        }
        s
    }

    fn table(&mut self, t: &Table, path: &str) {
        for (name, item) in t.iter() {
            let p = join(path, name);
            let key = t.key(name).and_then(|k| k.span());
            match item {
                Item::Table(sub) => {
                    if sub.is_dotted() {
                        if let Some(k) = key {
                            let end = sub.span().map_or(k.end, |s| s.end.max(k.end));
                            self.entry(&p, k.start, k.start..end, None);
                        }
                    } else if let (false, Some(s)) = (sub.is_implicit(), sub.span()) {
                        self.headers.push((p.clone(), s.start));
                    }
                    self.table(sub, &p);
                }
                Item::ArrayOfTables(arr) => {
                    for (i, sub) in arr.iter().enumerate() {
                        let pi = format!("{p}[{i}]");
                        if let Some(s) = sub.span() {
                            self.headers.push((pi.clone(), s.start));
                        }
                        self.table(sub, &pi);
                    }
                }
                Item::Value(v) => {
                    if let (Some(k), Some(vs)) = (key, v.span()) {
                        self.entry(&p, k.start, k.start..vs.end, None);
                    }
                    self.value(v, &p);
                }
                Item::None => {}
            }
        }
    }

    fn value(&mut self, v: &Value, path: &str) {
        match v {
            Value::InlineTable(t) => {
                for (name, inner) in t.iter() {
                    let p = join(path, name);
                    if let (Some(k), Some(vs)) = (t.key(name).and_then(|k| k.span()), inner.span())
                    {
                        self.entry(&p, k.start, k.start..vs.end, Some(path));
                    }
                    self.value(inner, &p);
                }
            }
            Value::Array(a) => {
                for (i, el) in a.iter().enumerate() {
                    let p = format!("{path}[{i}]");
                    if let Some(s) = el.span() {
                        self.entry(&p, s.start, s, Some(path));
                    }
                    self.value(el, &p);
                }
            }
            _ => {}
        }
    }

    fn entry(&mut self, path: &str, key: usize, span: Range<usize>, parent: Option<&str>) {
        self.entries.push(Entry {
            path: path.to_string(),
            key,
            span,
            inline_parent: parent.map(str::to_string),
        });
    }

    /// Byte offset where `path` is written (see the module docs).
    pub(crate) fn find(&self, path: &str) -> Option<usize> {
        if let Some(e) = self.entries.iter().find(|e| e.path == path) {
            return Some(e.key);
        }
        if let Some(h) = self.headers.iter().find(|h| h.0 == path) {
            return Some(h.1);
        }
        // the closest written enclosing key, else table header
        let entry = self
            .entries
            .iter()
            .filter(|e| is_prefix(&e.path, path))
            .max_by_key(|e| e.path.len());
        if let Some(e) = entry {
            return Some(e.key);
        }
        self.headers
            .iter()
            .filter(|h| is_prefix(&h.0, path))
            .max_by_key(|h| h.0.len())
            .map(|h| h.1)
    }

    /// The table containing byte `offset` (`""` at the top level; an inline
    /// table or array when the offset is inside one) and the key whose key
    /// or value holds it, both as absolute paths.
    pub(crate) fn context(&self, offset: usize) -> (String, Option<String>) {
        let header = self
            .headers
            .iter()
            .rev()
            .find(|h| h.1 <= offset)
            .map(|h| h.0.clone())
            .unwrap_or_default();
        // the innermost entry holding the offset (array elements count
        // as their array's key)
        let entry = self
            .entries
            .iter()
            .filter(|e| e.span.contains(&offset) || e.span.start == offset)
            .filter(|e| !e.path.ends_with(']'))
            .min_by_key(|e| e.span.len());
        match entry {
            None => (header, None),
            Some(e) => {
                let table = match &e.inline_parent {
                    Some(p) => p.clone(),
                    None => header,
                };
                (table, Some(e.path.clone()))
            }
        }
    }
}

/// `a.b` is a prefix of `a.b.c` and of `a.b[2].c`.
fn is_prefix(prefix: &str, path: &str) -> bool {
    path.len() > prefix.len()
        && path.starts_with(prefix)
        && matches!(path.as_bytes()[prefix.len()], b'.' | b'[')
}

/// 1-based line and column of a byte offset.
pub(crate) fn line_col(text: &str, offset: usize) -> Location {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    Location {
        line,
        column: text[line_start..offset].chars().count() + 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"x\"\n[mesh]\ngenerate = \"bar\"\n\n[effects]\ngravity = [0, -9.8, 0]\ninertia = { dt = 0.01, mass = \"lumped\" }\n\n[[effects.handles]]\nids = [1, 2]\n\n[[effects.handles]]\nplane = { point = [0,0,0], normal = [1,0,0] }\nkeys = [ { frame = 0 }, { frame = 10, translate = [1, 0, 0] } ]\n";

    fn at(path: &str) -> Option<Location> {
        Spans::new(TEXT).find(path).map(|p| line_col(TEXT, p))
    }

    #[test]
    fn finds_plain_dotted_inline_and_indexed_keys() {
        assert_eq!(at("name").unwrap().line, 1);
        assert_eq!(at("mesh.generate").unwrap().line, 3);
        assert_eq!(at("effects.gravity").unwrap().line, 6);
        let dt = at("effects.inertia.dt").unwrap();
        assert_eq!((dt.line, dt.column), (7, 13));
        assert_eq!(at("effects.handles[0].ids").unwrap().line, 10);
        assert_eq!(at("effects.handles[1].plane.normal").unwrap().line, 13);
        let k = at("effects.handles[1].keys[1].translate").unwrap();
        assert_eq!(k.line, 14);
        assert!(k.column > 30, "{k:?}");
        // not written: the enclosing table
        assert_eq!(at("effects.handles[1].center").unwrap().line, 12);
        assert_eq!(at("solver.tol"), None);
    }

    #[test]
    fn context_names_table_and_key() {
        let s = Spans::new(TEXT);
        let off = TEXT.find("gravity").unwrap() + 12;
        let (t, k) = s.context(off);
        assert_eq!(t, "effects");
        assert_eq!(k.as_deref(), Some("effects.gravity"));
        let off = TEXT.find("\"lumped\"").unwrap();
        let (t, k) = s.context(off);
        assert_eq!(t, "effects.inertia");
        assert_eq!(k.as_deref(), Some("effects.inertia.mass"));
    }

    #[test]
    fn dotted_keys_and_invalid_text() {
        let text = "[mesh]\ngenerate = \"bar\"\n\n[energy]\nparams.mu = 2.0\n";
        let s = Spans::new(text);
        assert_eq!(
            s.find("energy.params.mu").map(|o| line_col(text, o).line),
            Some(5)
        );
        assert_eq!(
            s.find("energy.params").map(|o| line_col(text, o).line),
            Some(5)
        );
        assert!(Spans::new("[mesh\n").find("mesh").is_none());
    }
}
