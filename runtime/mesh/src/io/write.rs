//! Writers: OBJ (with per-vertex uvs) and legacy ASCII VTK unstructured
//! grids with point data. Every writer checks its input first (indices in
//! range, finite numbers, data lengths) so that it never writes a file it
//! could not read back, then writes atomically (see [`super::atomic`]).
//!
//! Numbers are printed in shortest round-trip form (floats by `zmij`, e.g.
//! `1.0`, `-0.0`, `0.1`, `0.00001`, `1e-7`, `1e+300`; integers by `itoa`),
//! so reading a written file gives bit-identical values. The body of a file
//! is formatted in parallel chunks of [`CHUNK_LINES`] lines (rayon), at
//! most [`CHUNKS_PER_BATCH`] chunks in memory at once, written in order:
//! the bytes do not depend on the number of threads.

use std::io::{self, Write};
use std::path::Path;

use rayon::prelude::*;

use super::atomic::write_atomic;
use crate::error::{MeshError, ValidationError};
use crate::types::{TetMesh, TriMesh};
use crate::validate::check_all_finite;

/// Lines formatted by one parallel task into one buffer (about 0.5 MB of
/// text for OBJ vertex lines).
const CHUNK_LINES: usize = 8192;

/// Chunks formatted before they are written: bounds the text held in
/// memory to about `CHUNK_LINES × CHUNKS_PER_BATCH` lines whatever the
/// mesh size.
const CHUNKS_PER_BATCH: usize = 16;

/// One named point-data array: `(name, values, components)`, with
/// `values.len() == vertex_count · components`, stored vertex-major.
pub type PointData<'a> = (&'a str, &'a [f64], usize);

fn check_elements<const K: usize>(
    elements: &[[usize; K]],
    positions: &[[f64; 3]],
) -> Result<(), MeshError> {
    let n = positions.len();
    for (e, el) in elements.iter().enumerate() {
        if let Some(&index) = el.iter().find(|&&v| v >= n) {
            return Err(ValidationError::IndexOutOfRange {
                element: e,
                index,
                vertex_count: n,
            }
            .into());
        }
    }
    check_all_finite(positions)?;
    Ok(())
}

fn check_point_data(path: &Path, n: usize, data: &[PointData<'_>]) -> Result<(), MeshError> {
    let bad = |message: String| MeshError::Data {
        path: path.to_path_buf(),
        message,
    };
    for (i, (name, values, comps)) in data.iter().enumerate() {
        if name.is_empty() || name.chars().any(|c| c.is_whitespace() || c.is_control()) {
            return Err(bad(format!(
                "point-data name {name:?} must be non-empty without spaces"
            )));
        }
        if data[..i].iter().any(|(other, _, _)| other == name) {
            return Err(bad(format!("point-data name {name:?} is used twice")));
        }
        if *comps == 0 || Some(values.len()) != n.checked_mul(*comps) {
            return Err(bad(format!(
                "point data {name:?} has {} values, expected {n} vertices × {comps} components",
                values.len()
            )));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(bad(format!(
                "point data {name:?} has a non-finite value {} at vertex {} component {}",
                values[k],
                k / comps,
                k % comps
            )));
        }
    }
    Ok(())
}

/// Append `x` in shortest round-trip form (finite by the writers' checks;
/// a non-finite value would print as `NaN`/`inf`, never garbage).
fn put_f64(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(zmij::Buffer::new().format(x).as_bytes());
}

/// Append the decimal digits of `i`.
fn put_usize(out: &mut Vec<u8>, i: usize) {
    out.extend_from_slice(itoa::Buffer::new().format(i).as_bytes());
}

/// Append one line: `prefix`, then `xs` separated by single spaces.
fn put_floats(out: &mut Vec<u8>, prefix: &[u8], xs: &[f64]) {
    out.extend_from_slice(prefix);
    for (k, &x) in xs.iter().enumerate() {
        if k > 0 {
            out.push(b' ');
        }
        put_f64(out, x);
    }
    out.push(b'\n');
}

/// Append one line: `prefix`, then ` i` (or ` i/i` when `with_vt`) for each
/// index, `i = ids[k] + base`.
fn put_ids(out: &mut Vec<u8>, prefix: &[u8], ids: &[usize], base: usize, with_vt: bool) {
    out.extend_from_slice(prefix);
    for &id in ids {
        out.push(b' ');
        put_usize(out, id + base);
        if with_vt {
            out.push(b'/');
            put_usize(out, id + base);
        }
    }
    out.push(b'\n');
}

/// Write lines `0..n`, line `i` appended to a buffer by `line(buffer, i)`
/// (newline included), formatted in parallel chunks and written in order.
fn write_lines(
    w: &mut dyn Write,
    n: usize,
    line: impl Fn(&mut Vec<u8>, usize) + Sync,
) -> io::Result<()> {
    write_lines_in(w, n, CHUNK_LINES, CHUNKS_PER_BATCH, line)
}

/// [`write_lines`] with explicit chunk and batch sizes (lines per chunk,
/// chunks per batch; both at least 1): each batch is formatted in
/// parallel, one buffer per chunk, then the buffers are written in order.
/// The buffers are reused from batch to batch.
fn write_lines_in(
    w: &mut dyn Write,
    n: usize,
    chunk: usize,
    batch: usize,
    line: impl Fn(&mut Vec<u8>, usize) + Sync,
) -> io::Result<()> {
    let chunk = chunk.max(1);
    let batch = batch.max(1).min(n.div_ceil(chunk));
    let mut buffers = vec![Vec::new(); batch];
    let mut start = 0;
    while start < n {
        let end = start.saturating_add(chunk.saturating_mul(batch)).min(n);
        buffers.par_iter_mut().enumerate().for_each(|(c, out)| {
            out.clear();
            let first = start.saturating_add(c * chunk).min(end);
            for i in first..first.saturating_add(chunk).min(end) {
                line(out, i);
            }
        });
        for b in &buffers {
            w.write_all(b)?;
        }
        start = end;
    }
    Ok(())
}

/// Write an OBJ file: `v x y z` per vertex, then (when `mesh.uvs` is set)
/// `vt u v` per vertex and faces `f a/a b/b c/c`, else `f a b c`.
pub fn write_obj(path: impl AsRef<Path>, mesh: &TriMesh) -> Result<(), MeshError> {
    let path = path.as_ref();
    check_elements(&mesh.triangles, &mesh.positions)?;
    if let Some(uvs) = &mesh.uvs {
        if uvs.len() != mesh.positions.len() {
            return Err(ValidationError::UvCountMismatch {
                uvs: uvs.len(),
                vertices: mesh.positions.len(),
            }
            .into());
        }
        if let Some((vertex, uv)) = uvs
            .iter()
            .enumerate()
            .find(|(_, uv)| !uv[0].is_finite() || !uv[1].is_finite())
        {
            return Err(ValidationError::NonFiniteUv { vertex, uv: *uv }.into());
        }
    }
    write_atomic(path, |w| obj_body(w, mesh))
}

/// The text of [`write_obj`] (input already checked).
fn obj_body(w: &mut dyn Write, mesh: &TriMesh) -> io::Result<()> {
    let (positions, triangles) = (&mesh.positions, &mesh.triangles);
    writeln!(
        w,
        "# ecc-mesh: {} vertices, {} triangles",
        positions.len(),
        triangles.len()
    )?;
    write_lines(w, positions.len(), |out, i| {
        put_floats(out, b"v ", &positions[i]);
    })?;
    if let Some(uvs) = &mesh.uvs {
        write_lines(w, uvs.len(), |out, i| put_floats(out, b"vt ", &uvs[i]))?;
    }
    let with_vt = mesh.uvs.is_some();
    write_lines(w, triangles.len(), |out, i| {
        put_ids(out, b"f", &triangles[i], 1, with_vt);
    })
}

fn write_vtk<const K: usize>(
    path: &Path,
    positions: &[[f64; 3]],
    elements: &[[usize; K]],
    cell_type: u8,
    data: &[PointData<'_>],
) -> Result<(), MeshError> {
    check_elements(elements, positions)?;
    check_point_data(path, positions.len(), data)?;
    write_atomic(path, |w| {
        vtk_body(w, positions, elements, cell_type)?;
        vtk_point_data(w, positions.len(), data)
    })
}

/// Header, points, cells and cell types of [`write_vtk`].
fn vtk_body<const K: usize>(
    w: &mut dyn Write,
    positions: &[[f64; 3]],
    elements: &[[usize; K]],
    cell_type: u8,
) -> io::Result<()> {
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "ecc-mesh output")?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET UNSTRUCTURED_GRID")?;
    writeln!(w, "POINTS {} double", positions.len())?;
    write_lines(w, positions.len(), |out, i| {
        put_floats(out, b"", &positions[i]);
    })?;
    writeln!(w, "CELLS {} {}", elements.len(), elements.len() * (K + 1))?;
    let count = K.to_string();
    write_lines(w, elements.len(), |out, i| {
        put_ids(out, count.as_bytes(), &elements[i], 0, false);
    })?;
    writeln!(w, "CELL_TYPES {}", elements.len())?;
    let type_line = format!("{cell_type}\n");
    write_lines(w, elements.len(), |out, _| {
        out.extend_from_slice(type_line.as_bytes());
    })
}

/// The `POINT_DATA` section of [`write_vtk`] (none when `data` is empty):
/// one `FIELD` array per entry, one line of components per vertex.
fn vtk_point_data(w: &mut dyn Write, n: usize, data: &[PointData<'_>]) -> io::Result<()> {
    if data.is_empty() {
        return Ok(());
    }
    writeln!(w, "POINT_DATA {n}")?;
    writeln!(w, "FIELD FieldData {}", data.len())?;
    for &(name, values, comps) in data {
        writeln!(w, "{name} {comps} {n} double")?;
        write_lines(w, n, |out, i| {
            put_floats(out, b"", &values[i * comps..(i + 1) * comps]);
        })?;
    }
    Ok(())
}

/// Write a triangle mesh as a legacy ASCII VTK unstructured grid (cell
/// type 5) with optional point data (written as a `FIELD` of `double`
/// arrays, one tuple per vertex).
pub fn write_vtk_tri(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    point_data: &[PointData<'_>],
) -> Result<(), MeshError> {
    write_vtk(
        path.as_ref(),
        &mesh.positions,
        &mesh.triangles,
        5,
        point_data,
    )
}

/// Write a tet mesh as a legacy ASCII VTK unstructured grid (cell type 10)
/// with optional point data.
pub fn write_vtk_tet(
    path: impl AsRef<Path>,
    mesh: &TetMesh,
    point_data: &[PointData<'_>],
) -> Result<(), MeshError> {
    write_vtk(path.as_ref(), &mesh.positions, &mesh.tets, 10, point_data)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(xs: &[f64]) -> String {
        let mut out = Vec::new();
        put_floats(&mut out, b"", xs);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn floats_are_shortest_round_trip() {
        let awkward = [
            0.0,
            -0.0,
            1.0,
            -3.0,
            0.1,
            1.0 / 3.0,
            1e-5,
            1e-7,
            1e16,
            2f64.powi(53),
            1e-300,
            5e-324,
            -5e-324,
            1e300,
            f64::MAX,
            f64::MIN_POSITIVE,
        ];
        let line = text(&awkward);
        assert!(line.ends_with('\n') && !line.ends_with(" \n"), "{line:?}");
        let toks: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(toks.len(), awkward.len());
        for (t, x) in toks.iter().zip(awkward) {
            assert_eq!(t.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{t}");
            // shortest: never longer than Rust's own shortest form plus an
            // exponent sign or the zeros of a fixed-point form
            assert!(t.len() <= format!("{x:?}").len() + 4, "{t} vs {x:?}");
        }
        assert_eq!(text(&[1.0, -0.0, 0.5]), "1.0 -0.0 0.5\n");
    }

    #[test]
    fn indices_keep_every_digit() {
        let mut out = Vec::new();
        put_ids(&mut out, b"f", &[0, 41, usize::MAX - 1], 1, true);
        let max = usize::MAX;
        assert_eq!(
            String::from_utf8(out).unwrap(),
            format!("f 1/1 42/42 {max}/{max}\n")
        );
        let mut out = Vec::new();
        put_ids(&mut out, b"4", &[7, 0, 1_000_000_007, 3], 0, false);
        assert_eq!(out, b"4 7 0 1000000007 3\n");
    }

    /// Every chunk/batch split gives the sequential text: no line lost,
    /// repeated or moved at chunk and batch boundaries.
    #[test]
    fn chunked_lines_equal_sequential_lines() {
        let line = |out: &mut Vec<u8>, i: usize| {
            out.extend_from_slice(format!("line {i} {}\n", i as f64 / 7.0).as_bytes());
        };
        for n in [0, 1, 2, 5, 6, 7, 12, 13, 40] {
            let mut want = Vec::new();
            (0..n).for_each(|i| line(&mut want, i));
            for (chunk, batch) in [(1, 1), (2, 3), (3, 2), (5, 1), (7, 4), (64, 16), (0, 0)] {
                let mut got = Vec::new();
                write_lines_in(&mut got, n, chunk, batch, line).unwrap();
                assert_eq!(got, want, "n {n}, chunk {chunk}, batch {batch}");
            }
        }
    }

    #[test]
    fn write_errors_propagate() {
        struct Full;
        impl Write for Full {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::other("disk full"))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let e = write_lines(&mut Full, 3, |out, _| out.push(b'\n')).unwrap_err();
        assert_eq!(e.to_string(), "disk full");
        // nothing to write, nothing to fail
        assert!(write_lines(&mut Full, 0, |out, _| out.push(b'\n')).is_ok());
    }
}
