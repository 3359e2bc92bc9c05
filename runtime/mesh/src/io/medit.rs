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

/// What has been read so far; each section fills its slot once.
#[derive(Default)]
struct Medit {
    saw_version: bool,
    dim: Option<usize>,
    positions: Option<Vec<[f64; 3]>>,
    tris: Option<Elements<3>>,
    tets: Option<Elements<4>>,
}

/// `MeshVersionFormatted v` after its keyword (v in 1..=4).
fn read_version(t: &mut Tokens<'_>) -> Result<(), ParseError> {
    let (v, vline) = t.usize("the mesh version")?;
    if !(1..=4).contains(&v) {
        return Err(ParseError::line(
            vline,
            format!("unknown MEDIT version {v}"),
        ));
    }
    Ok(())
}

/// `Dimension d` after its keyword (d = 2 or 3).
fn read_dimension(t: &mut Tokens<'_>) -> Result<usize, ParseError> {
    let (d, dline) = t.usize("the dimension")?;
    if d != 2 && d != 3 {
        return Err(ParseError::line(
            dline,
            format!("dimension must be 2 or 3, found {d}"),
        ));
    }
    Ok(d)
}

/// The `n` records of `Vertices`: `d` coordinates (z = 0 when d = 2) and a
/// reference each.
fn read_vertices(t: &mut Tokens<'_>, n: usize, d: usize) -> Result<Vec<[f64; 3]>, ParseError> {
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
    Ok(pos)
}

/// A section we do not keep: an empty unsupported element section or a
/// skipped one (its records are consumed); anything else is an error.
fn skip_section(
    t: &mut Tokens<'_>,
    kw: &str,
    line: usize,
    n: usize,
    d: usize,
) -> Result<(), ParseError> {
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
    Ok(())
}

impl Medit {
    /// A counted section `kw n` (after the version and the dimension).
    fn read_section(
        &mut self,
        t: &mut Tokens<'_>,
        kw: &str,
        line: usize,
    ) -> Result<(), ParseError> {
        if !self.saw_version {
            return Err(ParseError::line(
                line,
                format!(
                    "expected `MeshVersionFormatted`, found `{}` (binary .meshb is not supported)",
                    shorten(kw)
                ),
            ));
        }
        let d = self
            .dim
            .ok_or_else(|| ParseError::line(line, format!("section `{kw}` before `Dimension`")))?;
        let (n, _) = t.usize(&format!("the number of {kw}"))?;
        match kw.to_ascii_lowercase().as_str() {
            "vertices" => {
                if self.positions.is_some() {
                    return Err(ParseError::line(line, "a second `Vertices` section"));
                }
                self.positions = Some(read_vertices(t, n, d)?);
            }
            "triangles" => {
                if self.tris.is_some() {
                    return Err(ParseError::line(line, "a second `Triangles` section"));
                }
                self.tris = Some(read_elements(t, "triangle", n)?);
            }
            "tetrahedra" => {
                if self.tets.is_some() {
                    return Err(ParseError::line(line, "a second `Tetrahedra` section"));
                }
                self.tets = Some(read_elements(t, "tetrahedron", n)?);
            }
            _ => skip_section(t, kw, line, n, d)?,
        }
        Ok(())
    }

    /// The mesh: tetrahedra when there are any, else triangles, with every
    /// index checked against the vertex count.
    fn into_mesh(self) -> Result<AnyMesh, ParseError> {
        let positions = self
            .positions
            .ok_or_else(|| ParseError::format("no `Vertices` section in the MEDIT file"))?;
        let nv = positions.len();
        match (self.tets, self.tris) {
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
}

/// Parse MEDIT `.mesh` text (see the module docs).
pub fn parse_medit(text: &str) -> Result<AnyMesh, ParseError> {
    let mut t = Tokens::new(text, Some(b'#'));
    if t.peek().is_none() {
        return Err(ParseError::format(
            "empty file: expected `MeshVersionFormatted`",
        ));
    }
    let mut m = Medit::default();
    while let Some((kw, line)) = t.next_token() {
        match kw.to_ascii_lowercase().as_str() {
            "meshversionformatted" => {
                read_version(&mut t)?;
                m.saw_version = true;
            }
            "dimension" => m.dim = Some(read_dimension(&mut t)?),
            "end" => break,
            _ => m.read_section(&mut t, kw, line)?,
        }
    }
    m.into_mesh()
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
