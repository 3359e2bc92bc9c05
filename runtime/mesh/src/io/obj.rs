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

/// The statements of the whole file, in file order.
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

/// Storage for a known number of items, filled in order.
struct Slots<'a, T> {
    items: &'a mut [T],
    len: usize,
}

impl<'a, T> Slots<'a, T> {
    fn new(items: &'a mut [T]) -> Self {
        Slots { items, len: 0 }
    }

    fn push(&mut self, item: T, line: usize) -> Result<(), ParseError> {
        let slot = self.items.get_mut(self.len).ok_or_else(|| {
            ParseError::line(line, "internal error: more statements than counted")
        })?;
        *slot = item;
        self.len += 1;
        Ok(())
    }
}

/// One chunk of lines being read into its part of the file's storage.
struct Chunk<'a> {
    /// `v` and `vt` statements before the chunk (negative indices count
    /// back over them too).
    v_base: usize,
    vt_base: usize,
    positions: Slots<'a, [f64; 3]>,
    tex: Slots<'a, [f64; 2]>,
    triangles: Slots<'a, [usize; 3]>,
    /// As [`Obj::corner_vt`], faces counted in the chunk.
    corner_vt: Vec<[Option<usize>; 3]>,
    /// As [`Obj::forward`], faces counted in the chunk.
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

impl Chunk<'_> {
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
        let (n_v, n_vt) = (
            self.v_base + self.positions.len,
            self.vt_base + self.tex.len,
        );
        for (k, c) in corners.iter().enumerate() {
            let mut parts = c.split('/');
            let vtok = parts.next().unwrap_or("");
            tri[k] = resolve(vtok, n_v, line, "vertex index")?;
            if let Some(t) = parts.next().filter(|t| !t.is_empty()) {
                vts[k] = Some(resolve(t, n_vt, line, "texture index")?);
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
        let face = self.triangles.len;
        let ahead = |i: &usize, n: usize| *i >= n;
        if tri.iter().any(|v| ahead(v, n_v)) || vts.iter().flatten().any(|t| ahead(t, n_vt)) {
            self.forward.push((face, line));
        }
        self.triangles.push(tri, line)?;
        if self.corner_vt.is_empty() && vts.iter().any(Option::is_some) {
            self.corner_vt.resize(face, [None; 3]);
        }
        if self.corner_vt.len() == face {
            self.corner_vt.push(vts);
        }
        Ok(())
    }
}

impl Obj {
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

/// Files at least this long are parsed in chunks of lines on rayon's
/// threads ([`parse_chunks`], four chunks a thread for balance); below, in
/// one. The 1M-triangle disk's 54 MB (`setup_timing`, 2 threads, best of
/// 3): read in 0.28 s against 0.37–0.40 s in one pass (0.21–0.23 s since
/// tokens are split at ASCII whitespace bytes, [`is_plain`]).
const PARALLEL_MIN_BYTES: usize = 1 << 20;

/// Parse OBJ text into a triangle mesh (see the module docs).
pub fn parse_obj(text: &str) -> Result<TriMesh, ParseError> {
    let pieces = if text.len() >= PARALLEL_MIN_BYTES {
        4 * rayon::current_num_threads()
    } else {
        1
    };
    let o = parse_chunks(text, pieces)?;
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

/// The statements of `text` cut into about `pieces` chunks of whole lines,
/// parsed concurrently and joined in file order: the same result and the
/// same (first) error as one pass over the file. Each chunk first counts its
/// lines and its `v`, `vt` and `f` statements, so every chunk knows its
/// first line number, the vertices and texture coordinates before it (which
/// negative indices and forward references are resolved against) and where
/// its statements go in the file's storage.
fn parse_chunks(text: &str, pieces: usize) -> Result<Obj, ParseError> {
    use rayon::prelude::*;
    let chunks = line_chunks(text, pieces);
    // whether each chunk's tokens split at ASCII whitespace, decided once
    // for both passes
    let plain: Vec<bool> = chunks.par_iter().map(|c| is_plain(c)).collect();
    let counts: Vec<Counts> = chunks
        .par_iter()
        .zip(&plain)
        .map(|(c, &plain)| count_statements(c, plain))
        .collect();
    let mut bases = Vec::with_capacity(chunks.len());
    let mut total = Counts {
        lines: 1,
        ..Counts::default()
    };
    for c in &counts {
        bases.push(total);
        total = total.plus(c);
    }
    let mut obj = Obj {
        positions: vec![[0.0; 3]; total.v],
        tex: vec![[0.0; 2]; total.vt],
        triangles: vec![[0; 3]; total.f],
        ..Obj::default()
    };
    // each chunk's part of the storage, in file order
    let (mut positions, mut tex, mut triangles) = (
        obj.positions.as_mut_slice(),
        obj.tex.as_mut_slice(),
        obj.triangles.as_mut_slice(),
    );
    let mut jobs = Vec::with_capacity(chunks.len());
    for (((chunk, &plain), base), own) in chunks.iter().zip(&plain).zip(&bases).zip(&counts) {
        let (p, rest_p) = positions.split_at_mut(own.v);
        let (t, rest_t) = tex.split_at_mut(own.vt);
        let (f, rest_f) = triangles.split_at_mut(own.f);
        (positions, tex, triangles) = (rest_p, rest_t, rest_f);
        let out = Chunk {
            v_base: base.v,
            vt_base: base.vt,
            positions: Slots::new(p),
            tex: Slots::new(t),
            triangles: Slots::new(f),
            corner_vt: Vec::new(),
            forward: Vec::new(),
        };
        jobs.push((*chunk, plain, base.lines, out));
    }
    let parsed: Vec<Result<Chunk<'_>, ParseError>> = jobs
        .into_par_iter()
        .map(|(chunk, plain, line, out)| parse_lines(chunk, plain, line, out))
        .collect();
    let (mut corner_vt, mut forward) = (Vec::new(), Vec::new());
    for (chunk, before) in parsed.into_iter().zip(&bases) {
        let chunk = chunk?;
        let (faces, own) = (before.f, chunk.triangles.len);
        if !chunk.corner_vt.is_empty() || !corner_vt.is_empty() {
            // one entry per face from the first corner with a `vt` on
            corner_vt.resize(faces, [None; 3]);
            corner_vt.extend_from_slice(&chunk.corner_vt);
            corner_vt.resize(faces + own, [None; 3]);
        }
        forward.extend(chunk.forward.iter().map(|&(f, line)| (faces + f, line)));
    }
    (obj.corner_vt, obj.forward) = (corner_vt, forward);
    Ok(obj)
}

/// `text` cut after a newline near each of `pieces` equal byte lengths.
fn line_chunks(text: &str, pieces: usize) -> Vec<&str> {
    let mut chunks = Vec::with_capacity(pieces);
    let mut start = 0;
    for k in 1..pieces {
        let target = (text.len() * k / pieces).max(start);
        let Some(nl) = text.as_bytes()[target..].iter().position(|&b| b == b'\n') else {
            break;
        };
        let end = target + nl + 1;
        chunks.push(&text[start..end]);
        start = end;
    }
    chunks.push(&text[start..]);
    chunks
}

/// A line's content (before any `#`) and its tokens: the counting pass and
/// the parse read statements alike. `plain` says the line's chunk passed
/// [`is_plain`], so its tokens can be split at ASCII whitespace bytes.
fn statement(raw: &str, plain: bool) -> (&str, Words<'_>) {
    let end = memchr::memchr(b'#', raw.as_bytes()).unwrap_or(raw.len());
    // `#` is ASCII: `end` is a char boundary
    let content = &raw[..end];
    let words = if plain {
        Words::Ascii(content.split_ascii_whitespace())
    } else {
        Words::Unicode(content.split_whitespace())
    };
    (content, words)
}

/// Text without bytes ≥ 0x80 or vertical tabs: there, Unicode whitespace
/// (`str::split_whitespace`, which separates tokens) is exactly ASCII
/// whitespace, found byte by byte instead of by decoding characters (a
/// third of the 54 MB disk's read).
fn is_plain(text: &str) -> bool {
    text.is_ascii() && memchr::memchr(0x0B, text.as_bytes()).is_none()
}

/// The whitespace-separated tokens of a statement ([`statement`]).
enum Words<'a> {
    Ascii(std::str::SplitAsciiWhitespace<'a>),
    Unicode(std::str::SplitWhitespace<'a>),
}

impl<'a> Iterator for Words<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        match self {
            Words::Ascii(w) => w.next(),
            Words::Unicode(w) => w.next(),
        }
    }
}

/// The lines of `chunk`, as `str::lines` gives them up to a trailing `\r`
/// (which [`statement`]'s whitespace split drops): the pieces between
/// `\n`s, without an empty one after a final `\n`.
fn lines(chunk: &str) -> impl Iterator<Item = &str> {
    let bytes = chunk.as_bytes();
    let mut ends = memchr::memchr_iter(b'\n', bytes);
    let mut start = 0;
    std::iter::from_fn(move || {
        let end = match ends.next() {
            Some(k) => k,
            None if start < bytes.len() => bytes.len(),
            None => return None,
        };
        // `\n` is ASCII: `start` and `end` are char boundaries
        let line = &chunk[start..end];
        start = end + 1;
        Some(line)
    })
}

/// Lines and `v`, `vt`, `f` statements (of a chunk, or before it).
#[derive(Clone, Copy, Default)]
struct Counts {
    lines: usize,
    v: usize,
    vt: usize,
    f: usize,
}

impl Counts {
    fn plus(self, o: &Counts) -> Counts {
        Counts {
            lines: self.lines + o.lines,
            v: self.v + o.v,
            vt: self.vt + o.vt,
            f: self.f + o.f,
        }
    }
}

/// The [`Counts`] of a chunk (`plain`: it passed [`is_plain`]).
fn count_statements(chunk: &str, plain: bool) -> Counts {
    let mut n = Counts::default();
    for raw in lines(chunk) {
        n.lines += 1;
        match statement(raw, plain).1.next() {
            Some("v") => n.v += 1,
            Some("vt") => n.vt += 1,
            Some("f") => n.f += 1,
            _ => {}
        }
    }
    n
}

/// Parse one chunk (`plain`: it passed [`is_plain`]), whose first line is
/// `first_line`, into `out`.
fn parse_lines<'a>(
    chunk: &str,
    plain: bool,
    first_line: usize,
    mut out: Chunk<'a>,
) -> Result<Chunk<'a>, ParseError> {
    for (i, raw) in lines(chunk).enumerate() {
        let line = first_line + i;
        let (content, mut toks) = statement(raw, plain);
        let Some(key) = toks.next() else { continue };
        match key {
            "v" => out
                .positions
                .push(read_vertex(&mut toks, content, line)?, line)?,
            "vt" => out.tex.push(read_texture(toks, line)?, line)?,
            "f" => out.read_face(&mut toks, content, line)?,
            _ => {}
        }
    }
    Ok(out)
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

    /// The byte scans give what `str::lines` and `split_whitespace` give.
    #[test]
    fn byte_scans_agree_with_str_methods() {
        for text in [
            "",
            "\n",
            "a",
            "a\n",
            "a\r\nb",
            "\n\nx\n",
            "v 1 2\r\n# c\nf 1 2 3",
        ] {
            let ours: Vec<&str> = lines(text)
                .map(|l| l.strip_suffix('\r').unwrap_or(l))
                .collect();
            assert_eq!(ours, text.lines().collect::<Vec<_>>(), "{text:?}");
        }
        for raw in ["v 1\t2 3 # x", " f  1/1 2 3\x0c", "vt 0 # 1 2", "#", ""] {
            assert!(is_plain(raw), "{raw:?}");
            let (content, words) = statement(raw, true);
            let (general, unicode) = statement(raw, false);
            assert_eq!(content, general);
            assert_eq!(words.collect::<Vec<_>>(), unicode.collect::<Vec<_>>());
        }
        assert!(!is_plain("v 1\u{b}2 3"));
        assert!(!is_plain("v 1 2 3 # é"));
    }

    #[test]
    fn seams_or_missing_vt_give_no_uvs() {
        let seam = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 5 5\n\
                    f 1/1 2/2 3/3\nf 2/4 4/2 3/3\n";
        assert!(parse_obj(seam).unwrap().uvs.is_none());
        let partial = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n";
        assert!(parse_obj(partial).unwrap().uvs.is_none());
    }

    /// Chunked parsing (any number of chunks, cut anywhere between lines)
    /// gives one pass's statements and, for bad input, its first error.
    #[test]
    fn chunks_parse_as_one_pass() {
        let mut good = String::from("# grid with uvs\r\n");
        for j in 0..6 {
            for i in 0..6 {
                good += &format!("v {i} {j} 0.5\nvt {} {}\n", i as f64 / 5.0, j as f64 / 5.0);
            }
        }
        good += "f 40/40 41/41 -1/-1\ng x\n"; // forward references first
        for j in 0..5 {
            for i in 0..5 {
                let v = 1 + i + 6 * j;
                good += &format!("f {v}/{v} {}/{} {}/{}  # c\n", v + 1, v + 1, v + 7, v + 7);
                good += &format!("f {v} {} {}\n", v + 7, v + 6);
            }
        }
        good += "f 37 38 39\nv 9 9 9\nv 9 8 9\nv 8 9 9\nf -3 -2 -1\n";
        let bad = [
            good.replace("f 7 13 12\n", "f 7 13\n"),
            good.replace("v 3 4 0.5", "v 3 four 0.5"),
            good.replace("f -3 -2 -1", "f -3 -2 -99"),
            good.replace("f 40/40 41/41", "f 40/40 99/41"),
            good.replace("f 37 38 39", "f 37 38 40"),
            good.replace("f 7 13 12\n", "f 7 13\n") + "v 1\n",
        ];
        let one = parse_chunks(&good, 1).unwrap();
        assert!(one.forward.len() == 2 && !one.corner_vt.is_empty());
        for pieces in 2..=9 {
            let o = parse_chunks(&good, pieces).unwrap();
            assert_eq!(o.positions, one.positions, "{pieces}");
            assert_eq!(o.tex, one.tex);
            assert_eq!(o.triangles, one.triangles);
            assert_eq!(o.corner_vt, one.corner_vt);
            assert_eq!(o.forward, one.forward);
            for text in &bad {
                let want = parse_chunks(text, 1).and_then(|o| o.check_ranges());
                let got = parse_chunks(text, pieces).and_then(|o| o.check_ranges());
                let (want, got) = (want.unwrap_err(), got.unwrap_err());
                assert_eq!(want.to_string(), got.to_string(), "{pieces}");
            }
        }
        assert_eq!(line_chunks("a\nb\nc", 3), ["a\n", "b\n", "c"]);
        assert_eq!(line_chunks("abc", 4), ["abc"]);
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
