//! The vertex separator of the split factorisation ([`super::split`]), read
//! off a supernodal elimination tree of A ([`Tree`]): that of the group
//! graph when the ordering is by groups (vertex blocks: [`Tree::of_groups`],
//! from faer's elimination tree and column counts, no symbolic
//! factorisation of A), else that of faer's plain symbolic analysis
//! ([`Tree::of_supernodal`]).
//!
//! In the factor L of A (fill-reducing order, supernodal), the rows of a
//! supernode's columns are its own columns and those of its ancestors, so
//! A[i, j] ≠ 0 only for i, j in the same supernode or in an
//! ancestor–descendant pair. Take a set S of supernodes closed under
//! "parent of": removing S leaves a forest of subtrees, two distinct
//! subtrees are never coupled in A, and any grouping of the subtrees into
//! P₁ and P₂ makes S a vertex separator. Each subtree keeps its columns'
//! structure in the half Bᵢ = A[Pᵢ∪S] (its columns' rows lie in the
//! subtree and in S), so the halves cost exactly their share of the plain
//! factorisation's flops, plus the separator's dense block: no ordering is
//! lost by splitting.
//!
//! S grows from the roots: repeatedly the heaviest subtree of the forest
//! moves its root supernode into S (its children become subtrees), and the
//! forest is split between the two halves by longest-processing-time
//! greedy on subtree flops, until the heaviest subtree is below a quarter of
//! the total. The S with the least estimated critical path,
//! max(flops of a half's subtrees) + k³/3, is kept (k separator unknowns:
//! the halves' subtree flops already include their updates of S, and the
//! only extra work is the dense L_Σ, Σ_{j<k} (k − j)² ≈ k³/3 in the same
//! Σ c² measure).
//!
//! The split is used (unless forced) only when that critical path is at
//! most [`MAX_CRITICAL_RATIO`] of the plain factorisation's flops: the
//! decision depends on the symbolic analysis alone, so it is the same run
//! to run, and a split is only made when two threads have a margin to be
//! faster than one (docs/benchmarks/threads.md).

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

use crate::linear::ordering::GroupElimination;

/// Weight of k³ in the estimated critical path (see the module docs).
const DENSE_WEIGHT: f64 = 1.0 / 3.0;

/// A split is made when its estimated critical path is at most this
/// fraction of the plain factorisation's flops (an estimated speed-up of
/// at least 1/0.9 ≈ 1.11 on two threads). The estimate is pessimistic: the
/// halves' left-looking kernel is itself faster than faer's plain
/// factorisation on these matrices, and on a quiet machine hand.mesh's
/// scene matrices (estimate 0.81) factorised 1.5× faster split than on one
/// thread, camelhead and armadillo_cut_low (0.67, 0.70) 1.7× and 1.9×
/// (docs/benchmarks/threads.md).
pub(crate) const MAX_CRITICAL_RATIO: f64 = 0.9;

/// At most this many supernodes move into S (each step is O(forest)).
const MAX_STEPS: usize = 256;

/// Which part of the bisection a supernode belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Part {
    /// First half, P₁.
    First,
    /// Second half, P₂.
    Second,
    /// The separator S.
    Separator,
}

/// An elimination tree of supernodes, read by [`split`]: node `k` holds the
/// columns `begin[k]..end[k]` of the fill-reducing order, costs `flops[k]`
/// (Σ c² over its columns) and has the parent `parent[k] > k`
/// (`usize::MAX` for a root), so ascending `k` is bottom-up.
pub(crate) struct Tree {
    pub parent: Vec<usize>,
    pub flops: Vec<f64>,
    pub begin: Vec<usize>,
    pub end: Vec<usize>,
}

impl Tree {
    /// The supernodes of faer's plain symbolic analysis.
    pub(crate) fn of_supernodal(s: &SymbolicSupernodalCholesky<usize>) -> Tree {
        let n = s.n_supernodes();
        let (begin, end) = (s.supernode_begin(), s.supernode_end());
        let parent = (0..n)
            .map(|k| match s.supernode(k).pattern().iter().min() {
                Some(&row) => end.partition_point(|&e| e <= row),
                None => usize::MAX,
            })
            .collect();
        let flops = (0..n)
            .map(|k| column_flops(end[k] - begin[k], s.supernode(k).pattern().len()))
            .collect();
        Tree {
            parent,
            flops,
            begin: begin[..n].to_vec(),
            end: end[..n].to_vec(),
        }
    }

    /// The tree of the scalar factor from the elimination tree `etree`
    /// (`-1` for a root) and column counts `counts` (diagonal included) of
    /// the *group* graph in the fill-reducing order, group `j` holding
    /// `sizes[j]` consecutive unknowns ([`GroupElimination`]): no symbolic
    /// factorisation of the scalar matrix. Group `j`'s unknowns form a
    /// dense diagonal block whose columns have `sizes[j]·counts[j] − i`
    /// entries (i = 0, 1, …; exact when all groups have one size, as the
    /// vertex blocks of a mesh do),
    /// and a group joins the next one's node when that is its parent and
    /// its only child (a chain gains nothing from being split column by
    /// column: [`split`] would only walk down it).
    pub(crate) fn of_groups(groups: &GroupElimination) -> Tree {
        let (etree, counts, sizes) = (&groups.etree, &groups.counts, &groups.sizes);
        let ng = etree.len();
        let mut children = vec![0u32; ng];
        for &p in etree {
            if p >= 0 {
                children[p as usize] += 1;
            }
        }
        let mut tree = Tree {
            parent: Vec::new(),
            flops: Vec::new(),
            begin: Vec::new(),
            end: Vec::new(),
        };
        // node of each group
        let mut node = vec![0usize; ng];
        let mut col = 0;
        for j in 0..ng {
            let chained = j > 0 && etree[j - 1] == j as isize && children[j] == 1;
            if !chained {
                tree.begin.push(col);
                tree.end.push(col);
                tree.flops.push(0.0);
            }
            let k = tree.begin.len() - 1;
            node[j] = k;
            let b = sizes[j];
            tree.flops[k] += column_flops(b, b * (counts[j] - 1));
            col += b;
            tree.end[k] = col;
        }
        // a node's parent: the node of its last group's parent
        tree.parent = vec![usize::MAX; tree.begin.len()];
        for j in 0..ng {
            if etree[j] >= 0 && node[etree[j] as usize] != node[j] {
                tree.parent[node[j]] = node[etree[j] as usize];
            }
        }
        tree
    }

    fn len(&self) -> usize {
        self.parent.len()
    }

    /// Σ c² over all columns: the plain factorisation's flops.
    pub(crate) fn total_flops(&self) -> f64 {
        self.flops.iter().sum()
    }
}

/// Σ c² over the `w` columns of a dense diagonal block with `r` rows
/// below it: column i has c = w − i + r entries.
fn column_flops(w: usize, r: usize) -> f64 {
    (0..w).map(|c| ((w - c + r) as f64).powi(2)).sum()
}

/// Longest-processing-time split of `forest` (subtree roots) by `weight`:
/// the bin of each root and the two bin totals.
fn two_bins(forest: &[usize], weight: &[f64]) -> (Vec<(usize, Part)>, [f64; 2]) {
    let mut sorted = forest.to_vec();
    sorted.sort_by(|&a, &b| weight[b].total_cmp(&weight[a]).then(a.cmp(&b)));
    let mut bins = [0.0, 0.0];
    let assigned = sorted
        .into_iter()
        .map(|r| {
            let i = usize::from(bins[1] < bins[0]);
            bins[i] += weight[r];
            (r, if i == 0 { Part::First } else { Part::Second })
        })
        .collect();
    (assigned, bins)
}

/// The part of each supernode in the split of the supernodal tree with the
/// least estimated critical path, or `None` when one half would be empty or
/// (unless `force`) its critical path is above [`MAX_CRITICAL_RATIO`] of the
/// plain factorisation's flops.
pub(crate) fn split(tree: &Tree, force: bool) -> Option<Vec<Part>> {
    let n = tree.len();
    let parent = &tree.parent;
    let mut subtree = tree.flops.clone();
    let mut children = vec![Vec::new(); n];
    for k in 0..n {
        // a parent's columns follow its children's: ascending k is bottom-up
        if parent[k] != usize::MAX {
            subtree[parent[k]] += subtree[k];
            children[parent[k]].push(k);
        }
    }
    let total: f64 = (0..n)
        .filter(|&k| parent[k] == usize::MAX)
        .map(|k| subtree[k])
        .sum();
    let mut forest: Vec<usize> = (0..n).filter(|&k| parent[k] == usize::MAX).collect();
    let mut separator: Vec<usize> = Vec::new();
    let mut k_cols = 0usize;
    // (critical path, separator supernodes, forest roots with their half)
    type Candidate = (f64, Vec<usize>, Vec<(usize, Part)>);
    let mut best: Option<Candidate> = None;
    for _ in 0..MAX_STEPS {
        let (assigned, bins) = two_bins(&forest, &subtree);
        if bins[0] > 0.0 && bins[1] > 0.0 {
            let cost = bins[0].max(bins[1]) + DENSE_WEIGHT * (k_cols as f64).powi(3);
            if best.as_ref().is_none_or(|b| cost < b.0) {
                best = Some((cost, separator.clone(), assigned));
            }
        }
        let Some((at, &heaviest)) = forest
            .iter()
            .enumerate()
            .max_by(|a, b| subtree[*a.1].total_cmp(&subtree[*b.1]))
        else {
            break;
        };
        if subtree[heaviest] < 0.25 * total {
            break;
        }
        forest.swap_remove(at);
        forest.extend_from_slice(&children[heaviest]);
        separator.push(heaviest);
        k_cols += tree.end[heaviest] - tree.begin[heaviest];
    }
    let (critical, separator, assigned) = best?;
    if critical > MAX_CRITICAL_RATIO * total && !force {
        return None;
    }
    let mut parts = vec![Part::First; n];
    let mut fixed = vec![false; n];
    for &k in &separator {
        (parts[k], fixed[k]) = (Part::Separator, true);
    }
    for &(k, p) in &assigned {
        (parts[k], fixed[k]) = (p, true);
    }
    // top-down: a supernode below a forest root inherits the root's half
    for k in (0..n).rev() {
        if !fixed[k] {
            parts[k] = parts[parent[k]];
        }
    }
    Some(parts)
}
