//! Wavefront OBJ reader.
//!
//! Understood statements: `v x y [z …]` (a missing `z` is 0; extra values
//! such as `w` or vertex colours are ignored), `vt u [v …]`, and
//! `f a b c` with corners `v`, `v/vt`, `v//vn` or `v/vt/vn`. Indices are
//! 1-based; negative indices count back from the last vertex defined so far.
//! Every other statement (`vn`, `o`, `g`, `s`, `usemtl`, `mtllib`, `l`, …)
//! is ignored. Faces with more than three corners are rejected (triangulate
//! first): splitting them silently would change the elements.
//!
//! Texture coordinates: OBJ attaches them to face corners, [`TriMesh`] to
//! vertices. `uvs` is filled when every vertex is used with exactly one
//! `vt` (a seamless parameterisation, as [`crate::write_obj`] writes it);
//! otherwise (seams, as in `spot.obj`, or no `vt`) `uvs` is `None`.

use super::text::{parse_f64, parse_i64, shorten};
use crate::error::ParseError;
use crate::types::TriMesh;

/// Resolve a 1-based or negative OBJ index against `count` items so far.
fn resolve(tok: &str, count: usize, line: usize, what: &str) -> Result<usize, ParseError> {
    let k = parse_i64(tok, line, what)?;
    if k == 0 {
        return Err(ParseError::line(
            line,
            format!("{what} 0 is invalid: OBJ indices are 1-based (or negative, relative)"),
        ));
    }
    if k > 0 {
        Ok((k - 1) as usize)
    } else {
        let back = k.unsigned_abs() as usize;
        if back > count {
            Err(ParseError::line(
                line,
                format!("relative {what} {k} points before the first one ({count} defined so far)"),
            ))
        } else {
            Ok(count - back)
        }
    }
}

/// The statements read so far, in file order.
#[derive(Default)]
struct Obj {
    positions: Vec<[f64; 3]>,
    tex: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    /// The `vt` index of each face corner, when given; empty until the
    /// first corner with a `vt` (then one entry per face: a file without
    /// texture coordinates pays nothing for them).
    corner_vt: Vec<[Option<usize>; 3]>,
    /// `(face, line)` of the faces that refer to a vertex or texture
    /// coordinate not defined yet when they are read: the only ones that
    /// can be out of range at the end ([`Obj::check_ranges`]).
    forward: Vec<(usize, usize)>,
}

/// `v x y [z …]` after its keyword: a missing z is 0, extra values ignored.
fn read_vertex<'a>(
    toks: &mut impl Iterator<Item = &'a str>,
    content: &str,
    line: usize,
) -> Result<[f64; 3], ParseError> {
    // no per-line allocation: read at most x, y, z
    let (Some(tx), Some(ty)) = (toks.next(), toks.next()) else {
        let found = content.split_whitespace().count() - 1;
        return Err(ParseError::line(
            line,
            format!("vertex needs at least x and y, found {found} values"),
        ));
    };
    let x = parse_f64(tx, line, "vertex x")?;
    let y = parse_f64(ty, line, "vertex y")?;
    let z = match toks.next() {
        Some(t) => parse_f64(t, line, "vertex z")?,
        None => 0.0,
    };
    Ok([x, y, z])
}

/// `vt u [v …]` after its keyword: a missing v is 0.
fn read_texture<'a>(
    toks: impl Iterator<Item = &'a str>,
    line: usize,
) -> Result<[f64; 2], ParseError> {
    let vals: Vec<&str> = toks.collect();
    if vals.is_empty() {
        return Err(ParseError::line(
            line,
            "texture coordinate needs at least u",
        ));
    }
    let u = parse_f64(vals[0], line, "texture u")?;
    let v = match vals.get(1) {
        Some(t) => parse_f64(t, line, "texture v")?,
        None => 0.0,
    };
    Ok([u, v])
}

impl Obj {
    /// `f a b c` after its keyword: exactly three corners `v`, `v/vt`,
    /// `v//vn` or `v/vt/vn`, indices resolved against what is defined so far.
    fn read_face<'a>(
        &mut self,
        toks: &mut impl Iterator<Item = &'a str>,
        content: &str,
        line: usize,
    ) -> Result<(), ParseError> {
        let (Some(c0), Some(c1), Some(c2), None) =
            (toks.next(), toks.next(), toks.next(), toks.next())
        else {
            let found = content.split_whitespace().count() - 1;
            return Err(ParseError::line(
                line,
                format!(
                    "face has {found} corners: only triangles are supported (triangulate the mesh first)"
                ),
            ));
        };
        let corners = [c0, c1, c2];
        let mut tri = [0usize; 3];
        let mut vts = [None; 3];
        for (k, c) in corners.iter().enumerate() {
            let mut parts = c.split('/');
            let vtok = parts.next().unwrap_or("");
            tri[k] = resolve(vtok, self.positions.len(), line, "vertex index")?;
            if let Some(t) = parts.next().filter(|t| !t.is_empty()) {
                vts[k] = Some(resolve(t, self.tex.len(), line, "texture index")?);
            }
            if let Some(n) = parts.next().filter(|t| !t.is_empty()) {
                parse_i64(n, line, "normal index")?;
            }
            if parts.next().is_some() {
                return Err(ParseError::line(
                    line,
                    format!("malformed face corner `{}`", shorten(c)),
                ));
            }
        }
        let face = self.triangles.len();
        let ahead = |i: &usize, n: usize| *i >= n;
        if tri.iter().any(|v| ahead(v, self.positions.len()))
            || vts.iter().flatten().any(|t| ahead(t, self.tex.len()))
        {
            self.forward.push((face, line));
        }
        self.triangles.push(tri);
        if self.corner_vt.is_empty() && vts.iter().any(Option::is_some) {
            self.corner_vt.resize(face, [None; 3]);
        }
        if self.corner_vt.len() == face {
            self.corner_vt.push(vts);
        }
        Ok(())
    }

    /// Every face's vertex and texture indices are within what the whole
    /// file defines (positive indices may point forward; only the faces in
    /// `forward` can fail, the others were in range when read).
    fn check_ranges(&self) -> Result<(), ParseError> {
        let (positions, tex) = (&self.positions, &self.tex);
        for &(f, line) in &self.forward {
            for &v in &self.triangles[f] {
                if v >= positions.len() {
                    return Err(ParseError::line(
                        line,
                        format!(
                            "face refers to vertex {} but the file defines only {} vertices",
                            v + 1,
                            positions.len()
                        ),
                    ));
                }
            }
            for t in self.corner_vt.get(f).into_iter().flatten().flatten() {
                if *t >= tex.len() {
                    return Err(ParseError::line(
                        line,
                        format!(
                            "face refers to texture coordinate {} but the file defines only {}",
                            t + 1,
                            tex.len()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Parse OBJ text into a triangle mesh (see the module docs).
pub fn parse_obj(text: &str) -> Result<TriMesh, ParseError> {
    let mut o = Obj::default();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut toks = content.split_whitespace();
        let Some(key) = toks.next() else { continue };
        match key {
            "v" => o.positions.push(read_vertex(&mut toks, content, line)?),
            "vt" => o.tex.push(read_texture(toks, line)?),
            "f" => o.read_face(&mut toks, content, line)?,
            _ => {}
        }
    }
    if o.positions.is_empty() && o.triangles.is_empty() {
        return Err(ParseError::format("no vertices or faces: empty OBJ file"));
    }
    if o.triangles.is_empty() {
        return Err(ParseError::format("the OBJ file has vertices but no faces"));
    }
    o.check_ranges()?;
    let uvs = per_vertex_uvs(o.positions.len(), &o.triangles, &o.corner_vt, &o.tex);
    Ok(TriMesh {
        positions: o.positions,
        triangles: o.triangles,
        uvs,
    })
}

/// Per-vertex uvs if every vertex has exactly one `vt` over all its corners.
fn per_vertex_uvs(
    n: usize,
    triangles: &[[usize; 3]],
    corner_vt: &[[Option<usize>; 3]],
    tex: &[[f64; 2]],
) -> Option<Vec<[f64; 2]>> {
    if tex.is_empty() || corner_vt.len() != triangles.len() {
        return None;
    }
    let mut vt_of: Vec<Option<usize>> = vec![None; n];
    for (tri, vts) in triangles.iter().zip(corner_vt) {
        for k in 0..3 {
            let t = vts[k]?;
            match vt_of[tri[k]] {
                None => vt_of[tri[k]] = Some(t),
                Some(prev) if prev == t || tex[prev] == tex[t] => {}
                Some(_) => return None,
            }
        }
    }
    vt_of.into_iter().map(|t| t.map(|t| tex[t])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_vertices_and_non_triangles_are_located_errors() {
        let e = parse_obj("v 1 2 3\nv 1 # y missing\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2: vertex needs at least x and y, found 1 values"
        );
        let e = parse_obj("v 0 0\nv 1 0\nv 1 1\nv 0 1\nf 1 2 3 4\n").unwrap_err();
        assert!(
            e.to_string().starts_with("line 5: face has 4 corners"),
            "{e}"
        );
        let e = parse_obj("v 0 0\nv 1 0\nf 1 2\n").unwrap_err();
        assert!(
            e.to_string().starts_with("line 3: face has 2 corners"),
            "{e}"
        );
    }

    #[test]
    fn reads_triangles_uvs_and_negative_indices() {
        let text = "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                    vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf -4/-4 -2/-2 -1/-1\ng x\nusemtl m\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.uvs.unwrap()[3], [0.0, 1.0]);
    }

    #[test]
    fn forward_references_and_late_texture_corners() {
        // faces may name vertices defined further down
        let m = parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        // the first face without vt, a later one with: no uvs, no panic
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1 2 3\nf 2/1 4/1 3/1\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert!(m.uvs.is_none());
        // the error names the line of the first face out of range, not a later one
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1/2 2 3\nf 1 2 9\nvt 0 0\n";
        let e = parse_obj(text).unwrap_err().to_string();
        assert!(
            e.contains("line 5: face refers to texture coordinate 2 but the file defines only 1"),
            "{e}"
        );
        let text = "f 1 2 3\nf 1 2 7\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let e = parse_obj(text).unwrap_err().to_string();
        assert!(e.contains("line 2: face refers to vertex 7"), "{e}");
    }

    #[test]
    fn non_ascii_whitespace_separates_tokens() {
        // U+00A0, U+000B and U+2003 are whitespace (str::split_whitespace)
        let ascii = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let odd = parse_obj("v 0\u{a0}0 0\nv 1\u{b}0 0\nv 0 1 0 # é\nf 1 2\u{2003}3\n").unwrap();
        assert_eq!(ascii, odd);
    }

    #[test]
    fn seams_or_missing_vt_give_no_uvs() {
        let seam = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 5 5\n\
                    f 1/1 2/2 3/3\nf 2/4 4/2 3/3\n";
        assert!(parse_obj(seam).unwrap().uvs.is_none());
        let partial = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n";
        assert!(parse_obj(partial).unwrap().uvs.is_none());
    }

    #[test]
    fn malformed_inputs_are_rejected_with_lines() {
        let cases: &[(&str, &str)] = &[
            ("", "empty OBJ"),
            ("v 0 0 0\n", "no faces"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1\n",
                "line 4: face has 4 corners",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                "line 4: vertex index 0 is invalid: OBJ indices are 1-based",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                "line 4: face refers to vertex 4 but the file defines only 3",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",
                "line 4: relative vertex index -4",
            ),
            (
                "v 0 zero 0\n",
                "line 1: expected vertex y (a number), found `zero`",
            ),
            ("v 0 0 nan\n", "line 1: vertex z is not finite"),
            ("v 0\n", "line 1: vertex needs at least x and y"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
                "line 4: expected vertex index (an integer), found `x`",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
                "line 4: face refers to texture coordinate 1 but the file defines only 0",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n",
                "line 4: malformed face corner",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "face has 2 corners"),
            ("vt\n", "line 1: texture coordinate needs at least u"),
        ];
        for (text, want) in cases {
            let err = parse_obj(text).unwrap_err().to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
    }
}
