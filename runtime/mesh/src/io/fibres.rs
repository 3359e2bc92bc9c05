//! Per-element fibre data read from mesh files.
//!
//! * Legacy ASCII VTK: a cell-data array with (at least) d components, as
//!   `VECTORS name type`, `NORMALS name type`, `SCALARS name type k` (k ≥ d,
//!   with its `LOOKUP_TABLE`) or an array of a `FIELD` block; one tuple per
//!   cell, cells in file order (the mesh's element order: the VTK reader
//!   accepts only triangle or tetrahedron cells). The name is configurable;
//!   [`DEFAULT_FIBRE_NAMES`] are tried by default. `POINT_DATA` blocks and
//!   other attributes are skipped.
//! * MEDIT `.mesh`: the integer reference of every element (the last number
//!   of each `Tetrahedra` record, or of `Triangles` when there are no
//!   tetrahedra); a table maps references to directions
//!   ([`crate::fibre::from_references`]).
//!
//! Errors are located [`ParseError`]s (line numbers, what was expected).

use super::text::{Tokens, capacity_hint};
use crate::error::ParseError;

/// Cell-data names tried when none is given.
pub const DEFAULT_FIBRE_NAMES: &[&str] = &["fiber", "fibre", "fibers", "fibres"];

/// One attribute array: name, components per tuple, values (tuple-major).
struct Array {
    name: String,
    comps: usize,
    values: Vec<f64>,
}

fn read_values(t: &mut Tokens<'_>, n: usize, what: &str) -> Result<Vec<f64>, ParseError> {
    let mut v = Vec::with_capacity(capacity_hint(n, t.text_len()));
    for i in 0..n {
        v.push(t.f64(&format!("value {} of `{what}`", i + 1))?);
    }
    Ok(v)
}

/// Reads one attribute (after its keyword) with `m` tuples.
fn read_attribute(
    t: &mut Tokens<'_>,
    kw: &str,
    m: usize,
    line: usize,
) -> Result<Vec<Array>, ParseError> {
    let upper = kw.to_ascii_uppercase();
    let (name, _) = t.expect(&format!("the name of a `{kw}` attribute"))?;
    let name = name.to_string();
    let array = |comps: usize, t: &mut Tokens<'_>| -> Result<Vec<Array>, ParseError> {
        let n = m
            .checked_mul(comps)
            .ok_or_else(|| ParseError::line(line, "attribute too large"))?;
        Ok(vec![Array {
            name: name.clone(),
            comps,
            values: read_values(t, n, &name)?,
        }])
    };
    match upper.as_str() {
        "VECTORS" | "NORMALS" => {
            t.expect("the data type")?;
            array(3, t)
        }
        "TENSORS" => {
            t.expect("the data type")?;
            array(9, t)
        }
        "SCALARS" => {
            t.expect("the data type")?;
            let comps = match t.peek() {
                Some((tok, _)) if tok.bytes().all(|b| b.is_ascii_digit()) => {
                    t.usize("the component count")?.0
                }
                _ => 1,
            };
            if matches!(t.peek(), Some((tok, _)) if tok.eq_ignore_ascii_case("LOOKUP_TABLE")) {
                t.next_token();
                t.expect("the lookup table name")?;
            }
            array(comps, t)
        }
        "COLOR_SCALARS" => {
            let comps = t.usize("the number of colour values")?.0;
            array(comps, t)
        }
        "TEXTURE_COORDINATES" => {
            let comps = t.usize("the texture dimension")?.0;
            t.expect("the data type")?;
            array(comps, t)
        }
        "LOOKUP_TABLE" => {
            let size = t.usize("the lookup table size")?.0;
            read_values(t, size.saturating_mul(4), &name)?;
            Ok(Vec::new())
        }
        "FIELD" => read_field(t, line),
        _ => Err(ParseError::line(
            line,
            format!("unknown VTK attribute `{}`", super::text::shorten(kw)),
        )),
    }
}

/// The arrays of a `FIELD name k` block (after its name).
fn read_field(t: &mut Tokens<'_>, _line: usize) -> Result<Vec<Array>, ParseError> {
    let k = t.usize("the number of FIELD arrays")?.0;
    let mut out = Vec::new();
    for _ in 0..k {
        let (name, line) = t.expect("a FIELD array name")?;
        let comps = t.usize(&format!("the component count of `{name}`"))?.0;
        let tuples = t.usize(&format!("the tuple count of `{name}`"))?.0;
        t.expect("the data type")?;
        let n = comps
            .checked_mul(tuples)
            .ok_or_else(|| ParseError::line(line, "array too large"))?;
        out.push(Array {
            name: name.to_string(),
            comps,
            values: read_values(t, n, name)?,
        });
    }
    Ok(out)
}

/// The cell-data arrays of a legacy VTK text and the cell count.
fn cell_arrays(text: &str) -> Result<(usize, Vec<Array>), ParseError> {
    let mut t = Tokens::new(text, None);
    // skip to the first data block (numbers never match the keywords)
    let mut block: Option<(bool, usize)> = None;
    let mut cells: Option<usize> = None;
    let mut out = Vec::new();
    while let Some((kw, line)) = t.next_token() {
        let upper = kw.to_ascii_uppercase();
        if upper == "CELL_DATA" || upper == "POINT_DATA" {
            let (m, _) = t.usize(&format!("the tuple count of `{kw}`"))?;
            let is_cell = upper == "CELL_DATA";
            if is_cell {
                cells = Some(m);
            }
            block = Some((is_cell, m));
        } else if let Some((is_cell, m)) = block {
            if upper == "METADATA" {
                return Err(ParseError::line(
                    line,
                    "VTK `METADATA` blocks are not supported",
                ));
            }
            let arrays = read_attribute(&mut t, kw, m, line)?;
            if is_cell {
                out.extend(arrays);
            }
        }
    }
    let n =
        cells.ok_or_else(|| ParseError::format("no CELL_DATA section (no per-element data)"))?;
    Ok((n, out))
}

/// Per-cell directions (first `D` components) of the first array whose name
/// is in `names` (exact match, tried in order) in a legacy ASCII VTK text.
pub fn parse_vtk_cell_vectors<const D: usize>(
    text: &str,
    names: &[&str],
) -> Result<Vec<[f64; D]>, ParseError> {
    let (n, arrays) = cell_arrays(text)?;
    let found = names
        .iter()
        .find_map(|want| arrays.iter().find(|a| a.name == *want));
    let Some(a) = found else {
        let have: Vec<&str> = arrays.iter().map(|a| a.name.as_str()).collect();
        return Err(ParseError::format(format!(
            "no cell data array named {} (the file has: {})",
            names
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(" or "),
            if have.is_empty() {
                "none".to_string()
            } else {
                have.join(", ")
            }
        )));
    };
    if a.comps < D || a.values.len() != n * a.comps {
        return Err(ParseError::format(format!(
            "cell data `{}` has {} components × {} tuples; expected at least {D} components × {n} cells",
            a.name,
            a.comps,
            a.values.len() / a.comps.max(1)
        )));
    }
    Ok(a.values
        .chunks(a.comps)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect())
}

/// The element references of a MEDIT `.mesh` text: of `Tetrahedra` when the
/// file has tetrahedra, else of `Triangles`.
pub fn parse_medit_references(text: &str) -> Result<Vec<i64>, ParseError> {
    for (section, k) in [("tetrahedra", 4), ("triangles", 3)] {
        let mut t = Tokens::new(text, Some(b'#'));
        while let Some((kw, _)) = t.next_token() {
            if !kw.eq_ignore_ascii_case(section) {
                continue;
            }
            let (n, _) = t.usize(&format!("the number of {kw}"))?;
            let mut refs = Vec::with_capacity(capacity_hint(n, t.text_len()));
            for e in 0..n {
                for _ in 0..k {
                    t.usize(&format!("a vertex index of {section} element {}", e + 1))?;
                }
                refs.push(
                    t.i64(&format!("the reference of {section} element {}", e + 1))?
                        .0,
                );
            }
            return Ok(refs);
        }
    }
    Err(ParseError::format("no `Tetrahedra` or `Triangles` section"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const VTK: &str = "# vtk DataFile Version 3.0\nfibres\nASCII\nDATASET UNSTRUCTURED_GRID\n\
POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n\
POINT_DATA 4\nSCALARS t float 1\nLOOKUP_TABLE default\n1 2 3 4\n\
CELL_DATA 1\nSCALARS id int\nLOOKUP_TABLE default\n7\nFIELD extra 2\nw 1 1 double\n0.5\n\
fibre 3 1 double\n0 2 0\nVECTORS fiber double\n1 0 0\n";

    #[test]
    fn reads_vectors_field_arrays_and_names() {
        assert_eq!(
            parse_vtk_cell_vectors::<3>(VTK, DEFAULT_FIBRE_NAMES).unwrap(),
            vec![[1.0, 0.0, 0.0]]
        );
        assert_eq!(
            parse_vtk_cell_vectors::<3>(VTK, &["fibre"]).unwrap(),
            vec![[0.0, 2.0, 0.0]]
        );
        assert_eq!(
            parse_vtk_cell_vectors::<2>(VTK, &["fibre"]).unwrap(),
            vec![[0.0, 2.0]]
        );
        let e = parse_vtk_cell_vectors::<3>(VTK, &["dir"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`dir`") && e.contains("id, w, fibre, fiber"),
            "{e}"
        );
        let e = parse_vtk_cell_vectors::<3>(VTK, &["id"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("1 components"), "{e}");
        let bad = VTK.replace("1 0 0\n", "1 nan 0\n");
        let e = parse_vtk_cell_vectors::<3>(&bad, &["fiber"]).unwrap_err();
        assert!(matches!(e, ParseError::Line { line: 25, .. }), "{e}");
        let short = VTK.replace(
            "VECTORS fiber double\n1 0 0\n",
            "VECTORS fiber double\n1 0\n",
        );
        assert!(
            parse_vtk_cell_vectors::<3>(&short, &["fiber"])
                .unwrap_err()
                .to_string()
                .contains("end of file")
        );
        let none =
            "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 0 double\n";
        assert!(
            parse_vtk_cell_vectors::<3>(none, &["fiber"])
                .unwrap_err()
                .to_string()
                .contains("no CELL_DATA")
        );
    }

    #[test]
    fn reads_medit_references() {
        let m = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n\
Triangles\n1\n1 2 3 9\nTetrahedra\n2\n1 2 3 4 5\n1 2 3 4 -2\nEnd\n";
        assert_eq!(parse_medit_references(m).unwrap(), vec![5, -2]);
        let tri = "MeshVersionFormatted 1\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3 4\nEnd\n";
        assert_eq!(parse_medit_references(tri).unwrap(), vec![4]);
        let bad = m.replace("1 2 3 4 -2", "1 2 3 4 x");
        assert!(matches!(
            parse_medit_references(&bad),
            Err(ParseError::Line { line: 15, .. })
        ));
    }
}
