//! Checks shared by triangle and tet validation.

use crate::error::ValidationError;
use crate::geometry::{norm, sub};
use crate::topology::sort_by_vertex;
use crate::types::DEGENERATE_REL_TOL;

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
    check_finite_where(positions, |v| used.get(v).copied().unwrap_or(false))
}

/// Finite coordinates for every vertex (writers, the Tutte embedding).
pub(crate) fn check_all_finite(positions: &[[f64; 3]]) -> Result<(), ValidationError> {
    check_finite_where(positions, |_| true)
}

/// The first vertex `v` with `checked(v)` and a non-finite coordinate.
fn check_finite_where(
    positions: &[[f64; 3]],
    checked: impl Fn(usize) -> bool,
) -> Result<(), ValidationError> {
    for (vertex, p) in positions.iter().enumerate() {
        if checked(vertex) && p.iter().any(|c| !c.is_finite()) {
            return Err(ValidationError::NonFiniteCoordinate {
                vertex,
                position: *p,
            });
        }
    }
    Ok(())
}

/// Longest edge of the element `el`.
pub(crate) fn longest_edge<const K: usize>(positions: &[[f64; 3]], el: &[usize; K]) -> f64 {
    let mut l = 0.0f64;
    for i in 0..K {
        for j in i + 1..K {
            l = l.max(norm(sub(positions[el[i]], positions[el[j]])));
        }
    }
    l
}

/// How the rest measures of one mesh are judged (see [`super`]).
pub(crate) struct MeasureRule {
    /// 2 for triangles, 3 for tets.
    pub dimension: usize,
    /// Measure = det Dm / `den` (2 for triangles, 6 for tets).
    pub den: f64,
    /// Signed measures (planar triangles, tets): negative is inverted.
    pub signed: bool,
    /// Refuse quality below this (0: only degenerate elements).
    pub min_quality: f64,
    /// Warn about quality below this.
    pub sliver_quality: f64,
}

/// Elements below a quality threshold: (count, first ids, worst (id, q)).
#[derive(Default)]
struct Below {
    count: usize,
    first: Vec<usize>,
    worst: Option<(usize, f64)>,
}

impl Below {
    fn add(&mut self, e: usize, q: f64) {
        self.count += 1;
        if self.first.len() < 10 {
            self.first.push(e);
        }
        if self.worst.is_none_or(|(_, w)| q < w) {
            self.worst = Some((e, q));
        }
    }
}

/// Check rest measures `(m, L)` (measure, longest edge) per element, each
/// against its own edges (scale-invariant, the element library's rule):
/// degenerate if `m` or `L` is not finite or `|m|·den ≤ 1e-12·L^d` (first
/// one reported); inverted if `signed` and `m < 0` (first one and the
/// count); quality `q = |m| / L^d` below `min_quality` refused, below
/// `sliver_quality` a warning naming the elements.
pub(crate) fn check_measures(
    measures: impl Iterator<Item = (f64, f64)>,
    rule: &MeasureRule,
    warnings: &mut Vec<String>,
) -> Result<(), ValidationError> {
    let mut first_inverted: Option<(usize, f64)> = None;
    let (mut count, mut total) = (0, 0);
    let (mut refused, mut slivers) = (Below::default(), Below::default());
    let d = rule.dimension as i32;
    for (e, (m, l)) in measures.enumerate() {
        total += 1;
        let scale = l.powi(d);
        let tolerance = DEGENERATE_REL_TOL * scale / rule.den;
        if !m.is_finite() || !scale.is_finite() || m.abs() <= tolerance {
            return Err(ValidationError::DegenerateElement {
                element: e,
                measure: m,
                tolerance,
                dimension: rule.dimension,
            });
        }
        if rule.signed && m < 0.0 {
            count += 1;
            first_inverted.get_or_insert((e, m));
        }
        let q = m.abs() / scale;
        if q < rule.min_quality {
            refused.add(e, q);
        } else if q < rule.sliver_quality {
            slivers.add(e, q);
        }
    }
    if let Some((element, measure)) = first_inverted {
        return Err(ValidationError::InvertedElement {
            element,
            measure,
            count,
            total,
            dimension: rule.dimension,
        });
    }
    if let Some((worst, quality)) = refused.worst {
        return Err(ValidationError::LowQualityElements {
            count: refused.count,
            total,
            first: refused.first,
            worst,
            quality,
            min_quality: rule.min_quality,
            dimension: rule.dimension,
        });
    }
    if let Some((worst, q)) = slivers.worst {
        warnings.push(sliver_warning(&slivers, worst, q, rule));
    }
    Ok(())
}

fn sliver_warning(s: &Below, worst: usize, q: f64, rule: &MeasureRule) -> String {
    let ids: Vec<String> = s.first.iter().map(|v| v.to_string()).collect();
    let more = if s.count > s.first.len() { ", …" } else { "" };
    let (what, power) = if rule.dimension == 2 {
        ("area", "²")
    } else {
        ("volume", "³")
    };
    format!(
        "{} sliver element{} (rest {what} ÷ longest edge{power} below {:e}): {}{more}; \
         the worst is element {worst} ({q:e}); they are kept (set a minimum quality to refuse them)",
        s.count,
        if s.count == 1 { "" } else { "s" },
        rule.sliver_quality,
        ids.join(", "),
    )
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
