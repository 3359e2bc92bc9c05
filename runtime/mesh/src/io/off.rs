//! Object File Format (OFF) reader.
//!
//! Layout: a header `OFF` (also `COFF`, `NOFF`, `CNOFF`), the counts
//! `nV nF nE` (on the header line or the next), `nV` vertex records `x y z`
//! and `nF` face records `3 a b c`. Indices are 0-based. Records are
//! line-oriented: anything after the coordinates / indices on a record's
//! line (colours, normals) is ignored. `#` starts a comment. Faces with
//! more than three corners are rejected (triangulate first).

use super::text::{Tokens, capacity_hint, shorten};
use crate::error::ParseError;
use crate::types::TriMesh;

/// Parse OFF text into a triangle mesh (see the module docs).
pub fn parse_off(text: &str) -> Result<TriMesh, ParseError> {
    let mut t = Tokens::new(text, Some(b'#'));
    let Some((head, line)) = t.next_token() else {
        return Err(ParseError::format("empty file: expected an `OFF` header"));
    };
    let known = ["OFF", "COFF", "NOFF", "CNOFF"];
    if !known.iter().any(|k| head.eq_ignore_ascii_case(k)) {
        return Err(ParseError::line(
            line,
            format!(
                "expected an `OFF` header, found `{}` (4OFF / nOFF / binary OFF are not supported)",
                shorten(head)
            ),
        ));
    }
    let (nv, _) = t.usize("the vertex count")?;
    let (nf, _) = t.usize("the face count")?;
    let _ = t.usize("the edge count")?;
    let mut positions = Vec::with_capacity(capacity_hint(nv, t.text_len()));
    for i in 0..nv {
        let what = format!("coordinate of vertex {i} (of {nv})");
        let x = t.f64(&what)?;
        let y = t.f64(&what)?;
        let z = t.f64(&what)?;
        positions.push([x, y, z]);
        t.skip_line();
    }
    let mut triangles = Vec::with_capacity(capacity_hint(nf, t.text_len()));
    for f in 0..nf {
        let (k, line) = t.usize(&format!("the corner count of face {f} (of {nf})"))?;
        if k != 3 {
            return Err(ParseError::line(
                line,
                format!(
                    "face {f} has {k} corners: only triangles are supported (triangulate the mesh first)"
                ),
            ));
        }
        let mut tri = [0usize; 3];
        for slot in &mut tri {
            let (v, line) = t.usize(&format!("a vertex index of face {f}"))?;
            if v >= nv {
                let hint = if v == nv {
                    " (OFF indices are 0-based: is the file 1-based?)"
                } else {
                    ""
                };
                return Err(ParseError::line(
                    line,
                    format!("face {f} refers to vertex {v} but there are only {nv} vertices{hint}"),
                ));
            }
            *slot = v;
        }
        triangles.push(tri);
        t.skip_line();
    }
    if triangles.is_empty() {
        return Err(ParseError::format("the OFF file declares no faces"));
    }
    Ok(TriMesh::new(positions, triangles))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_counts_on_header_line_comments_and_colours() {
        let text = "OFF 4 2 0\n# comment\n0 0 0\n1 0 0\n1 1 0 \n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3\n";
        let m = parse_off(text).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn malformed_inputs_are_rejected_with_lines() {
        let cases: &[(&str, &str)] = &[
            ("", "empty file"),
            ("PLY\n", "line 1: expected an `OFF` header, found `PLY`"),
            (
                "OFF\n3 1\n",
                "line 2: unexpected end of file: expected the edge count",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n",
                "unexpected end of file: expected coordinate of vertex 2",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 a 0\n3 0 1 2\n",
                "line 5: expected coordinate of vertex 2 (of 3) (a number), found `a`",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n",
                "line 6: face 0 has 4 corners",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 1 2 3\n",
                "line 6: face 0 refers to vertex 3 but there are only 3 vertices (OFF indices are 0-based",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n",
                "line 6: expected a vertex index of face 0 (a non-negative integer), found `-2`",
            ),
            (
                "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                "unexpected end of file: expected the corner count of face 1 (of 2)",
            ),
            ("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "declares no faces"),
            (
                "OFF\n99999999999999999999 1 0\n",
                "line 2: expected the vertex count",
            ),
        ];
        for (text, want) in cases {
            let err = parse_off(text).unwrap_err().to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
    }

    #[test]
    fn huge_declared_counts_do_not_allocate() {
        let err = parse_off("OFF\n1000000000000 1 0\n0 0 0\n").unwrap_err();
        assert!(err.to_string().contains("vertex 1 (of 1000000000000)"));
    }
}
