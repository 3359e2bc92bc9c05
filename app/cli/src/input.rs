//! Parsing command-line values: the deformation gradient `--F` and `--param NAME=VALUE`.

use std::fmt;

/// A square matrix given row-major, e.g. `"1 0 0; 0 1 0; 0 0 1"`.
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixArg {
    /// Rows, each of the same length as the number of rows.
    pub rows: Vec<Vec<f64>>,
}

impl MatrixArg {
    /// Number of rows (= columns).
    pub fn dim(&self) -> usize {
        self.rows.len()
    }
}

/// What is wrong with a `--F` value.
#[derive(Clone, Debug, PartialEq)]
pub enum MatrixError {
    /// Nothing but separators.
    Empty,
    /// An entry that does not parse as a number.
    NotANumber {
        /// 1-based row.
        row: usize,
        /// 1-based column.
        col: usize,
        /// The text.
        text: String,
    },
    /// NaN or ±∞ (including overflow such as `1e400`).
    NotFinite {
        /// 1-based row.
        row: usize,
        /// 1-based column.
        col: usize,
        /// The text.
        text: String,
    },
    /// A row of the wrong length.
    RowLength {
        /// 1-based row.
        row: usize,
        /// Entries found.
        found: usize,
        /// Entries expected (the number of rows / the dimension).
        expected: usize,
    },
    /// The number of rows does not fit the dimension.
    RowCount {
        /// Rows found.
        found: usize,
        /// Rows expected.
        expected: usize,
    },
    /// Inferred size not 2×2 or 3×3 (no `--dim` given).
    BadSize {
        /// Rows found.
        rows: usize,
    },
}

impl fmt::Display for MatrixError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MatrixError::Empty => write!(
                f,
                "--F is empty; expected rows separated by `;`, e.g. --F \"1 0; 0 1\""
            ),
            MatrixError::NotANumber { row, col, text } => {
                write!(
                    f,
                    "--F: entry `{text}` at row {row}, column {col} is not a number"
                )
            }
            MatrixError::NotFinite { row, col, text } => write!(
                f,
                "--F: entry `{text}` at row {row}, column {col} is not finite (NaN and infinities are not allowed)"
            ),
            MatrixError::RowLength {
                row,
                found,
                expected,
            } => write!(
                f,
                "--F: row {row} has {found} entr{}, expected {expected}",
                if *found == 1 { "y" } else { "ies" }
            ),
            MatrixError::RowCount { found, expected } => write!(
                f,
                "--F has {found} row{} but a {expected}D deformation gradient needs {expected} (rows are separated by `;`)",
                if *found == 1 { "" } else { "s" }
            ),
            MatrixError::BadSize { rows } => write!(
                f,
                "--F has {rows} row{}; only 2×2 and 3×3 matrices are supported",
                if *rows == 1 { "" } else { "s" }
            ),
        }
    }
}

impl std::error::Error for MatrixError {}

/// Parse `text` as a square matrix: rows separated by `;` (one trailing `;`
/// allowed), entries by whitespace or `,`. With `dim` the size must be
/// dim×dim; without it, 2×2 or 3×3 is inferred from the row count.
pub fn parse_matrix(text: &str, dim: Option<usize>) -> Result<MatrixArg, MatrixError> {
    let mut parts: Vec<&str> = text.split(';').collect();
    if parts.len() > 1 && parts.last().is_some_and(|p| p.trim().is_empty()) {
        parts.pop();
    }
    if parts.iter().all(|p| p.trim().is_empty()) {
        return Err(MatrixError::Empty);
    }
    let expected = match dim {
        Some(d) => d,
        None if parts.len() == 2 || parts.len() == 3 => parts.len(),
        None => return Err(MatrixError::BadSize { rows: parts.len() }),
    };
    if parts.len() != expected {
        return Err(MatrixError::RowCount {
            found: parts.len(),
            expected,
        });
    }
    let mut rows = Vec::with_capacity(expected);
    for (r, part) in parts.iter().enumerate() {
        let entries: Vec<&str> = part
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .collect();
        if entries.len() != expected {
            return Err(MatrixError::RowLength {
                row: r + 1,
                found: entries.len(),
                expected,
            });
        }
        let mut row = Vec::with_capacity(expected);
        for (c, e) in entries.iter().enumerate() {
            let (row1, col1, text) = (r + 1, c + 1, e.to_string());
            let v: f64 = e.parse().map_err(|_| MatrixError::NotANumber {
                row: row1,
                col: col1,
                text: text.clone(),
            })?;
            if !v.is_finite() {
                return Err(MatrixError::NotFinite {
                    row: row1,
                    col: col1,
                    text,
                });
            }
            row.push(v);
        }
        rows.push(row);
    }
    Ok(MatrixArg { rows })
}

/// What is wrong with a `--param` value.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamArgError {
    /// Not of the form NAME=VALUE.
    Syntax {
        /// The argument.
        arg: String,
    },
    /// VALUE does not parse.
    NotANumber {
        /// The parameter.
        name: String,
        /// The text.
        text: String,
    },
    /// VALUE is NaN or infinite.
    NotFinite {
        /// The parameter.
        name: String,
        /// The text.
        text: String,
    },
    /// The same parameter given twice.
    Duplicate {
        /// The parameter.
        name: String,
    },
}

impl fmt::Display for ParamArgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamArgError::Syntax { arg } => {
                write!(
                    f,
                    "--param `{arg}` is not of the form NAME=VALUE (e.g. --param mu=2.5)"
                )
            }
            ParamArgError::NotANumber { name, text } => {
                write!(f, "--param {name}: `{text}` is not a number")
            }
            ParamArgError::NotFinite { name, text } => write!(
                f,
                "--param {name}: `{text}` is not finite (NaN and infinities are not allowed)"
            ),
            ParamArgError::Duplicate { name } => {
                write!(f, "--param {name} is given more than once")
            }
        }
    }
}

impl std::error::Error for ParamArgError {}

/// Parse every `NAME=VALUE` (names are checked against the energy later).
pub fn parse_params(args: &[String]) -> Result<Vec<(String, f64)>, ParamArgError> {
    let mut out: Vec<(String, f64)> = Vec::with_capacity(args.len());
    for arg in args {
        let Some((name, text)) = arg.split_once('=') else {
            return Err(ParamArgError::Syntax { arg: arg.clone() });
        };
        let (name, text) = (name.trim(), text.trim());
        let valid_name = name
            .chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_')
            && name.chars().all(|c| c.is_alphanumeric() || c == '_');
        if !valid_name {
            return Err(ParamArgError::Syntax { arg: arg.clone() });
        }
        let v: f64 = text.parse().map_err(|_| ParamArgError::NotANumber {
            name: name.to_string(),
            text: text.to_string(),
        })?;
        if !v.is_finite() {
            return Err(ParamArgError::NotFinite {
                name: name.to_string(),
                text: text.to_string(),
            });
        }
        if out.iter().any(|(n, _)| n == name) {
            return Err(ParamArgError::Duplicate {
                name: name.to_string(),
            });
        }
        out.push((name.to_string(), v));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_rows_and_infers_dim() {
        let m = parse_matrix("1 2; 3 4", None).unwrap();
        assert_eq!(m.rows, vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
        let m = parse_matrix(" 1,0,0 ; 0 1 0;0 0 -2.5e-1; ", Some(3)).unwrap();
        assert_eq!(m.rows[2], vec![0.0, 0.0, -0.25]);
    }

    #[test]
    fn matrix_errors_say_where() {
        assert_eq!(parse_matrix(" ; ", None), Err(MatrixError::Empty));
        assert_eq!(
            parse_matrix("1 2; 3", None),
            Err(MatrixError::RowLength {
                row: 2,
                found: 1,
                expected: 2
            })
        );
        assert_eq!(
            parse_matrix("1 0; 0 1", Some(3)),
            Err(MatrixError::RowCount {
                found: 2,
                expected: 3
            })
        );
        assert_eq!(
            parse_matrix("1", None),
            Err(MatrixError::BadSize { rows: 1 })
        );
        assert!(matches!(
            parse_matrix("1 x; 0 1", None),
            Err(MatrixError::NotANumber { row: 1, col: 2, .. })
        ));
        for bad in ["nan", "inf", "-infinity", "1e400"] {
            let text = format!("1 0; 0 {bad}");
            assert!(matches!(
                parse_matrix(&text, None),
                Err(MatrixError::NotFinite { row: 2, col: 2, .. })
            ));
        }
        let msg = parse_matrix("1 2 3; 4 5; 6 7 8", Some(3))
            .unwrap_err()
            .to_string();
        assert!(msg.contains("row 2") && msg.contains("expected 3"), "{msg}");
    }

    #[test]
    fn params_parse_and_reject() {
        let p = parse_params(&["mu=2".into(), " lambda = -1e3 ".into()]).unwrap();
        assert_eq!(
            p,
            vec![("mu".to_string(), 2.0), ("lambda".to_string(), -1000.0)]
        );
        assert!(matches!(
            parse_params(&["mu".into()]),
            Err(ParamArgError::Syntax { .. })
        ));
        assert!(matches!(
            parse_params(&["=1".into()]),
            Err(ParamArgError::Syntax { .. })
        ));
        assert!(matches!(
            parse_params(&["mu=abc".into()]),
            Err(ParamArgError::NotANumber { .. })
        ));
        assert!(matches!(
            parse_params(&["mu=NaN".into()]),
            Err(ParamArgError::NotFinite { .. })
        ));
        assert!(matches!(
            parse_params(&["mu=1".into(), "mu=2".into()]),
            Err(ParamArgError::Duplicate { .. })
        ));
    }
}
