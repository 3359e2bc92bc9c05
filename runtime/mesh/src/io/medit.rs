//! MEDIT `.mesh` (ASCII) reader.
//!
//! Keywords: `MeshVersionFormatted v`, `Dimension d` (2 or 3), then
//! sections `Keyword n` followed by `n` records, until `End`:
//! `Vertices` (`d` coordinates + a reference), `Triangles` (3 indices +
//! ref), `Tetrahedra` (4 indices + ref). Indices are 1-based. Sections that
//! carry no elements we need (`Edges`, `Corners`, `Ridges`, `Required*`,
//! `Normals`, `Tangents`, …) are skipped. Other element kinds
//! (`Quadrilaterals`, `Hexahedra`, `Prisms`, `Pyramids`, second-order
//! elements) are rejected when non-empty. `#` starts a comment.
//!
//! When the file has tetrahedra, the result is a [`TetMesh`] and the
//! triangles (usually the boundary, with references) are not kept;
//! otherwise it is a [`TriMesh`] (z = 0 for `Dimension 2`).

use super::text::{Tokens, capacity_hint, shorten};
use crate::error::ParseError;
use crate::types::{AnyMesh, TetMesh, TriMesh};

/// Sections we skip: name and the number of tokens per record
/// (`None`: depends on the dimension `d`).
fn skipped_record_len(keyword: &str, dim: usize) -> Option<usize> {
    let k = keyword.to_ascii_lowercase();
    Some(match k.as_str() {
        "edges" => 3,
        "corners" | "ridges" | "requiredvertices" | "requirededges" | "requiredtriangles"
        | "requiredtetrahedra" => 1,
        "normals" | "tangents" => dim,
        "normalatvertices" | "tangentatvertices" => 2,
        "normalattrianglevertices" => 3,
        _ => return None,
    })
}

/// Element sections we do not support when non-empty.
fn unsupported_elements(keyword: &str) -> bool {
    let k = keyword.to_ascii_lowercase();
    matches!(
        k.as_str(),
        "quadrilaterals"
            | "hexahedra"
            | "prisms"
            | "pyramids"
            | "edgesp2"
            | "trianglesp2"
            | "quadrilateralsq2"
            | "tetrahedrap2"
            | "hexahedraq2"
    )
}

struct Elements<const K: usize> {
    items: Vec<[usize; K]>,
    lines: Vec<usize>,
}

fn read_elements<const K: usize>(
    t: &mut Tokens<'_>,
    name: &str,
    n: usize,
) -> Result<Elements<K>, ParseError> {
    let cap = capacity_hint(n, t.text_len());
    let mut out = Elements {
        items: Vec::with_capacity(cap),
        lines: Vec::with_capacity(cap),
    };
    for e in 0..n {
        let mut el = [0usize; K];
        let mut first_line = 0;
        for (k, slot) in el.iter_mut().enumerate() {
            let (v, line) = t.usize(&format!("vertex index of {name} {} (of {n})", e + 1))?;
            if k == 0 {
                first_line = line;
            }
            if v == 0 {
                return Err(ParseError::line(
                    line,
                    format!(
                        "{name} {} has vertex index 0: MEDIT indices are 1-based",
                        e + 1
                    ),
                ));
            }
            *slot = v - 1;
        }
        t.i64(&format!("reference of {name} {}", e + 1))?;
        out.items.push(el);
        out.lines.push(first_line);
    }
    Ok(out)
}

fn check_range<const K: usize>(els: &Elements<K>, name: &str, nv: usize) -> Result<(), ParseError> {
    for (e, (el, line)) in els.items.iter().zip(&els.lines).enumerate() {
        if let Some(&v) = el.iter().find(|&&v| v >= nv) {
            return Err(ParseError::line(
                *line,
                format!(
                    "{name} {} refers to vertex {} but there are only {nv} vertices",
                    e + 1,
                    v + 1
                ),
            ));
        }
    }
    Ok(())
}

/// Parse MEDIT `.mesh` text (see the module docs).
pub fn parse_medit(text: &str) -> Result<AnyMesh, ParseError> {
    let mut t = Tokens::new(text, Some(b'#'));
    if t.peek().is_none() {
        return Err(ParseError::format(
            "empty file: expected `MeshVersionFormatted`",
        ));
    }
    let mut dim: Option<usize> = None;
    let mut positions: Option<Vec<[f64; 3]>> = None;
    let mut tris: Option<Elements<3>> = None;
    let mut tets: Option<Elements<4>> = None;
    let mut saw_version = false;
    while let Some((kw, line)) = t.next_token() {
        let lower = kw.to_ascii_lowercase();
        match lower.as_str() {
            "meshversionformatted" => {
                let (v, vline) = t.usize("the mesh version")?;
                if !(1..=4).contains(&v) {
                    return Err(ParseError::line(
                        vline,
                        format!("unknown MEDIT version {v}"),
                    ));
                }
                saw_version = true;
            }
            "dimension" => {
                let (d, dline) = t.usize("the dimension")?;
                if d != 2 && d != 3 {
                    return Err(ParseError::line(
                        dline,
                        format!("dimension must be 2 or 3, found {d}"),
                    ));
                }
                dim = Some(d);
            }
            "end" => break,
            _ => {
                if !saw_version {
                    return Err(ParseError::line(
                        line,
                        format!(
                            "expected `MeshVersionFormatted`, found `{}` (binary .meshb is not supported)",
                            shorten(kw)
                        ),
                    ));
                }
                let d = dim.ok_or_else(|| {
                    ParseError::line(line, format!("section `{kw}` before `Dimension`"))
                })?;
                let (n, _) = t.usize(&format!("the number of {kw}"))?;
                match lower.as_str() {
                    "vertices" => {
                        if positions.is_some() {
                            return Err(ParseError::line(line, "a second `Vertices` section"));
                        }
                        let mut pos = Vec::with_capacity(capacity_hint(n, t.text_len()));
                        for i in 0..n {
                            let what = format!("coordinate of vertex {} (of {n})", i + 1);
                            let mut p = [0.0; 3];
                            for c in p.iter_mut().take(d) {
                                *c = t.f64(&what)?;
                            }
                            t.i64(&format!("reference of vertex {}", i + 1))?;
                            pos.push(p);
                        }
                        positions = Some(pos);
                    }
                    "triangles" => {
                        if tris.is_some() {
                            return Err(ParseError::line(line, "a second `Triangles` section"));
                        }
                        tris = Some(read_elements(&mut t, "triangle", n)?);
                    }
                    "tetrahedra" => {
                        if tets.is_some() {
                            return Err(ParseError::line(line, "a second `Tetrahedra` section"));
                        }
                        tets = Some(read_elements(&mut t, "tetrahedron", n)?);
                    }
                    _ => {
                        if unsupported_elements(kw) {
                            if n > 0 {
                                return Err(ParseError::line(
                                    line,
                                    format!(
                                        "unsupported element section `{kw}` with {n} elements: only triangles and tetrahedra are supported"
                                    ),
                                ));
                            }
                        } else if let Some(len) = skipped_record_len(kw, d) {
                            for _ in 0..n.saturating_mul(len) {
                                t.expect(&format!("a record of `{kw}`"))?;
                            }
                        } else {
                            return Err(ParseError::line(
                                line,
                                format!("unknown MEDIT keyword `{}`", shorten(kw)),
                            ));
                        }
                    }
                }
            }
        }
    }
    let positions =
        positions.ok_or_else(|| ParseError::format("no `Vertices` section in the MEDIT file"))?;
    let nv = positions.len();
    match (tets, tris) {
        (Some(tets), _) if !tets.items.is_empty() => {
            check_range(&tets, "tetrahedron", nv)?;
            Ok(AnyMesh::Tet(TetMesh::new(positions, tets.items)))
        }
        (_, Some(tris)) if !tris.items.is_empty() => {
            check_range(&tris, "triangle", nv)?;
            Ok(AnyMesh::Tri(TriMesh::new(positions, tris.items)))
        }
        _ => Err(ParseError::format(
            "the MEDIT file has no triangles and no tetrahedra",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TET: &str = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n\
                       Edges 1\n1 2 0\nTriangles\n1\n1 3 2 5\nTetrahedra\n1\n1 2 3 4 0\nEnd\n";

    #[test]
    fn reads_tets_and_skips_other_sections() {
        let AnyMesh::Tet(m) = parse_medit(TET).unwrap() else {
            panic!("expected tets")
        };
        assert_eq!(m.tets, vec![[0, 1, 2, 3]]);
        assert_eq!(m.positions[3], [0.0, 0.0, 1.0]);
    }

    #[test]
    fn reads_planar_triangles() {
        let text = "MeshVersionFormatted 1\nDimension 2\n# c\nVertices 3\n0 0 1\n1 0 1\n0 1 1\n\
                    Triangles 1\n1 2 3 0\nCorners 1\n1\nEnd";
        let AnyMesh::Tri(m) = parse_medit(text).unwrap() else {
            panic!("expected triangles")
        };
        assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn malformed_inputs_are_rejected_with_lines() {
        let cases: &[(&str, &str)] = &[
            ("", "empty file"),
            (
                "Dimension 3\nVertices 0\n",
                "line 2: expected `MeshVersionFormatted`, found `Vertices`",
            ),
            (
                "MeshVersionFormatted 1\nVertices 0\n",
                "line 2: section `Vertices` before `Dimension`",
            ),
            (
                "MeshVersionFormatted 1\nDimension 4\n",
                "line 2: dimension must be 2 or 3",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 2\n0 0 0 0\n",
                "unexpected end of file: expected coordinate of vertex 2 (of 2)",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 1\n0 x 0 0\n",
                "line 4: expected coordinate of vertex 1 (of 1) (a number), found `x`",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles 1\n0 1 2 0\n",
                "line 8: triangle 1 has vertex index 0: MEDIT indices are 1-based",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles 1\n1 2 4 0\n",
                "line 8: triangle 1 refers to vertex 4 but there are only 3 vertices",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nQuadrilaterals 1\n1 2 3 1 0\n",
                "line 7: unsupported element section `Quadrilaterals`",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nFoo 3\n",
                "line 3: unknown MEDIT keyword `Foo`",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 1\n0 0 0 0\nEnd\n",
                "no triangles and no tetrahedra",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nTriangles 0\nEnd\n",
                "no `Vertices` section",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 1\n0 0 0 0\nVertices 1\n",
                "line 5: a second `Vertices` section",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nVertices 18446744073709551615\n",
                "unexpected end of file",
            ),
            (
                "MeshVersionFormatted 1\nDimension 3\nEdges 18446744073709551615\n",
                "unexpected end of file",
            ),
        ];
        for (text, want) in cases {
            let err = parse_medit(text).unwrap_err().to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
    }
}
