//! A streaming whitespace tokenizer that remembers line numbers, plus
//! number parsing with error messages that say what was expected where.

use crate::error::ParseError;

/// Splits text into whitespace-separated tokens, skipping comments that
/// start with `comment` (if any) and run to the end of the line.
pub(crate) struct Tokens<'a> {
    text: &'a str,
    pos: usize,
    line: usize,
    last_line: usize,
    comment: Option<u8>,
}

/// Largest capacity we pre-allocate from a count read in a file: a
/// malicious count must not make us allocate more than the file could hold.
pub(crate) fn capacity_hint(count: usize, text_len: usize) -> usize {
    count.min(text_len / 2 + 1)
}

impl<'a> Tokens<'a> {
    pub(crate) fn new(text: &'a str, comment: Option<u8>) -> Self {
        Tokens {
            text,
            pos: 0,
            line: 1,
            last_line: 1,
            comment,
        }
    }

    /// Tokens of `text[pos..]`, where `pos` starts line number `line`.
    /// `pos` must be a char boundary (callers pass offsets just after `\n`).
    pub(crate) fn starting_at(text: &'a str, pos: usize, line: usize, comment: Option<u8>) -> Self {
        Tokens {
            text,
            pos: pos.min(text.len()),
            line,
            last_line: line,
            comment,
        }
    }

    /// Skip whole lines until (and including) the next blank line.
    pub(crate) fn skip_past_blank_line(&mut self) {
        self.skip_line();
        let bytes = self.text.as_bytes();
        while self.pos < bytes.len() {
            // at a '\n': move to the next line
            self.pos += 1;
            self.line += 1;
            let start = self.pos;
            self.skip_line();
            if self.text[start..self.pos].trim().is_empty() {
                return;
            }
        }
    }

    /// The (1-based) line of the last token returned.
    pub(crate) fn last_line(&self) -> usize {
        self.last_line
    }

    /// Length of the whole text (for [`capacity_hint`]).
    pub(crate) fn text_len(&self) -> usize {
        self.text.len()
    }

    fn skip_space(&mut self) {
        let bytes = self.text.as_bytes();
        while self.pos < bytes.len() {
            let b = bytes[self.pos];
            if b == b'\n' {
                self.line += 1;
                self.pos += 1;
            } else if b.is_ascii_whitespace() {
                self.pos += 1;
            } else if Some(b) == self.comment {
                while self.pos < bytes.len() && bytes[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
    }

    /// The next token and its line, or `None` at the end of the text.
    pub(crate) fn next_token(&mut self) -> Option<(&'a str, usize)> {
        self.skip_space();
        let bytes = self.text.as_bytes();
        if self.pos >= bytes.len() {
            return None;
        }
        let start = self.pos;
        while self.pos < bytes.len() && !bytes[self.pos].is_ascii_whitespace() {
            if Some(bytes[self.pos]) == self.comment {
                break;
            }
            self.pos += 1;
        }
        self.last_line = self.line;
        // `start..pos` is delimited by ASCII bytes, hence on char boundaries.
        Some((&self.text[start..self.pos], self.line))
    }

    /// The next token without consuming it.
    pub(crate) fn peek(&mut self) -> Option<(&'a str, usize)> {
        let (pos, line, last) = (self.pos, self.line, self.last_line);
        let t = self.next_token();
        self.pos = pos;
        self.line = line;
        self.last_line = last;
        t
    }

    /// Skip the rest of the current line (after the last token read).
    pub(crate) fn skip_line(&mut self) {
        let bytes = self.text.as_bytes();
        while self.pos < bytes.len() && bytes[self.pos] != b'\n' {
            self.pos += 1;
        }
    }

    /// The next token, or an "unexpected end of file" error naming `what`.
    pub(crate) fn expect(&mut self, what: &str) -> Result<(&'a str, usize), ParseError> {
        self.next_token().ok_or_else(|| {
            ParseError::line(
                self.last_line,
                format!("unexpected end of file: expected {what}"),
            )
        })
    }

    /// The next token, which must equal `word` (ASCII case-insensitive).
    pub(crate) fn keyword(&mut self, word: &str) -> Result<usize, ParseError> {
        let (tok, line) = self.expect(&format!("`{word}`"))?;
        if tok.eq_ignore_ascii_case(word) {
            Ok(line)
        } else {
            Err(ParseError::line(
                line,
                format!("expected `{word}`, found `{}`", shorten(tok)),
            ))
        }
    }

    /// The next token as a non-negative integer.
    pub(crate) fn usize(&mut self, what: &str) -> Result<(usize, usize), ParseError> {
        let (tok, line) = self.expect(what)?;
        Ok((parse_usize(tok, line, what)?, line))
    }

    /// The next token as a signed integer.
    pub(crate) fn i64(&mut self, what: &str) -> Result<(i64, usize), ParseError> {
        let (tok, line) = self.expect(what)?;
        Ok((parse_i64(tok, line, what)?, line))
    }

    /// The next token as a finite float.
    pub(crate) fn f64(&mut self, what: &str) -> Result<f64, ParseError> {
        let (tok, line) = self.expect(what)?;
        parse_f64(tok, line, what)
    }
}

/// Cut long tokens in messages.
pub(crate) fn shorten(tok: &str) -> String {
    if tok.chars().count() <= 40 {
        tok.to_string()
    } else {
        let s: String = tok.chars().take(40).collect();
        format!("{s}…")
    }
}

pub(crate) fn parse_usize(tok: &str, line: usize, what: &str) -> Result<usize, ParseError> {
    tok.parse::<usize>().map_err(|_| {
        ParseError::line(
            line,
            format!(
                "expected {what} (a non-negative integer), found `{}`",
                shorten(tok)
            ),
        )
    })
}

pub(crate) fn parse_i64(tok: &str, line: usize, what: &str) -> Result<i64, ParseError> {
    tok.parse::<i64>().map_err(|_| {
        ParseError::line(
            line,
            format!("expected {what} (an integer), found `{}`", shorten(tok)),
        )
    })
}

pub(crate) fn parse_f64(tok: &str, line: usize, what: &str) -> Result<f64, ParseError> {
    match tok.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(ParseError::line(
            line,
            format!("{what} is not finite: `{}`", shorten(tok)),
        )),
        Err(_) => Err(ParseError::line(
            line,
            format!("expected {what} (a number), found `{}`", shorten(tok)),
        )),
    }
}

/// Decode file bytes as UTF-8, replacing invalid sequences (mesh formats
/// are ASCII; stray bytes in comments must not stop us).
pub(crate) fn decode(bytes: &[u8]) -> std::borrow::Cow<'_, str> {
    // the strict check first: it runs word-at-a-time over ASCII, where the
    // lossy decoder walks chunk by chunk (0.02 s of a 54 MB file)
    match std::str::from_utf8(bytes) {
        Ok(text) => std::borrow::Cow::Borrowed(text),
        Err(_) => String::from_utf8_lossy(bytes),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_track_lines_and_comments() {
        let mut t = Tokens::new("a b # c d\r\n\n e", Some(b'#'));
        assert_eq!(t.next_token(), Some(("a", 1)));
        assert_eq!(t.next_token(), Some(("b", 1)));
        assert_eq!(t.peek(), Some(("e", 3)));
        assert_eq!(t.next_token(), Some(("e", 3)));
        assert_eq!(t.next_token(), None);
        let err = t.expect("a vertex").unwrap_err();
        assert_eq!(
            err.to_string(),
            "line 3: unexpected end of file: expected a vertex"
        );
    }

    #[test]
    fn numbers_are_checked() {
        assert!(
            parse_f64("nan", 4, "x")
                .unwrap_err()
                .to_string()
                .contains("not finite")
        );
        assert!(parse_f64("1.5.2", 4, "x").is_err());
        assert_eq!(parse_f64("6.14986e-005", 1, "x").unwrap(), 6.14986e-5);
        assert!(
            parse_usize("-1", 2, "a count")
                .unwrap_err()
                .to_string()
                .contains("line 2")
        );
        assert!(shorten(&"x".repeat(100)).ends_with('…'));
    }
}
