//! A vertex separator of the matrix graph for the two-way split
//! factorisation ([`super::split`]).
//!
//! Works on the vertex (supervariable) graph of the pattern only: the linear
//! system knows no coordinates. A disconnected graph is split between its
//! components (empty separator). A connected one is cut along a level of the
//! breadth-first level structure rooted at a pseudo-peripheral vertex
//! (George–Liu): every edge joins two vertices of the same or of adjacent
//! levels, so level m separates the levels < m from the levels > m. The
//! level is the one where the cumulative weight crosses the requested
//! fraction, and it is trimmed: a level-m vertex with no neighbour in a
//! level > m joins the first part (it then touches no vertex of the second).

use std::collections::VecDeque;

use crate::linear::ordering::Supervariables;

/// Which part of the bisection a vertex belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Part {
    /// First part, P₁.
    First,
    /// Second part, P₂.
    Second,
    /// The separator S: no edge joins P₁ and P₂.
    Separator,
}

/// Breadth-first levels from `root` over the vertices of its component:
/// `level[v]` (`usize::MAX` if unreached) and the vertices in visiting order.
fn levels(sv: &Supervariables, root: usize) -> (Vec<usize>, Vec<usize>) {
    let mut level = vec![usize::MAX; sv.len()];
    let mut order = Vec::new();
    let mut queue = VecDeque::from([root]);
    level[root] = 0;
    while let Some(v) = queue.pop_front() {
        order.push(v);
        for &w in &sv.adj[sv.adj_ptr[v]..sv.adj_ptr[v + 1]] {
            if level[w] == usize::MAX {
                level[w] = level[v] + 1;
                queue.push_back(w);
            }
        }
    }
    (level, order)
}

/// A pseudo-peripheral vertex of the component of `start`: repeatedly root at
/// a minimum-degree vertex of the deepest level while the depth grows.
fn pseudo_peripheral(sv: &Supervariables, start: usize) -> usize {
    let degree = |v: usize| sv.adj_ptr[v + 1] - sv.adj_ptr[v];
    let mut root = start;
    let (mut level, mut order) = levels(sv, root);
    for _ in 0..8 {
        let depth = level[*order.last().expect("root is visited")];
        let candidate = order
            .iter()
            .copied()
            .filter(|&v| level[v] == depth)
            .min_by_key(|&v| (degree(v), v))
            .expect("the deepest level is not empty");
        let (l2, o2) = levels(sv, candidate);
        if l2[*o2.last().expect("root is visited")] <= depth {
            break;
        }
        (root, level, order) = (candidate, l2, o2);
    }
    root
}

/// Split the components between the two parts, heaviest first onto the
/// lighter part; `None` for a connected graph.
fn by_components(sv: &Supervariables, weight: &[f64]) -> Option<Vec<Part>> {
    let mut comp = vec![usize::MAX; sv.len()];
    let mut comps: Vec<(f64, usize)> = Vec::new();
    for v in 0..sv.len() {
        if comp[v] == usize::MAX {
            let (level, order) = levels(sv, v);
            let id = comps.len();
            order.iter().for_each(|&w| comp[w] = id);
            comps.push((order.iter().map(|&w| weight[w]).sum(), id));
            debug_assert!(level[v] == 0);
        }
    }
    if comps.len() < 2 {
        return None;
    }
    comps.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut side = vec![Part::First; comps.len()];
    let (mut w1, mut w2) = (0.0, 0.0);
    for &(w, id) in &comps {
        if w1 <= w2 {
            w1 += w;
        } else {
            side[id] = Part::Second;
            w2 += w;
        }
    }
    Some(comp.into_iter().map(|c| side[c]).collect())
}

/// Bisect the vertex graph so that about `fraction` of the total `weight`
/// precedes the separator. `None` when the graph has fewer than 3 levels
/// (no level has vertices on both sides) or fewer than 2 vertices.
pub(crate) fn bisect(sv: &Supervariables, weight: &[f64], fraction: f64) -> Option<Vec<Part>> {
    if sv.len() < 2 {
        return None;
    }
    if let Some(parts) = by_components(sv, weight) {
        return Some(parts);
    }
    let (level, order) = levels(sv, pseudo_peripheral(sv, 0));
    let depth = level[*order.last()?];
    if depth < 2 {
        return None;
    }
    let mut per_level = vec![0.0; depth + 1];
    for v in 0..sv.len() {
        per_level[level[v]] += weight[v];
    }
    let target = fraction * per_level.iter().sum::<f64>();
    // smallest m in 1..depth with weight(levels ≤ m) ≥ target
    let mut upto = per_level[0] + per_level[1];
    let mut m = 1;
    while m < depth - 1 && upto < target {
        m += 1;
        upto += per_level[m];
    }
    let touches_beyond = |v: usize| {
        sv.adj[sv.adj_ptr[v]..sv.adj_ptr[v + 1]]
            .iter()
            .any(|&w| level[w] > m)
    };
    Some(
        (0..sv.len())
            .map(|v| match level[v].cmp(&m) {
                std::cmp::Ordering::Less => Part::First,
                std::cmp::Ordering::Greater => Part::Second,
                std::cmp::Ordering::Equal if touches_beyond(v) => Part::Separator,
                std::cmp::Ordering::Equal => Part::First,
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::ordering::tests::grid;

    /// No edge of the vertex graph joins the two parts, and both are used.
    fn check(sv: &Supervariables, parts: &[Part]) {
        for v in 0..sv.len() {
            for &w in &sv.adj[sv.adj_ptr[v]..sv.adj_ptr[v + 1]] {
                let pair = (parts[v], parts[w]);
                assert!(
                    pair != (Part::First, Part::Second) && pair != (Part::Second, Part::First),
                    "edge {v}-{w} crosses the separator"
                );
            }
        }
        assert!(parts.contains(&Part::First) && parts.contains(&Part::Second));
    }

    #[test]
    fn a_grid_is_cut_by_a_short_balanced_separator() {
        let sv = Supervariables::of(&grid(30, 20, 2));
        let w = vec![2.0; sv.len()];
        let parts = bisect(&sv, &w, 0.5).unwrap();
        check(&sv, &parts);
        let count = |p| parts.iter().filter(|&&q| q == p).count();
        let (a, b, s) = (
            count(Part::First),
            count(Part::Second),
            count(Part::Separator),
        );
        assert!(s <= 2 * 31, "separator of {s} vertices");
        assert!(a.abs_diff(b) < sv.len() / 5, "unbalanced: {a} vs {b}");
        let early = bisect(&sv, &w, 0.25).unwrap();
        check(&sv, &early);
        let first = early.iter().filter(|&&q| q == Part::First).count();
        assert!(
            first < a,
            "a smaller fraction moves the cut: {first} vs {a}"
        );
    }

    #[test]
    fn disconnected_halves_have_an_empty_separator() {
        let (p, _) = crate::linear::cholesky::split::tests::two_grids(6, 5, 2);
        let sv = Supervariables::of(&p);
        let parts = bisect(&sv, &vec![1.0; sv.len()], 0.5).unwrap();
        check(&sv, &parts);
        assert!(!parts.contains(&Part::Separator));
    }

    #[test]
    fn too_small_graphs_are_not_split() {
        let (p, _) = crate::linear::cholesky::split::tests::triangle();
        let sv = Supervariables::of(&p);
        assert!(bisect(&sv, &vec![1.0; sv.len()], 0.5).is_none());
    }
}
