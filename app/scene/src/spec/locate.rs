//! Finding keys in TOML text (for error positions), without a second parser.
//!
//! The scanner follows table headers (`[a.b]`, `[[a.c]]` with a running
//! index per array of tables) and `key = value` lines (dotted keys too), so
//! a key path such as `effects.handles[1].keys[0].frame` can be mapped back to
//! the line where it is written. Inline tables and arrays are searched
//! textually on the line of their parent key. This is best effort: when a
//! key is not written (a missing key, a default), the closest enclosing
//! table header is returned instead, and `None` when even that is absent.

use super::super::error::Location;

/// One `key = value` line, with its absolute key path.
#[derive(Debug)]
struct Entry {
    /// Path with array indices, e.g. `effects.handles[0].ids`.
    path: String,
    /// Byte offset of the key in the text.
    offset: usize,
    /// Byte range of the whole line.
    line: (usize, usize),
}

/// Headers and entries of a TOML text.
#[derive(Debug)]
pub(crate) struct Outline {
    headers: Vec<(String, usize)>,
    entries: Vec<Entry>,
}

/// Strip a trailing comment (outside quotes) and surrounding blanks.
fn strip_comment(line: &str) -> &str {
    let mut in_str: Option<char> = None;
    for (i, c) in line.char_indices() {
        match (in_str, c) {
            (None, '#') => return line[..i].trim_end(),
            (None, '"' | '\'') => in_str = Some(c),
            (Some(q), c) if c == q => in_str = None,
            _ => {}
        }
    }
    line.trim_end()
}

/// Normalise a dotted key: drop blanks and quotes around parts.
fn normalise_key(k: &str) -> String {
    k.split('.')
        .map(|p| p.trim().trim_matches('"').trim_matches('\''))
        .collect::<Vec<_>>()
        .join(".")
}

/// Position of the first `=` outside quotes.
fn find_eq(line: &str) -> Option<usize> {
    let mut in_str: Option<char> = None;
    for (i, c) in line.char_indices() {
        match (in_str, c) {
            (None, '=') => return Some(i),
            (None, '"' | '\'') => in_str = Some(c),
            (Some(q), c) if c == q => in_str = None,
            _ => {}
        }
    }
    None
}

impl Outline {
    /// Scan `text`.
    pub(crate) fn new(text: &str) -> Self {
        let mut headers = Vec::new();
        let mut entries = Vec::new();
        let mut counts: std::collections::HashMap<String, usize> = Default::default();
        let mut current = String::new();
        let mut start = 0usize;
        for raw in text.split_inclusive('\n') {
            let end = start + raw.len();
            let body = strip_comment(raw.trim_end_matches(['\n', '\r']));
            let trimmed = body.trim_start();
            let indent = body.len() - trimmed.len();
            if let Some(h) = trimmed.strip_prefix("[[") {
                let name = normalise_key(h.trim_end().trim_end_matches("]]"));
                // an array of tables nested in one: index the parent prefix,
                // never the array itself (each `[[…]]` opens a new element)
                let full = match name.rsplit_once('.') {
                    Some((parent, last)) => format!("{}.{last}", indexed(&current, parent)),
                    None => name.clone(),
                };
                let k = counts.entry(full.clone()).or_insert(0);
                current = format!("{full}[{k}]");
                *k += 1;
                headers.push((current.clone(), start + indent));
            } else if let Some(h) = trimmed.strip_prefix('[') {
                let name = normalise_key(h.trim_end().trim_end_matches(']'));
                current = indexed(&current, &name);
                headers.push((current.clone(), start + indent));
            } else if let Some(eq) = find_eq(trimmed) {
                let key = normalise_key(&trimmed[..eq]);
                if !key.is_empty() {
                    let path = if current.is_empty() {
                        key
                    } else {
                        format!("{current}.{key}")
                    };
                    entries.push(Entry {
                        path,
                        offset: start + indent,
                        line: (start, end),
                    });
                }
            }
            start = end;
        }
        Outline { headers, entries }
    }

    /// Byte offset where `path` is written (see the module docs).
    pub(crate) fn find(&self, text: &str, path: &str) -> Option<usize> {
        if let Some(e) = self.entries.iter().find(|e| e.path == path) {
            return Some(e.offset);
        }
        // an inline table / array: the longest written prefix, then the
        // remaining key names searched on (and after) that line
        let mut best: Option<&Entry> = None;
        for e in &self.entries {
            if is_prefix(&e.path, path) && best.is_none_or(|b| e.path.len() > b.path.len()) {
                best = Some(e);
            }
        }
        if let Some(e) = best {
            let rest = &path[e.path.len()..];
            return Some(search_rest(text, e, rest).unwrap_or(e.offset));
        }
        // a table header that is the path or encloses it
        let mut header: Option<&(String, usize)> = None;
        for h in &self.headers {
            if (h.0 == path || is_prefix(&h.0, path))
                && header.is_none_or(|b| h.0.len() > b.0.len())
            {
                header = Some(h);
            }
        }
        header.map(|h| h.1)
    }

    /// The table containing byte `offset` (`""` at the top level) and the
    /// key written on that line, both as absolute paths.
    pub(crate) fn context(&self, text: &str, offset: usize) -> (String, Option<String>) {
        let header = self
            .headers
            .iter()
            .rev()
            .find(|h| h.1 <= offset)
            .map(|h| h.0.clone())
            .unwrap_or_default();
        // the key of the entry whose line holds the offset, or the last one before it
        let entry = self
            .entries
            .iter()
            .rev()
            .find(|e| e.offset <= offset && e.path.starts_with(&header));
        let Some(e) = entry else {
            return (header, None);
        };
        if offset >= e.line.1 && !inside_open_bracket(text, e.line.0, offset) {
            return (header, None);
        }
        // inline table on the line: `key = { a = 1, b = 2 }`
        let line = &text[e.line.0..offset.min(text.len())];
        if let Some(open) = line.rfind('{')
            && !line[open..].contains('}')
        {
            let inner = &line[open + 1..];
            let last_key = inner
                .rsplit([',', '{'])
                .next()
                .and_then(|s| find_eq(s).map(|i| normalise_key(&s[..i])));
            let table = e.path.clone();
            return (table.clone(), last_key.map(|k| format!("{table}.{k}")));
        }
        (header, Some(e.path.clone()))
    }
}

/// Whether an unclosed `[` or `{` between `from` and `to` continues a value
/// over several lines.
fn inside_open_bracket(text: &str, from: usize, to: usize) -> bool {
    let mut depth = 0i32;
    for c in text[from..to.min(text.len())].chars() {
        match c {
            '[' | '{' => depth += 1,
            ']' | '}' => depth -= 1,
            _ => {}
        }
    }
    depth > 0
}

/// `a.b` is a prefix of `a.b.c` and of `a.b[2].c`.
fn is_prefix(prefix: &str, path: &str) -> bool {
    path.len() > prefix.len()
        && path.starts_with(prefix)
        && matches!(path.as_bytes()[prefix.len()], b'.' | b'[')
}

/// `name` under `current` for a table header: headers are absolute, except
/// that an array of tables already entered keeps its index
/// (`[effects.handles]` inside `[[effects.handles]]` #1 → `effects.handles[1]`).
fn indexed(current: &str, name: &str) -> String {
    // re-apply the indices of the leading parts the header shares with `current`
    let cur: Vec<&str> = current.split('.').collect();
    let mut matching = true;
    let mut parts = Vec::new();
    for (i, part) in name.split('.').enumerate() {
        match cur.get(i) {
            Some(c) if matching && c.split('[').next() == Some(part) => parts.push(*c),
            _ => {
                matching = false;
                parts.push(part);
            }
        }
    }
    parts.join(".")
}

/// Search the key names of `rest` (e.g. `[1].frame` or `.mu`) from the entry's line on.
fn search_rest(text: &str, e: &Entry, rest: &str) -> Option<usize> {
    let mut pos = e.offset;
    for part in rest.split('.').filter(|p| !p.is_empty()) {
        let (name, index) = match part.split_once('[') {
            Some((n, i)) => (n, i.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        if !name.is_empty() {
            pos = find_word(text, pos, name)?;
        }
        if let Some(k) = index {
            // skip to the k-th `{` after the key (inline array of tables)
            let mut p = pos;
            for _ in 0..=k {
                p = p + text[p..].find('{')? + 1;
            }
            pos = p;
        }
    }
    Some(pos)
}

/// First occurrence of `word` as a whole key at or after `from`.
fn find_word(text: &str, from: usize, word: &str) -> Option<usize> {
    let mut p = from;
    while let Some(i) = text[p..].find(word) {
        let at = p + i;
        let before = text[..at].chars().next_back();
        let after = text[at + word.len()..].chars().next();
        let boundary = |c: Option<char>| c.is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        if boundary(before) && boundary(after) {
            return Some(at);
        }
        p = at + word.len();
    }
    None
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
        let o = Outline::new(TEXT);
        o.find(TEXT, path).map(|p| line_col(TEXT, p))
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
        let o = Outline::new(TEXT);
        let off = TEXT.find("gravity").unwrap() + 12;
        let (t, k) = o.context(TEXT, off);
        assert_eq!(t, "effects");
        assert_eq!(k.as_deref(), Some("effects.gravity"));
        let off = TEXT.find("\"lumped\"").unwrap();
        let (t, k) = o.context(TEXT, off);
        assert_eq!(t, "effects.inertia");
        assert_eq!(k.as_deref(), Some("effects.inertia.mass"));
    }
}
