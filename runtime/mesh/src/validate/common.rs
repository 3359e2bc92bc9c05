//! Checks shared by triangle and tet validation.

use crate::error::ValidationError;
use crate::geometry::bbox_diagonal;
use crate::topology::sort_by_vertex;

/// Indices in range and no repeated vertex inside an element.
pub(crate) fn check_indices<const K: usize>(
    elements: &[[usize; K]],
    vertex_count: usize,
) -> Result<(), ValidationError> {
    for (e, el) in elements.iter().enumerate() {
        if let Some(&index) = el.iter().find(|&&v| v >= vertex_count) {
            return Err(ValidationError::IndexOutOfRange {
                element: e,
                index,
                vertex_count,
            });
        }
        for i in 0..K {
            if el[i + 1..].contains(&el[i]) {
                return Err(ValidationError::RepeatedVertexInElement {
                    element: e,
                    vertices: el.to_vec(),
                });
            }
        }
    }
    Ok(())
}

/// No two elements with the same vertex set.
pub(crate) fn check_duplicates<const K: usize>(
    elements: &[[usize; K]],
) -> Result<(), ValidationError> {
    let mut keys: Vec<([usize; K], usize)> = elements
        .iter()
        .enumerate()
        .map(|(e, el)| {
            let mut key = *el;
            key.sort_unstable();
            (key, e)
        })
        .collect();
    sort_by_vertex(&mut keys, |k| k.0[0], |k| (k.0, k.1));
    // Report the smallest later element id that repeats an earlier one.
    let dup = keys
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|g| g.len() > 1)
        .map(|g| (g[1].1, g[0].1))
        .min();
    match dup {
        Some((element, first)) => Err(ValidationError::DuplicateElement { element, first }),
        None => Ok(()),
    }
}

/// Which vertices are used by some element.
pub(crate) fn referenced<const K: usize>(elements: &[[usize; K]], n: usize) -> Vec<bool> {
    let mut used = vec![false; n];
    for el in elements {
        for &v in el {
            used[v] = true;
        }
    }
    used
}

/// Finite coordinates for every referenced vertex.
pub(crate) fn check_finite(positions: &[[f64; 3]], used: &[bool]) -> Result<(), ValidationError> {
    for (vertex, (p, &u)) in positions.iter().zip(used).enumerate() {
        if u && p.iter().any(|c| !c.is_finite()) {
            return Err(ValidationError::NonFiniteCoordinate {
                vertex,
                position: *p,
            });
        }
    }
    Ok(())
}

/// Bounding-box diagonal of the referenced vertices.
pub(crate) fn reference_length(positions: &[[f64; 3]], used: &[bool]) -> f64 {
    bbox_diagonal(
        positions
            .iter()
            .zip(used)
            .filter(|(_, u)| **u)
            .map(|(p, _)| *p),
    )
}

/// Check rest measures: `|m| ≤ tol` is degenerate (first one reported);
/// when `signed`, `m < 0` is inverted (first one and the count reported).
pub(crate) fn check_measures(
    measures: impl Iterator<Item = f64>,
    tol: f64,
    signed: bool,
    dimension: usize,
) -> Result<(), ValidationError> {
    let mut first_inverted: Option<(usize, f64)> = None;
    let mut count = 0;
    let mut total = 0;
    for (e, m) in measures.enumerate() {
        total += 1;
        if m.abs() <= tol || !m.is_finite() {
            return Err(ValidationError::DegenerateElement {
                element: e,
                measure: m,
                tolerance: tol,
                dimension,
            });
        }
        if signed && m < 0.0 {
            count += 1;
            first_inverted.get_or_insert((e, m));
        }
    }
    match first_inverted {
        Some((element, measure)) => Err(ValidationError::InvertedElement {
            element,
            measure,
            count,
            total,
            dimension,
        }),
        None => Ok(()),
    }
}

/// Refuse unreferenced vertices unless `drop` is set.
pub(crate) fn check_unreferenced(used: &[bool], drop: bool) -> Result<(), ValidationError> {
    if drop {
        return Ok(());
    }
    let count = used.iter().filter(|u| !**u).count();
    if count == 0 {
        return Ok(());
    }
    let first = (0..used.len()).filter(|&v| !used[v]).take(10).collect();
    Err(ValidationError::UnreferencedVertices { count, first })
}

/// Drop unreferenced vertices: the old → new map, the kept old ids, and
/// a warning if anything was dropped.
pub(crate) fn compaction(used: &[bool]) -> (Vec<Option<usize>>, Vec<usize>, Option<String>) {
    let mut map = Vec::with_capacity(used.len());
    let mut kept = Vec::with_capacity(used.len());
    let mut dropped = Vec::new();
    for (v, &u) in used.iter().enumerate() {
        if u {
            map.push(Some(kept.len()));
            kept.push(v);
        } else {
            map.push(None);
            dropped.push(v);
        }
    }
    let warning = (!dropped.is_empty()).then(|| {
        let shown: Vec<String> = dropped.iter().take(10).map(|v| v.to_string()).collect();
        let more = if dropped.len() > 10 { ", …" } else { "" };
        format!(
            "dropped {} unreferenced vertices (ids {}{more}); vertex_map gives old → new ids",
            dropped.len(),
            shown.join(", ")
        )
    });
    (map, kept, warning)
}

/// Renumber elements through the vertex map.
pub(crate) fn renumber<const K: usize>(
    elements: Vec<[usize; K]>,
    map: &[Option<usize>],
) -> Vec<[usize; K]> {
    elements
        .into_iter()
        .map(|el| el.map(|v| map[v].unwrap_or(usize::MAX)))
        .collect()
}
