//! Legacy VTK (`.vtk`, ASCII) unstructured-grid reader.
//!
//! Layout: `# vtk DataFile Version x.y`, a title line, `ASCII`,
//! `DATASET UNSTRUCTURED_GRID`, then `POINTS n type` (3n numbers),
//! `CELLS` and `CELL_TYPES n`. Both `CELLS` layouts are understood: the
//! classic one (`CELLS n size`, records `k i0 … ik-1`) and the 5.x one
//! (`CELLS n_offsets n_conn`, `OFFSETS type`, `CONNECTIVITY type`).
//! `FIELD` and `METADATA` blocks are skipped; reading stops at
//! `POINT_DATA` / `CELL_DATA` (attributes are not mesh data). Cell types
//! 1–4 (vertices, lines) are ignored, 5 (triangle) and 10 (tetrahedron)
//! are read, everything else is rejected. When tets are present the
//! triangles are not kept.

use super::text::{Tokens, capacity_hint, shorten};
use crate::error::ParseError;
use crate::types::{AnyMesh, TetMesh, TriMesh};

fn cell_type_name(ty: usize) -> &'static str {
    match ty {
        6 => "triangle strip",
        7 => "polygon",
        8 => "pixel",
        9 => "quad",
        11 => "voxel",
        12 => "hexahedron",
        13 => "wedge",
        14 => "pyramid",
        21 => "quadratic edge",
        22 => "quadratic triangle",
        23 => "quadratic quad",
        24 => "quadratic tetra",
        25 => "quadratic hexahedron",
        _ => "unknown",
    }
}

/// Cells as flat connectivity with offsets, and the line of each cell.
struct Cells {
    offsets: Vec<usize>,
    conn: Vec<usize>,
    lines: Vec<usize>,
}

fn read_cells_classic(t: &mut Tokens<'_>, n: usize, size: usize) -> Result<Cells, ParseError> {
    let cap = capacity_hint(n, t.text_len());
    let mut c = Cells {
        offsets: Vec::with_capacity(cap + 1),
        conn: Vec::with_capacity(capacity_hint(size, t.text_len())),
        lines: Vec::with_capacity(cap),
    };
    c.offsets.push(0);
    let mut used = 0usize;
    for i in 0..n {
        let (k, line) = t.usize(&format!("the point count of cell {i} (of {n})"))?;
        used = used.saturating_add(k.saturating_add(1));
        if used > size {
            return Err(ParseError::line(
                line,
                format!("cell {i} goes beyond the declared CELLS size {size}"),
            ));
        }
        for _ in 0..k {
            c.conn
                .push(t.usize(&format!("a point index of cell {i}"))?.0);
        }
        c.offsets.push(c.conn.len());
        c.lines.push(line);
    }
    if used != size {
        return Err(ParseError::line(
            t.last_line(),
            format!("CELLS declares size {size} but the {n} cells use {used} numbers"),
        ));
    }
    Ok(c)
}

fn read_cells_v5(t: &mut Tokens<'_>, n_off: usize, n_conn: usize) -> Result<Cells, ParseError> {
    t.keyword("OFFSETS")?;
    t.expect("the OFFSETS data type")?;
    let mut offsets = Vec::with_capacity(capacity_hint(n_off, t.text_len()));
    let mut lines = Vec::with_capacity(capacity_hint(n_off, t.text_len()));
    for i in 0..n_off {
        let (o, line) = t.usize(&format!("offset {i} (of {n_off})"))?;
        if offsets.last().is_some_and(|&p| o < p) || (i == 0 && o != 0) {
            return Err(ParseError::line(
                line,
                format!("offset {i} = {o} is out of order"),
            ));
        }
        offsets.push(o);
        lines.push(line);
    }
    if n_off == 0 || offsets.last() != Some(&n_conn) {
        return Err(ParseError::line(
            t.last_line(),
            format!("the last offset must equal the connectivity size {n_conn}"),
        ));
    }
    t.keyword("CONNECTIVITY")?;
    t.expect("the CONNECTIVITY data type")?;
    let mut conn = Vec::with_capacity(capacity_hint(n_conn, t.text_len()));
    for i in 0..n_conn {
        conn.push(t.usize(&format!("connectivity entry {i} (of {n_conn})"))?.0);
    }
    lines.pop();
    Ok(Cells {
        offsets,
        conn,
        lines,
    })
}

/// Skip `FIELD name n` and its `n` arrays.
fn skip_field(t: &mut Tokens<'_>) -> Result<(), ParseError> {
    t.expect("the FIELD name")?;
    let (arrays, _) = t.usize("the number of FIELD arrays")?;
    for _ in 0..arrays {
        t.expect("a FIELD array name")?;
        let (comps, _) = t.usize("the FIELD array component count")?;
        let (tuples, _) = t.usize("the FIELD array tuple count")?;
        t.expect("the FIELD array data type")?;
        for _ in 0..comps.saturating_mul(tuples) {
            t.expect("a FIELD array value")?;
        }
    }
    Ok(())
}

/// Check the three header lines (`# vtk DataFile Version x.y`, a title,
/// `ASCII`) and return the byte offset where the body starts.
fn read_header(text: &str) -> Result<usize, ParseError> {
    let mut header = text.split_inclusive('\n');
    let l1 = header.next().unwrap_or("");
    if l1.trim().is_empty() {
        return Err(ParseError::format(
            "empty file: expected `# vtk DataFile Version`",
        ));
    }
    if !l1
        .trim_start()
        .to_ascii_lowercase()
        .starts_with("# vtk datafile")
    {
        return Err(ParseError::line(1, "expected `# vtk DataFile Version x.y`"));
    }
    let l2 = header
        .next()
        .ok_or_else(|| ParseError::line(1, "unexpected end of file: expected the title line"))?;
    let l3 = header
        .next()
        .ok_or_else(|| ParseError::line(2, "unexpected end of file: expected `ASCII`"))?;
    match l3.trim() {
        s if s.eq_ignore_ascii_case("ASCII") => {}
        s if s.eq_ignore_ascii_case("BINARY") => {
            return Err(ParseError::line(
                3,
                "binary VTK files are not supported: save as ASCII",
            ));
        }
        s => {
            return Err(ParseError::line(
                3,
                format!("expected `ASCII`, found `{}`", shorten(s)),
            ));
        }
    }
    Ok(l1.len() + l2.len() + l3.len())
}

/// `DATASET UNSTRUCTURED_GRID` (the only dataset type read).
fn read_dataset(t: &mut Tokens<'_>) -> Result<(), ParseError> {
    t.keyword("DATASET")?;
    let (kind, kline) = t.expect("the dataset type")?;
    if !kind.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
        return Err(ParseError::line(
            kline,
            format!(
                "unsupported dataset `{}`: only UNSTRUCTURED_GRID is supported",
                shorten(kind)
            ),
        ));
    }
    Ok(())
}

/// `POINTS n type` after its keyword: 3n coordinates.
fn read_points(t: &mut Tokens<'_>) -> Result<Vec<[f64; 3]>, ParseError> {
    let (n, _) = t.usize("the number of points")?;
    t.expect("the POINTS data type")?;
    let mut p = Vec::with_capacity(capacity_hint(n, t.text_len()));
    for i in 0..n {
        let what = format!("coordinate of point {i} (of {n})");
        p.push([t.f64(&what)?, t.f64(&what)?, t.f64(&what)?]);
    }
    Ok(p)
}

/// `CELLS a b` after its keyword, in the classic or the 5.x layout (the
/// latter is recognised by the `OFFSETS` keyword that follows).
fn read_cells(t: &mut Tokens<'_>) -> Result<Cells, ParseError> {
    let (a, _) = t.usize("the number of cells")?;
    let (b, _) = t.usize("the CELLS size")?;
    let is_v5 = t
        .peek()
        .is_some_and(|(k, _)| k.eq_ignore_ascii_case("OFFSETS"));
    if is_v5 {
        read_cells_v5(t, a, b)
    } else {
        read_cells_classic(t, a, b)
    }
}

/// `CELL_TYPES n` after its keyword: n type codes.
fn read_cell_types(t: &mut Tokens<'_>) -> Result<Vec<usize>, ParseError> {
    let (n, _) = t.usize("the number of cell types")?;
    let mut ty = Vec::with_capacity(capacity_hint(n, t.text_len()));
    for i in 0..n {
        ty.push(t.usize(&format!("the type of cell {i} (of {n})"))?.0);
    }
    Ok(ty)
}

/// The three mesh sections of the body; each is `None` until read.
#[derive(Default)]
struct Sections {
    points: Option<Vec<[f64; 3]>>,
    cells: Option<Cells>,
    /// The cell types and the line of their `CELL_TYPES` keyword.
    types: Option<(Vec<usize>, usize)>,
}

/// Read the body's sections, one keyword at a time, up to `POINT_DATA` /
/// `CELL_DATA` or the end of the file.
fn read_sections(t: &mut Tokens<'_>) -> Result<Sections, ParseError> {
    let mut s = Sections::default();
    while let Some((kw, line)) = t.next_token() {
        match kw.to_ascii_uppercase().as_str() {
            "POINTS" => s.points = Some(read_points(t)?),
            "CELLS" => s.cells = Some(read_cells(t)?),
            "CELL_TYPES" => s.types = Some((read_cell_types(t)?, line)),
            "FIELD" => skip_field(t)?,
            "METADATA" => t.skip_past_blank_line(),
            "POINT_DATA" | "CELL_DATA" => break,
            _ => {
                return Err(ParseError::line(
                    line,
                    format!("unknown VTK keyword `{}`", shorten(kw)),
                ));
            }
        }
    }
    Ok(s)
}

/// Parse legacy VTK ASCII text (see the module docs).
pub fn parse_vtk(text: &str) -> Result<AnyMesh, ParseError> {
    let start = read_header(text)?;
    let mut t = Tokens::starting_at(text, start, 4, None);
    read_dataset(&mut t)?;
    let s = read_sections(&mut t)?;
    let points = s
        .points
        .ok_or_else(|| ParseError::format("no POINTS section"))?;
    let cells = s
        .cells
        .ok_or_else(|| ParseError::format("no CELLS section"))?;
    let (types, tline) = s
        .types
        .ok_or_else(|| ParseError::format("no CELL_TYPES section"))?;
    let ncells = cells.lines.len();
    if types.len() != ncells {
        return Err(ParseError::line(
            tline,
            format!("CELL_TYPES has {} entries for {ncells} cells", types.len()),
        ));
    }
    build_mesh(points, &cells, &types, tline)
}

/// Keep the triangles (type 5) and tetrahedra (type 10), checking their
/// point counts and indices; tets win when both are present.
fn build_mesh(
    points: Vec<[f64; 3]>,
    cells: &Cells,
    types: &[usize],
    tline: usize,
) -> Result<AnyMesh, ParseError> {
    let mut tris = Vec::new();
    let mut tets = Vec::new();
    for (i, &ty) in types.iter().enumerate() {
        let ids = &cells.conn[cells.offsets[i]..cells.offsets[i + 1]];
        let line = cells.lines[i];
        if let Some(&bad) = ids.iter().find(|&&v| v >= points.len()) {
            return Err(ParseError::line(
                line,
                format!(
                    "cell {i} refers to point {bad} but there are only {} points",
                    points.len()
                ),
            ));
        }
        let want = match ty {
            1..=4 => continue,
            5 => 3,
            10 => 4,
            _ => {
                return Err(ParseError::line(
                    tline,
                    format!(
                        "cell {i} has unsupported VTK cell type {ty} ({}): only triangles (5) and tetrahedra (10) are supported",
                        cell_type_name(ty)
                    ),
                ));
            }
        };
        if ids.len() != want {
            return Err(ParseError::line(
                line,
                format!(
                    "cell {i} of type {ty} has {} points, expected {want}",
                    ids.len()
                ),
            ));
        }
        if ty == 5 {
            tris.push([ids[0], ids[1], ids[2]]);
        } else {
            tets.push([ids[0], ids[1], ids[2], ids[3]]);
        }
    }
    if !tets.is_empty() {
        Ok(AnyMesh::Tet(TetMesh::new(points, tets)))
    } else if !tris.is_empty() {
        Ok(AnyMesh::Tri(TriMesh::new(points, tris)))
    } else {
        Err(ParseError::format(
            "the VTK file has no triangles and no tetrahedra",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str =
        "# vtk DataFile Version 3.0\nany title: 1 2 3\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    const PTS: &str = "POINTS 4 double\n0 0 0 1 0 0\n0 1 0 0 0 1\n";

    #[test]
    fn reads_classic_and_v5_cells() {
        let text = format!(
            "{HEAD}FIELD FieldData 1\nTIME 1 1 double\n0\n{PTS}CELLS 2 7\n4 0 1 2 3\n1 0\nCELL_TYPES 2\n10\n1\nPOINT_DATA 4\nSCALARS a double\n"
        );
        let AnyMesh::Tet(m) = parse_vtk(&text).unwrap() else {
            panic!("expected tets")
        };
        assert_eq!(m.tets, vec![[0, 1, 2, 3]]);
        let v5 = format!(
            "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n{PTS}METADATA\nINFORMATION 0\n\n\
             CELLS 3 6\nOFFSETS vtktypeint64\n0 3 6\nCONNECTIVITY vtktypeint64\n0 1 2 0 2 3\nCELL_TYPES 2\n5 5\n"
        );
        let AnyMesh::Tri(m) = parse_vtk(&v5).unwrap() else {
            panic!("expected triangles")
        };
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn malformed_inputs_are_rejected_with_lines() {
        let cases: Vec<(String, &str)> = vec![
            (String::new(), "empty file"),
            (
                "hello\n".into(),
                "line 1: expected `# vtk DataFile Version x.y`",
            ),
            (
                "# vtk DataFile Version 3.0\n".into(),
                "line 1: unexpected end of file: expected the title line",
            ),
            (
                "# vtk DataFile Version 3.0\nt\nBINARY\n".into(),
                "line 3: binary VTK files are not supported",
            ),
            (
                "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n".into(),
                "line 4: unsupported dataset `POLYDATA`",
            ),
            (
                format!("{HEAD}POINTS 2 float\n0 0 0\n"),
                "unexpected end of file: expected coordinate of point 1 (of 2)",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 9\nCELL_TYPES 1\n10\n"),
                "line 9: cell 0 refers to point 9 but there are only 4 points",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 4\n4 0 1 2 3\nCELL_TYPES 1\n10\n"),
                "line 9: cell 0 goes beyond the declared CELLS size 4",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 6\n4 0 1 2 3\nCELL_TYPES 1\n10\n"),
                "CELLS declares size 6 but the 1 cells use 5 numbers",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n9\n"),
                "line 10: cell 0 has unsupported VTK cell type 9 (quad)",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n5\n"),
                "line 9: cell 0 of type 5 has 4 points, expected 3",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n"),
                "line 10: CELL_TYPES has 2 entries for 1 cells",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 3\n"),
                "no CELL_TYPES section",
            ),
            (
                format!("{HEAD}{PTS}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n3\n"),
                "no triangles and no tetrahedra",
            ),
            (
                format!("{HEAD}{PTS}BOGUS 1\n"),
                "line 8: unknown VTK keyword `BOGUS`",
            ),
            (
                format!("{HEAD}{PTS}CELLS 2 3\nOFFSETS int\n0 4\nCONNECTIVITY int\n0 1 2\n"),
                "the last offset must equal the connectivity size 3",
            ),
            (
                format!("{HEAD}{PTS}CELLS 3 3\nOFFSETS int\n0 2 1\n"),
                "offset 2 = 1 is out of order",
            ),
            (
                format!("{HEAD}POINTS 1 float\n0 0 x\n"),
                "line 6: expected coordinate of point 0 (of 1) (a number), found `x`",
            ),
        ];
        for (text, want) in &cases {
            let err = parse_vtk(text).unwrap_err().to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
    }
}
