//! Cutting a source text into statements.
//!
//! Statements end at `;` and at newlines outside parentheses, except that a
//! line ending in an operator, `=`, `(` or `,`, or followed by a line that
//! starts with an operator, continues. A line starting with a keyword
//! (`param`, `let`, `psi`, `dim`) always starts a new statement, so an
//! unclosed parenthesis cannot swallow the rest of the file.

use crate::span::Span;

/// Byte ranges of the statements (blank and comment-only pieces dropped).
pub fn split_statements(source: &str) -> Vec<Span> {
    let bytes = source.as_bytes();
    let mut out = Vec::new();
    let mut start = 0;
    let mut depth = 0usize;
    let mut in_comment = false;
    let mut last_sig: Option<u8> = None;
    let mut i = 0;
    let push = |start: usize, end: usize, sig: bool, out: &mut Vec<Span>| {
        if sig {
            out.push(Span::new(start, end));
        }
    };
    while i < bytes.len() {
        let c = bytes[i];
        if in_comment {
            if c == b'\n' {
                in_comment = false;
            } else {
                i += 1;
                continue;
            }
        }
        match c {
            b'#' => in_comment = true,
            b'(' => depth += 1,
            b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        let ends = match c {
            b';' => true,
            // A line starting with a keyword always starts a new statement
            // (so an unclosed parenthesis cannot swallow the rest of the file).
            b'\n' if next_line_starts_keyword(bytes, i + 1) => true,
            b'\n' if depth == 0 => {
                let continues_back = matches!(
                    last_sig,
                    Some(b'+' | b'-' | b'*' | b'/' | b'^' | b'=' | b'(' | b',')
                );
                !continues_back && !next_line_continues(bytes, i + 1)
            }
            _ => false,
        };
        if ends {
            push(start, i, last_sig.is_some(), &mut out);
            start = i + 1;
            last_sig = None;
            depth = 0;
        } else if !c.is_ascii_whitespace() && c != b'#' {
            last_sig = Some(c);
        }
        i += 1;
    }
    push(start, bytes.len(), last_sig.is_some(), &mut out);
    out
}

/// Whether the next line starts (after indentation) with a statement keyword.
pub(crate) fn next_line_starts_keyword(bytes: &[u8], mut i: usize) -> bool {
    while i < bytes.len() && (bytes[i] == b' ' || bytes[i] == b'\t' || bytes[i] == b'\r') {
        i += 1;
    }
    let rest = &bytes[i..];
    ["param", "let", "psi", "dim", "fiber", "fibre"]
        .iter()
        .any(|kw| {
            rest.starts_with(kw.as_bytes())
                && rest
                    .get(kw.len())
                    .is_none_or(|c| !(c.is_ascii_alphanumeric() || *c == b'_'))
        })
}

/// Whether the next non-blank, non-comment line starts with a binary operator.
pub(crate) fn next_line_continues(bytes: &[u8], mut i: usize) -> bool {
    while i < bytes.len() {
        match bytes[i] {
            b' ' | b'\t' | b'\r' | b'\n' => i += 1,
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'+' | b'-' | b'*' | b'/' | b'^' => return true,
            _ => return false,
        }
    }
    false
}
