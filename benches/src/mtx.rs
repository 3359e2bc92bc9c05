//! Matrix Market files of the symmetric Newton matrices ecc factorises, for
//! timing other sparse Cholesky codes on exactly the same matrix
//! (benches/cholmod: CHOLMOD as the reference of issue #11).
//!
//! Format: `%%MatrixMarket matrix coordinate real symmetric`, 1-based, the
//! **lower** triangle only (the Matrix Market rule for symmetric matrices;
//! `cholmod_read_sparse` reads it as is). ecc stores the upper triangle in
//! compressed sparse columns (see `ecc_fem::Pattern`): upper entry (i, j),
//! i ≤ j, is written as lower entry (j, i). Values are printed in Rust's
//! shortest round-trip form, so reading them back (here or with C's
//! `strtod`) gives the same bits.

use std::fmt;
use std::io::{BufRead, Write};

/// A symmetric matrix as the upper triangle in compressed sparse columns
/// (rows strictly increasing in each column, the diagonal last).
#[derive(Clone, Debug, PartialEq)]
pub struct UpperCsc {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
}

impl UpperCsc {
    /// The `n`×`n` matrix of the upper entries `(row, column, value)`,
    /// row ≤ column, in any order (sorted here by column, then row; a
    /// repeated entry is kept twice: callers check or avoid them).
    pub fn from_entries(n: usize, mut entries: Vec<(usize, usize, f64)>) -> UpperCsc {
        entries.sort_unstable_by_key(|&(i, j, _)| (j, i));
        let mut col_ptr = vec![0usize; n + 1];
        for &(_, j, _) in &entries {
            col_ptr[j + 1] += 1;
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        UpperCsc {
            n,
            col_ptr,
            row_idx: entries.iter().map(|e| e.0).collect(),
            values: entries.iter().map(|e| e.2).collect(),
        }
    }
}

/// Why a Matrix Market file could not be read (with its 1-based line).
#[derive(Debug)]
pub enum MtxError {
    Io(std::io::Error),
    Parse { line: usize, message: String },
}

impl fmt::Display for MtxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MtxError::Io(e) => write!(f, "{e}"),
            MtxError::Parse { line, message } => write!(f, "line {line}: {message}"),
        }
    }
}

impl std::error::Error for MtxError {}

impl From<std::io::Error> for MtxError {
    fn from(e: std::io::Error) -> Self {
        MtxError::Io(e)
    }
}

/// Write `m` (upper CSC) as a symmetric coordinate file, lower triangle;
/// each of `comments` becomes a `%` line after the banner.
pub fn write(out: &mut impl Write, m: &UpperCsc, comments: &[String]) -> std::io::Result<()> {
    writeln!(out, "%%MatrixMarket matrix coordinate real symmetric")?;
    for c in comments {
        for line in c.lines() {
            writeln!(out, "% {line}")?;
        }
    }
    writeln!(out, "{} {} {}", m.n, m.n, m.row_idx.len())?;
    for j in 0..m.n {
        for k in m.col_ptr[j]..m.col_ptr[j + 1] {
            // upper (i, j) → lower (j, i), 1-based
            writeln!(out, "{} {} {:e}", j + 1, m.row_idx[k] + 1, m.values[k])?;
        }
    }
    Ok(())
}

fn parse_err(line: usize, message: impl Into<String>) -> MtxError {
    MtxError::Parse {
        line,
        message: message.into(),
    }
}

/// The banner, comments and size line: (n, entries, lines read).
fn header(
    lines: &mut impl Iterator<Item = std::io::Result<String>>,
) -> Result<(usize, usize, usize), MtxError> {
    let banner = lines.next().ok_or_else(|| parse_err(1, "empty file"))??;
    let words: Vec<String> = banner.split_whitespace().map(str::to_lowercase).collect();
    if words
        != [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "real",
            "symmetric",
        ]
    {
        return Err(parse_err(
            1,
            format!("expected `%%MatrixMarket matrix coordinate real symmetric`, found `{banner}`"),
        ));
    }
    let mut no = 1;
    for line in lines {
        let line = line?;
        no += 1;
        if line.starts_with('%') || line.trim().is_empty() {
            continue;
        }
        let f: Vec<usize> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|e| parse_err(no, format!("size line `{line}`: {e}")))?;
        return match f[..] {
            [r, c, nnz] if r == c => Ok((r, nnz, no)),
            _ => Err(parse_err(
                no,
                format!("expected `n n entries`, found `{line}`"),
            )),
        };
    }
    Err(parse_err(no, "no size line"))
}

/// One entry line → upper (row i, column j, value), i ≤ j, 0-based.
fn entry(line: &str, no: usize, n: usize) -> Result<(usize, usize, f64), MtxError> {
    let mut f = line.split_whitespace();
    let mut index = |what: &str| -> Result<usize, MtxError> {
        let s = f
            .next()
            .ok_or_else(|| parse_err(no, format!("missing {what}")))?;
        match s.parse::<usize>() {
            Ok(k) if (1..=n).contains(&k) => Ok(k - 1),
            _ => Err(parse_err(no, format!("{what} `{s}` is not in 1..={n}"))),
        }
    };
    let (r, c) = (index("row")?, index("column")?);
    let s = f.next().ok_or_else(|| parse_err(no, "missing value"))?;
    let v: f64 = s
        .parse()
        .map_err(|e| parse_err(no, format!("value `{s}`: {e}")))?;
    if r < c {
        return Err(parse_err(
            no,
            format!("entry ({}, {}) above the diagonal", r + 1, c + 1),
        ));
    }
    Ok((c, r, v))
}

/// Read a file written by [`write`](fn@write) (any order of the lower-triangle
/// entries; duplicates, entries above the diagonal and a missing diagonal
/// are errors).
pub fn read(input: impl BufRead) -> Result<UpperCsc, MtxError> {
    let mut lines = input.lines();
    let (n, nnz, mut no) = header(&mut lines)?;
    let mut entries = Vec::with_capacity(nnz);
    for line in lines {
        let line = line?;
        no += 1;
        if line.starts_with('%') || line.trim().is_empty() {
            continue;
        }
        entries.push(entry(&line, no, n)?);
    }
    if entries.len() != nnz {
        return Err(parse_err(
            no,
            format!("{} entries, the size line says {nnz}", entries.len()),
        ));
    }
    let m = UpperCsc::from_entries(n, entries);
    for j in 0..n {
        let rows = &m.row_idx[m.col_ptr[j]..m.col_ptr[j + 1]];
        if let Some(w) = rows.windows(2).find(|w| w[0] == w[1]) {
            return Err(parse_err(
                no,
                format!("entry ({}, {}) repeated", j + 1, w[0] + 1),
            ));
        }
    }
    for j in 0..n {
        let rows = &m.row_idx[m.col_ptr[j]..m.col_ptr[j + 1]];
        if rows.last() != Some(&j) {
            return Err(parse_err(
                no,
                format!("no diagonal entry ({0}, {0})", j + 1),
            ));
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 3×3 upper CSC: [[4, 1, 0], [1, 5, -2.5e-300], [0, -2.5e-300, 1/3]].
    fn small() -> UpperCsc {
        UpperCsc {
            n: 3,
            col_ptr: vec![0, 1, 3, 5],
            row_idx: vec![0, 0, 1, 1, 2],
            values: vec![4.0, 1.0, 5.0, -2.5e-300, 1.0 / 3.0],
        }
    }

    #[test]
    fn round_trip_is_bitwise_and_lower_triangular() {
        let m = small();
        let mut buf = Vec::new();
        write(&mut buf, &m, &["mesh: test\nsecond line".into()]).unwrap();
        let text = String::from_utf8(buf.clone()).unwrap();
        assert!(text.starts_with(
            "%%MatrixMarket matrix coordinate real symmetric\n% mesh: test\n% second line\n3 3 5\n"
        ));
        // upper (0, 1) is written as lower (2, 1) in 1-based indices
        assert!(text.contains("\n2 1 1e0\n"), "{text}");
        let back = read(buf.as_slice()).unwrap();
        assert_eq!(back, m);
        assert_eq!(back.values[4].to_bits(), (1.0f64 / 3.0).to_bits());
    }

    #[test]
    fn entries_in_any_order_are_sorted() {
        let text =
            "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n2 2 2.0\n2 1 -1\n1 1 3\n";
        let m = read(text.as_bytes()).unwrap();
        assert_eq!(m.col_ptr, vec![0, 1, 3]);
        assert_eq!(m.row_idx, vec![0, 0, 1]);
        assert_eq!(m.values, vec![3.0, -1.0, 2.0]);
    }

    #[test]
    fn bad_files_are_located_errors() {
        let cases = [
            (
                "%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 1\n",
                "line 1",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n",
                "above the diagonal",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 1\n",
                "no diagonal entry (2, 2)",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n1 1 2\n1 1 1\n1 1 2\n",
                "repeated",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n1 1 2\n1 1 1\n",
                "1 entries",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n1 1 1\n1 2 1\n",
                "line 3: column `2`",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n1 1 1\n1 1 x\n",
                "line 3: value",
            ),
        ];
        for (text, want) in cases {
            let e = read(text.as_bytes()).unwrap_err().to_string();
            assert!(e.contains(want), "{want}: {e}");
        }
    }
}
