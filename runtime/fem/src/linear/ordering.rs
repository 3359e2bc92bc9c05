//! Fill-reducing orderings for the sparse Cholesky factor.
//!
//! The Newton matrix of a mesh problem has d×d blocks: the unknowns of one
//! vertex share their sparsity structure (same neighbours, fully coupled to
//! each other). `Supervariables` detects such groups (consecutive unknowns
//! whose closed neighbourhoods are equal), so the orderings work on the
//! vertex graph (d² times fewer edges) and expand each vertex back to its
//! unknowns, keeping the unknowns of a vertex adjacent in the factor (one
//! supernode column block per vertex at least).
//!
//! * [`FillOrdering::Amd`]: faer's approximate minimum degree on the full
//!   unknown graph.
//! * [`FillOrdering::BlockAmd`]: the same AMD on the vertex graph, expanded
//!   (what [`FillOrdering::Auto`], the default, picks in 3D and below
//!   [`METIS_MIN_UNKNOWNS`] unless METIS's factor is much cheaper).
//! * [`FillOrdering::Metis`]: METIS nested dissection (`METIS_NodeND`) on the
//!   vertex graph, vertex weights = unknowns per vertex; needs the `metis`
//!   cargo feature (METIS is compiled from source by cargo, a C compiler is
//!   all it needs). Without the feature, asking for it is a clear error.
//! * [`FillOrdering::Geometric`]: geometric nested dissection of the vertex
//!   graph from the vertices' positions ([`ecc_mesh::dissection`], the
//!   ordering of the Tutte solve); needs [`Coordinates`] (e.g.
//!   `NewtonSolver::with_geometry`), asking for it without is a clear error.
//!   [`FillOrdering::Auto`] takes it instead of METIS where the positions are
//!   known and the mesh is flat enough ([`GEOMETRIC_MAX_CONSTANT`]).
//!
//! All orderings produce `perm` with `perm[new] = old` (faer's and METIS's
//! convention: the factored matrix is A(perm, perm)).

use std::borrow::Cow;
use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::simplicial;
use serde::{Deserialize, Serialize};

use crate::error::FemError;
use crate::pattern::Pattern;

/// Which fill-reducing ordering the symbolic analysis uses.
///
/// The names (`"amd"`, `"block-amd"`, `"metis"`, `"geometric"`, `"auto"`)
/// are stable: scene keys and the benchmark report select orderings by them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FillOrdering {
    /// Approximate minimum degree on the unknown graph (faer's own).
    Amd,
    /// Approximate minimum degree on the vertex (supervariable) graph.
    BlockAmd,
    /// METIS nested dissection on the vertex graph (feature `metis`, on by
    /// default).
    Metis,
    /// Geometric nested dissection of the vertex graph from the vertex
    /// positions (needs [`Coordinates`]).
    Geometric,
    /// By size ([`FillOrdering::auto_choice`]) and cost: METIS for 2D
    /// systems of at least [`METIS_MIN_UNKNOWNS`] unknowns when compiled in
    /// — or there the geometric dissection when positions are known and its
    /// factor costs at most [`GEOMETRIC_MAX_CONSTANT`]·g^1.5 (g vertices: a
    /// flat mesh) —; for 2D systems of [`METIS_PROBE_UNKNOWNS`] unknowns, METIS
    /// when its factor costs at most [`METIS_MAX_RATIO`] × block AMD's (both
    /// computed, where block AMD's looks poor:
    /// [`METIS_PROBE_MIN_CONSTANT`]); block AMD otherwise.
    Auto,
}

impl Default for FillOrdering {
    /// [`FillOrdering::Auto`] (docs/benchmarks/ordering.md, "METIS by size").
    fn default() -> Self {
        FillOrdering::Auto
    }
}

/// Smallest 2D system (unknowns) that [`FillOrdering::Auto`] orders with
/// METIS. Measured with the split two-thread factorisation (2026-12-02,
/// bumpy disks, `ecc-fem` example `ordering --split`): METIS's analysis
/// costs 0.24 / 0.79 / 2.4 s more than block AMD's at 136k / 377k / 1.0M
/// unknowns and saves 18 / 81 / 370 ms per factorisation (0.108 → 0.090,
/// 0.408 → 0.327, 1.55 → 1.18 s), so it pays after 13 / 10 / 7
/// factorisations; these parameterisations converge in 8–9 Newton steps.
/// Below (camelhead, armadillo_cut_low) and in 3D (hand.mesh) block AMD is
/// as fast or faster per solve.
pub const METIS_MIN_UNKNOWNS: usize = 500_000;

impl FillOrdering {
    /// Every concrete ordering, compiled in or not (not [`FillOrdering::Auto`]).
    pub const ALL: [FillOrdering; 4] = [
        FillOrdering::Amd,
        FillOrdering::BlockAmd,
        FillOrdering::Metis,
        FillOrdering::Geometric,
    ];

    /// The stable name.
    pub fn name(self) -> &'static str {
        match self {
            FillOrdering::Amd => "amd",
            FillOrdering::BlockAmd => "block-amd",
            FillOrdering::Metis => "metis",
            FillOrdering::Geometric => "geometric",
            FillOrdering::Auto => "auto",
        }
    }

    /// The ordering with this stable name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .chain([FillOrdering::Auto])
            .find(|o| o.name() == name)
    }

    /// Whether this build can compute the ordering.
    pub fn is_available(self) -> bool {
        !matches!(self, FillOrdering::Metis) || cfg!(feature = "metis")
    }

    /// Whether the ordering needs the position of every unknown
    /// ([`Coordinates`]).
    pub fn needs_positions(self) -> bool {
        self == FillOrdering::Geometric
    }

    /// An error when this ordering cannot be computed here: not compiled
    /// in, or it needs a position per unknown and `positioned` is false.
    pub(crate) fn check_usable(self, positioned: bool) -> Result<(), FemError> {
        if !self.is_available() {
            Err(missing_feature(self))
        } else if self.needs_positions() && !positioned {
            Err(missing_positions())
        } else {
            Ok(())
        }
    }

    /// What [`FillOrdering::Auto`] uses for `n` unknowns in `groups`
    /// vertex groups (supervariables): METIS when it is compiled in, the
    /// system is 2D (fewer than 2.5 unknowns per group) and
    /// n ≥ [`METIS_MIN_UNKNOWNS`]; block AMD otherwise. Where this says
    /// METIS and the unknowns have positions, `Auto` takes the geometric
    /// dissection instead on a flat mesh ([`GEOMETRIC_MAX_CONSTANT`]); where it
    /// says block AMD for a 2D system of [`METIS_PROBE_UNKNOWNS`] unknowns,
    /// `Auto` takes METIS instead when its factor is much cheaper
    /// ([`METIS_MAX_RATIO`]).
    pub fn auto_choice(n: usize, groups: usize) -> FillOrdering {
        if FillOrdering::Metis.is_available() && two_d(n, groups) && n >= METIS_MIN_UNKNOWNS {
            FillOrdering::Metis
        } else {
            FillOrdering::BlockAmd
        }
    }
}

/// Where the unknowns are, for [`FillOrdering::Geometric`]: the position
/// of every unknown (its vertex's) and, when one was computed already, a
/// nested dissection of the vertices at these positions. Shared, so
/// analyses and re-analyses copy nothing.
#[derive(Clone, Debug)]
pub struct Coordinates {
    /// The position of every unknown.
    pub at: Arc<[[f64; 3]]>,
    /// The first unknown of every vertex in the order of a nested dissection
    /// of the vertex graph at these positions, computed elsewhere (the
    /// parameterisation shares `ecc_mesh::dissection::mesh_dissection` with
    /// its Tutte start). The geometric ordering takes it as its group order
    /// when it names every group exactly once by the group's first unknown
    /// (the groups are the vertices); otherwise the groups are dissected
    /// here. Only the fill depends on it, never the solution.
    pub dissection: Option<Arc<[usize]>>,
}

impl FromIterator<[f64; 3]> for Coordinates {
    fn from_iter<I: IntoIterator<Item = [f64; 3]>>(at: I) -> Self {
        at.into_iter().collect::<Vec<_>>().into()
    }
}

impl From<Vec<[f64; 3]>> for Coordinates {
    fn from(at: Vec<[f64; 3]>) -> Self {
        Coordinates {
            at: at.into(),
            dissection: None,
        }
    }
}

/// Groups of consecutive unknowns with equal closed neighbourhoods, and the
/// graph between groups (full adjacency, no self loops, CSR).
pub(crate) struct Supervariables {
    /// `start[g]..start[g + 1]` are the unknowns of group `g`.
    pub start: Vec<usize>,
    /// CSR row pointers of the group graph.
    pub adj_ptr: Vec<usize>,
    /// CSR neighbours of the group graph (sorted per group).
    pub adj: Vec<usize>,
}

/// Full symmetric adjacency of the upper-triangular `pattern`, each list
/// sorted, diagonal excluded.
fn full_adjacency(pattern: &Pattern) -> (Vec<usize>, Vec<usize>) {
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    crate::pattern::symmetric_graph(pattern.n(), |j| ri[cp[j]..cp[j + 1]].iter().copied())
}

/// Whether the closed neighbourhoods of `a` and `a + 1` are equal:
/// N(a) ∪ {a} = N(a+1) ∪ {a+1}, both lists sorted.
fn same_closed(adj: &[usize], ptr: &[usize], a: usize) -> bool {
    let (na, nb) = (&adj[ptr[a]..ptr[a + 1]], &adj[ptr[a + 1]..ptr[a + 2]]);
    if na.len() != nb.len() || na.binary_search(&(a + 1)).is_err() {
        return false;
    }
    let sa = na.iter().filter(|&&v| v != a + 1);
    let sb = nb.iter().filter(|&&v| v != a);
    sa.eq(sb)
}

impl Supervariables {
    /// The groups of `pattern` and their graph: consecutive vertex blocks
    /// ([`Pattern::vertex_blocks`], or single unknowns for a pattern not
    /// built from stencils) with the same closed neighbourhood merged.
    pub fn of(pattern: &Pattern) -> Self {
        match pattern.vertex_blocks() {
            Some(b) => Self::merged(&b.start, &b.adj_ptr, &b.adj),
            None => {
                let (ptr, adj) = full_adjacency(pattern);
                let singles: Vec<usize> = (0..=pattern.n()).collect();
                Self::merged(&singles, &ptr, &adj)
            }
        }
    }

    /// Merge runs of consecutive blocks (`block[b]..block[b + 1]`, graph
    /// `ptr`/`adj`: sorted, no self loops) with the same closed
    /// neighbourhood into groups, and build the group graph.
    fn merged(block: &[usize], ptr: &[usize], adj: &[usize]) -> Self {
        let nb = block.len() - 1;
        let mut start = vec![0usize];
        let mut group = vec![0usize; nb];
        for (b, gb) in group.iter_mut().enumerate() {
            if b > 0 && !same_closed(adj, ptr, b - 1) {
                start.push(b);
            }
            *gb = start.len() - 1;
        }
        start.push(nb);
        let ng = start.len() - 1;
        let mut adj_ptr = vec![0usize; ng + 1];
        let mut gadj = Vec::with_capacity(adj.len());
        for g in 0..ng {
            let first = start[g];
            // all members share the closed neighbourhood: read the first's;
            // sorted blocks map to sorted groups, so a repeat is the last
            let at = gadj.len();
            for h in adj[ptr[first]..ptr[first + 1]].iter().map(|&i| group[i]) {
                if h != g && gadj[at..].last() != Some(&h) {
                    gadj.push(h);
                }
            }
            adj_ptr[g + 1] = gadj.len();
        }
        Supervariables {
            start: start.iter().map(|&b| block[b]).collect(),
            adj_ptr,
            adj: gadj,
        }
    }

    /// Number of groups.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Expand a group permutation (`gperm[new] = old group`) to unknowns.
    pub fn expand(&self, gperm: &[usize]) -> Vec<usize> {
        gperm
            .iter()
            .flat_map(|&g| self.start[g]..self.start[g + 1])
            .collect()
    }

    /// Upper-triangular pattern (with diagonal, rows sorted) of the group
    /// graph in the order `gperm` (`gperm[new] = old group`), CSC.
    fn upper(&self, gperm: &[usize]) -> (Vec<usize>, Vec<usize>) {
        let mut inv = vec![0usize; self.len()];
        gperm.iter().enumerate().for_each(|(new, &g)| inv[g] = new);
        let mut cp = Vec::with_capacity(self.len() + 1);
        cp.push(0);
        let mut ri = Vec::with_capacity(self.adj.len() / 2 + self.len());
        for (j, &g) in gperm.iter().enumerate() {
            let start = ri.len();
            let nb = &self.adj[self.adj_ptr[g]..self.adj_ptr[g + 1]];
            ri.extend(nb.iter().map(|&h| inv[h]).filter(|&i| i < j));
            ri.push(j);
            ri[start..].sort_unstable();
            cp.push(ri.len());
        }
        (cp, ri)
    }
}

/// faer's AMD on the group graph: the group permutation of
/// [`FillOrdering::BlockAmd`].
fn amd_order(sv: &Supervariables) -> Result<Vec<usize>, FemError> {
    let n = sv.len();
    let (cp, ri) = sv.upper(&(0..n).collect::<Vec<_>>());
    let a = SymbolicSparseColMatRef::new_checked(n, n, &cp, None, &ri);
    let mut perm = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let mut mem = MemBuffer::try_new(amd::order_scratch::<usize>(n, ri.len()))
        .map_err(|_| FemError::Symbolic("out of memory for the AMD ordering".into()))?;
    amd::order(
        &mut perm,
        &mut inv,
        a,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| FemError::Symbolic(format!("AMD ordering: {e:?}")))?;
    Ok(perm)
}

/// The fill-reducing permutation (`perm[new] = old`) of `pattern` by
/// `ordering`, or `None` for [`FillOrdering::Amd`] (faer computes it inside
/// the symbolic analysis), and the concrete ordering used
/// ([`FillOrdering::Auto`] resolved). `coords` (one per unknown) is needed by
/// [`FillOrdering::Geometric`] only.
#[cfg(test)]
pub(crate) fn permutation(
    pattern: &Pattern,
    ordering: FillOrdering,
    coords: Option<&Coordinates>,
) -> Result<(Option<Vec<usize>>, FillOrdering), FemError> {
    let o = ordered(pattern, ordering, coords)?;
    Ok((o.perm, o.used))
}

/// A fill-reducing ordering of a pattern ([`ordered`]).
pub(crate) struct Ordered {
    /// `perm[new] = old`, or `None` for [`FillOrdering::Amd`] (computed
    /// inside faer's symbolic analysis).
    pub perm: Option<Vec<usize>>,
    /// The concrete ordering used ([`FillOrdering::Auto`] resolved).
    pub used: FillOrdering,
    /// The groups and their order `perm` expands (every ordering but
    /// [`FillOrdering::Amd`]).
    pub groups: Option<GroupOrder>,
}

/// Supervariables in a fill-reducing order: what the split factor's tree is
/// read from without a symbolic factorisation of the scalar matrix.
pub(crate) struct GroupOrder {
    sv: Supervariables,
    /// `gperm[new] = old group`.
    gperm: Vec<usize>,
    /// The group graph's elimination in this order where choosing the
    /// order computed it.
    elimination: Option<GroupElimination>,
}

impl GroupOrder {
    /// The elimination of the group graph in this order (the one choosing
    /// the order computed, else computed here).
    pub(crate) fn elimination(&self) -> Result<Cow<'_, GroupElimination>, FemError> {
        Ok(match &self.elimination {
            Some(e) => Cow::Borrowed(e),
            None => Cow::Owned(group_elimination(&self.sv, &self.gperm)?),
        })
    }
}

/// The Cholesky factor of the group graph in a group order, all indexed by
/// new position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct GroupElimination {
    /// Elimination tree (`-1` for a root).
    pub etree: Vec<isize>,
    /// Column counts, diagonal included.
    pub counts: Vec<usize>,
    /// Unknowns of each group.
    pub sizes: Vec<usize>,
}

/// [`permutation`] with the groups it expands.
pub(crate) fn ordered(
    pattern: &Pattern,
    ordering: FillOrdering,
    coords: Option<&Coordinates>,
) -> Result<Ordered, FemError> {
    if ordering == FillOrdering::Amd {
        return Ok(Ordered {
            perm: None,
            used: ordering,
            groups: None,
        });
    }
    let sv = Supervariables::of(pattern);
    let (gperm, used, elimination) = group_permutation(&sv, pattern.n(), ordering, coords)?;
    Ok(Ordered {
        perm: Some(sv.expand(&gperm)),
        used,
        groups: Some(GroupOrder {
            sv,
            gperm,
            elimination,
        }),
    })
}

/// The group permutation of [`ordered`] (any ordering but
/// [`FillOrdering::Amd`]) and the concrete ordering used.
fn group_permutation(
    sv: &Supervariables,
    n: usize,
    ordering: FillOrdering,
    coords: Option<&Coordinates>,
) -> Result<(Vec<usize>, FillOrdering, Option<GroupElimination>), FemError> {
    let used = match ordering {
        FillOrdering::Auto => FillOrdering::auto_choice(n, sv.len()),
        o => o,
    };
    if ordering == FillOrdering::Auto
        && used == FillOrdering::Metis
        && let Some((gperm, elimination)) = flat_geometric(sv, n, coords, GEOMETRIC_MAX_CONSTANT)?
    {
        return Ok((gperm, FillOrdering::Geometric, Some(elimination)));
    }
    if ordering == FillOrdering::Auto && used == FillOrdering::BlockAmd && probes_metis(sv) {
        let (gperm, used) = cheaper_of_metis_and_amd(sv)?;
        return Ok((gperm, used, None));
    }
    let gperm = match used {
        FillOrdering::Metis => metis_groups(sv)?,
        FillOrdering::Geometric => {
            let coords = coords
                .filter(|c| c.at.len() == n)
                .ok_or_else(missing_positions)?;
            geometric_groups(sv, coords)
        }
        _ => amd_order(sv)?,
    };
    Ok((gperm, used, None))
}

/// The error of [`FillOrdering::Geometric`] without a position per unknown.
fn missing_positions() -> FemError {
    FemError::Symbolic(
        "the `geometric` ordering needs the vertex positions (NewtonSolver::with_geometry)".into(),
    )
}

/// The error of an ordering this build does not have.
fn missing_feature(ordering: FillOrdering) -> FemError {
    FemError::Symbolic(format!(
        "the `{}` ordering needs ecc-fem built with the `metis` feature",
        ordering.name()
    ))
}

/// Geometric nested dissection of the group graph, each group at the
/// position of its first unknown: the dissection `coords` carries when it
/// is one of the groups ([`Coordinates::dissection`]), else computed here.
fn geometric_groups(sv: &Supervariables, coords: &Coordinates) -> Vec<usize> {
    if let Some(gperm) = coords
        .dissection
        .as_deref()
        .and_then(|d| given_groups(sv, d))
    {
        return gperm;
    }
    let pos: Vec<[f64; 3]> = sv.start[..sv.len()].iter().map(|&u| coords.at[u]).collect();
    let graph = ecc_mesh::dissection::Graph {
        ptr: &sv.adj_ptr,
        idx: &sv.adj,
    };
    ecc_mesh::dissection::nested_dissection(graph, &pos)
}

/// The group permutation naming the groups in the order of `firsts` (the
/// first unknown of each vertex in a dissection's order), or `None` unless
/// `firsts` names every group exactly once by its first unknown.
fn given_groups(sv: &Supervariables, firsts: &[usize]) -> Option<Vec<usize>> {
    let n = *sv.start.last()?;
    if firsts.len() != sv.len() {
        return None;
    }
    let mut group = vec![usize::MAX; n];
    for g in 0..sv.len() {
        group[sv.start[g]] = g;
    }
    let mut seen = vec![false; sv.len()];
    firsts
        .iter()
        .map(|&u| {
            let g = *group.get(u)?;
            (g != usize::MAX && !std::mem::replace(&mut seen[g], true)).then_some(g)
        })
        .collect()
}

/// Largest cost of the geometric dissection's factor, Σ c² over the
/// vertex graph's factor columns (`group_flops`) per g^1.5 (g vertex
/// groups), at which [`FillOrdering::Auto`] takes the geometric ordering
/// where it would otherwise run METIS (2D, ≥ [`METIS_MIN_UNKNOWNS`],
/// positions known).
///
/// Nested dissection of a planar mesh costs ≈ c·g^1.5 flops. Measured c
/// (vertex graphs of the triangle meshes, 2026-12-03): flat square grids
/// of 15k / 91k / 491k vertices geometric 17.1 / 18.4 / 19.1, METIS 17.2 /
/// 18.6 / 19.1; the bumpy disk (68k / 503k vertices) geometric 23.0 /
/// 23.9, METIS 20.1 / 20.9; curved surfaces, where a plane cuts the
/// surface many times: the flat 491k grid rolled three times round an axis
/// 57.4, camelhead 47.8 (METIS 15.7), armadillo_cut_low 31.4 and
/// hand_1_i_f5000 31.6 (METIS 4.9 and 10.9: meshes cut open along seams).
/// So an accepted geometric ordering costs at most ≈ 1.4× what METIS
/// reaches on a flat mesh, and a curved or seam-cut one goes to METIS.
///
/// Until stop 31 the bound was relative, 0.85 × block AMD's cost, which
/// cost computing block AMD (0.4 s of setup on the 1M disk) and depended on
/// AMD's tie-breaking: the same disk in another vertex order gave block AMD
/// c = 21.7 instead of ≈ 29.5, a ratio of 1.10 instead of 0.81, which would
/// have sent it to METIS's 3.5 s ordering.
pub const GEOMETRIC_MAX_CONSTANT: f64 = 28.0;

/// The geometric dissection's group permutation and its elimination when
/// the unknowns have positions and its factor costs at most `max_constant`
/// · g^1.5 ([`GEOMETRIC_MAX_CONSTANT`]), else `None`.
fn flat_geometric(
    sv: &Supervariables,
    n: usize,
    coords: Option<&Coordinates>,
    max_constant: f64,
) -> Result<Option<(Vec<usize>, GroupElimination)>, FemError> {
    let Some(coords) = coords.filter(|c| c.at.len() == n) else {
        return Ok(None);
    };
    let geometric = geometric_groups(sv, coords);
    let elimination = group_elimination(sv, &geometric)?;
    let constant = per_nd_scale(flops_of(&elimination.counts), sv.len());
    Ok((constant <= max_constant).then_some((geometric, elimination)))
}

/// Σ c² over the columns c of the Cholesky factor of the group graph
/// (diagonal included) in the order `gperm` (`gperm[new] = old`): the
/// flops measure of the factor with one unknown per group, from faer's
/// elimination tree and column counts (no symbolic factorisation).
fn group_flops(sv: &Supervariables, gperm: &[usize]) -> Result<f64, FemError> {
    Ok(flops_of(&group_elimination(sv, gperm)?.counts))
}

/// A factor cost `flops` of a graph of `groups` vertices per groups^1.5:
/// the constant c of nested dissection's c·g^1.5 on a planar mesh, which
/// [`GEOMETRIC_MAX_CONSTANT`] and [`METIS_PROBE_MIN_CONSTANT`] bound.
fn per_nd_scale(flops: f64, groups: usize) -> f64 {
    flops / (groups as f64).powf(1.5)
}

/// Σ c² over column counts.
fn flops_of(counts: &[usize]) -> f64 {
    counts.iter().map(|&c| (c as f64).powi(2)).sum()
}

/// The [`GroupElimination`] of the group graph in the order `gperm`, from
/// faer's elimination tree and column counts.
fn group_elimination(sv: &Supervariables, gperm: &[usize]) -> Result<GroupElimination, FemError> {
    let ng = sv.len();
    let (cp, ri) = sv.upper(gperm);
    let a = SymbolicSparseColMatRef::new_checked(ng, ng, &cp, None, &ri);
    let mut etree = vec![0isize; ng];
    let mut counts = vec![0usize; ng];
    let req = simplicial::prefactorize_symbolic_cholesky_scratch::<usize>(ng, ri.len());
    let mut mem = MemBuffer::try_new(req)
        .map_err(|_| FemError::Symbolic("out of memory for the column counts".into()))?;
    simplicial::prefactorize_symbolic_cholesky(&mut etree, &mut counts, a, MemStack::new(&mut mem));
    let sizes = gperm
        .iter()
        .map(|&g| sv.start[g + 1] - sv.start[g])
        .collect();
    Ok(GroupElimination {
        etree,
        counts,
        sizes,
    })
}

/// The 2D systems (unknowns) for which [`FillOrdering::Auto`] may compute
/// METIS beside block AMD ([`METIS_PROBE_MIN_CONSTANT`]) and keep the
/// cheaper factor ([`METIS_MAX_RATIO`]). Below, a factorisation costs about
/// a millisecond (hand_1_i_f5000, 5k unknowns), less than METIS itself;
/// above, computing METIS costs more than it can save before these solves
/// converge: on the 136k-unknown bumpy disk it added 0.35–0.40 s to a
/// 0.45 s setup (`ecc sim`, three alternating runs) and would save 18 ms
/// per factorisation, 4 factorisations in all.
pub const METIS_PROBE_UNKNOWNS: std::ops::Range<usize> = 10_000..50_000;

/// Largest ratio of METIS's factor cost to block AMD's (`group_flops` on the
/// vertex graph) at which [`FillOrdering::Auto`] takes METIS below
/// [`METIS_MIN_UNKNOWNS`]. Measured (ordering.md, "METIS where it pays"):
/// camelhead 0.54, where METIS's split factorisations took 0.30–0.34 s
/// against 0.41–0.53 s over the same 19 and its analysis 0.05 s more
/// (`ecc sim`, alternating runs); the 136k-unknown bumpy disk 0.70, where
/// METIS saves 18 ms per factorisation for 0.24 s more analysis (13
/// factorisations to pay, 8–9 Newton steps): a factor with smaller
/// supernodes gains less than its flops say, hence the margin.
pub const METIS_MAX_RATIO: f64 = 0.6;

/// Block AMD's factor cost (`group_flops`) per g^1.5 (g vertex groups)
/// below which [`FillOrdering::Auto`] does not compute METIS for a 2D system
/// under [`METIS_MIN_UNKNOWNS`]: nested dissection of a planar mesh costs
/// ≈ c·g^1.5 flops, and METIS's c measured 15 (camelhead) to 20 (bumpy
/// disk, 68k vertices), so block AMD under 12·g^1.5 leaves METIS little to
/// gain. Measured block AMD: camelhead 28.6 (METIS taken, ratio 0.54),
/// the 136k-unknown bumpy disk 28.5 (METIS 0.70 of it; above the probed
/// sizes), armadillo_cut_low 4.5 (a mesh cut open along seams; METIS 4.8,
/// not computed).
pub const METIS_PROBE_MIN_CONSTANT: f64 = 12.0;

/// Whether [`FillOrdering::Auto`] may price METIS against block AMD here:
/// METIS compiled in and a 2D system (fewer than 2.5 unknowns per group)
/// with a number of unknowns in [`METIS_PROBE_UNKNOWNS`].
fn probes_metis(sv: &Supervariables) -> bool {
    let n = sv.start.last().copied().unwrap_or(0);
    FillOrdering::Metis.is_available() && two_d(n, sv.len()) && METIS_PROBE_UNKNOWNS.contains(&n)
}

/// Whether `n` unknowns in `groups` vertex groups are a 2D system: fewer
/// than 2.5 unknowns per group.
fn two_d(n: usize, groups: usize) -> bool {
    2 * n < 5 * groups
}

/// Block AMD's group permutation, or METIS's where that is much cheaper:
/// when block AMD's factor costs at least [`METIS_PROBE_MIN_CONSTANT`] ×
/// g^1.5 (g groups) METIS is computed too and taken if its `group_flops`
/// are at most [`METIS_MAX_RATIO`] × block AMD's. The group permutation and
/// the ordering it is.
fn cheaper_of_metis_and_amd(sv: &Supervariables) -> Result<(Vec<usize>, FillOrdering), FemError> {
    let amd = amd_order(sv)?;
    let amd_flops = group_flops(sv, &amd)?;
    if per_nd_scale(amd_flops, sv.len()) < METIS_PROBE_MIN_CONSTANT {
        return Ok((amd, FillOrdering::BlockAmd));
    }
    let metis = metis_groups(sv)?;
    Ok(if group_flops(sv, &metis)? <= METIS_MAX_RATIO * amd_flops {
        (metis, FillOrdering::Metis)
    } else {
        (amd, FillOrdering::BlockAmd)
    })
}

/// METIS's group permutation (an error without the feature).
fn metis_groups(sv: &Supervariables) -> Result<Vec<usize>, FemError> {
    #[cfg(feature = "metis")]
    return metis_nd::node_nd(sv);
    #[cfg(not(feature = "metis"))]
    Err(missing_feature(FillOrdering::Metis))
}

#[cfg(feature = "metis")]
mod metis_nd {
    use super::Supervariables;
    use crate::error::FemError;

    /// Held around every METIS call: METIS keeps its random number
    /// generator in process-wide statics (GKlib's Mersenne twister `mt[]`,
    /// `mti` in `random.c`), reseeded by every `METIS_NodeND`. Two solvers
    /// ordering at once in one process (threads of a Dask worker, a Rust
    /// caller's own threads) would race on them: a nondeterministic
    /// ordering, or a read past `mt[]` when both advance `mti` at once.
    static METIS: std::sync::Mutex<()> = std::sync::Mutex::new(());

    /// `METIS_NodeND` on the group graph, weights = group sizes.
    pub(super) fn node_nd(sv: &Supervariables) -> Result<Vec<usize>, FemError> {
        let ng = sv.len();
        if ng == 0 {
            return Ok(Vec::new());
        }
        let idx = |v: usize| {
            i32::try_from(v).map_err(|_| FemError::Symbolic("graph too large for METIS".into()))
        };
        let mut nvtxs = idx(ng)?;
        let mut xadj = sv
            .adj_ptr
            .iter()
            .map(|&v| idx(v))
            .collect::<Result<Vec<_>, _>>()?;
        let mut adjncy = sv
            .adj
            .iter()
            .map(|&v| idx(v))
            .collect::<Result<Vec<_>, _>>()?;
        let mut vwgt = (0..ng)
            .map(|g| idx(sv.start[g + 1] - sv.start[g]))
            .collect::<Result<Vec<_>, _>>()?;
        let mut perm = vec![0i32; ng];
        let mut iperm = vec![0i32; ng];
        // SAFETY: every array has the length METIS reads (nvtxs + 1, xadj[nvtxs],
        // nvtxs, nvtxs, nvtxs); options = NULL selects METIS's defaults.
        // a panic elsewhere while holding the lock leaves METIS's state as
        // valid as any finished call does: the poison is ignored
        let _one_at_a_time = METIS.lock().unwrap_or_else(|e| e.into_inner());
        let status = unsafe {
            metis_sys::METIS_NodeND(
                &mut nvtxs,
                xadj.as_mut_ptr(),
                adjncy.as_mut_ptr(),
                vwgt.as_mut_ptr(),
                std::ptr::null_mut(),
                perm.as_mut_ptr(),
                iperm.as_mut_ptr(),
            )
        };
        if status != metis_sys::rstatus_et_METIS_OK {
            return Err(FemError::Symbolic(format!(
                "METIS_NodeND failed (status {status})"
            )));
        }
        Ok(perm.into_iter().map(|p| p as usize).collect())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::dofs::DofMap;
    use crate::pattern::{StencilSet, build};

    /// Triangles of an nx×ny grid, `dim` unknowns per vertex.
    pub(crate) fn grid(nx: usize, ny: usize, dim: usize) -> Pattern {
        grid_with(nx, ny, DofMap::all_free((nx + 1) * (ny + 1), dim).unwrap())
    }

    /// Triangles of an nx×ny grid over the DOF map `dofs` ((nx + 1)(ny + 1)
    /// vertices).
    pub(crate) fn grid_with(nx: usize, ny: usize, dofs: DofMap) -> Pattern {
        let v = |i: usize, j: usize| i + j * (nx + 1);
        let mut tris = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                tris.extend([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
                tris.extend([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
            }
        }
        let set = StencilSet {
            name: "t",
            arity: 3,
            stencils: &tris,
        };
        build(&[set], &dofs).unwrap().0
    }

    /// The position of every unknown of [`grid`]: vertex (i, j) at (i, j, 0).
    pub(crate) fn grid_coords(nx: usize, ny: usize, dim: usize) -> Vec<[f64; 3]> {
        let n = (nx + 1) * (ny + 1) * dim;
        (0..n)
            .map(|u| {
                let v = u / dim;
                [(v % (nx + 1)) as f64, (v / (nx + 1)) as f64, 0.0]
            })
            .collect()
    }

    fn is_permutation(p: &[usize], n: usize) -> bool {
        let mut seen = vec![false; n];
        p.len() == n
            && p.iter()
                .all(|&i| i < n && !std::mem::replace(&mut seen[i], true))
    }

    #[test]
    fn supervariables_are_the_vertices() {
        for dim in [1, 2, 3] {
            let p = grid(4, 3, dim);
            let sv = Supervariables::of(&p);
            assert_eq!(sv.len(), 20, "dim {dim}");
            assert!(sv.start.windows(2).all(|w| w[1] - w[0] == dim));
            // interior vertex (1,1) = 6: 6 neighbours in this triangulation
            assert_eq!(sv.adj_ptr[7] - sv.adj_ptr[6], 6);
        }
    }

    /// The groups from a built pattern's vertex blocks are those detected
    /// from its entries alone: vertices with some DOFs fixed, a renumbered
    /// DOF map, untouched vertices, and consecutive vertices with the same
    /// closed neighbourhood (merged).
    #[test]
    fn supervariables_from_vertex_blocks_are_the_detected_ones() {
        use crate::pattern::{StencilSet, build};
        let tris = [0, 1, 2, 2, 1, 3, 3, 1, 4, 5, 6, 7, 1, 4, 8, 4, 9, 8];
        for dim in [1, 2, 3] {
            let mut fixed = vec![false; 11 * dim];
            fixed[dim] = true; // vertex 1's first coordinate
            fixed[5 * dim..6 * dim].iter_mut().for_each(|f| *f = true);
            let order = [3, 0, 10, 9, 1, 8, 2, 4, 6, 5, 7];
            for dofs in [
                DofMap::all_free(11, dim).unwrap(),
                DofMap::from_dof_mask(11, dim, &fixed).unwrap(),
                DofMap::from_dof_mask(11, dim, &fixed)
                    .unwrap()
                    .renumbered(&order),
            ] {
                let set = StencilSet {
                    name: "t",
                    arity: 3,
                    stencils: &tris,
                };
                let built = build(&[set], &dofs).unwrap().0;
                assert!(built.vertex_blocks().is_some());
                let plain = Pattern::from_upper_csc(
                    built.n(),
                    built.col_ptr().to_vec(),
                    built.row_idx().to_vec(),
                )
                .unwrap();
                let (a, b) = (Supervariables::of(&built), Supervariables::of(&plain));
                assert_eq!(a.start, b.start, "dim {dim}");
                assert_eq!((a.adj_ptr, a.adj), (b.adj_ptr, b.adj), "dim {dim}");
            }
        }
        // the triangle 5 6 7 alone: its vertices merge into one group
        let dofs = DofMap::all_free(3, 2).unwrap();
        let set = StencilSet {
            name: "t",
            arity: 3,
            stencils: &[0, 1, 2],
        };
        let sv = Supervariables::of(&build(&[set], &dofs).unwrap().0);
        assert_eq!(sv.start, [0, 6]);
    }

    #[test]
    fn names_round_trip() {
        for o in FillOrdering::ALL {
            assert_eq!(FillOrdering::from_name(o.name()), Some(o));
            let json = serde_json::to_string(&o).unwrap();
            assert_eq!(json, format!("\"{}\"", o.name()));
        }
        assert_eq!(FillOrdering::from_name("nested"), None);
        assert!(FillOrdering::default().is_available());
    }

    /// `Auto`: METIS only for large 2D systems and when compiled in; a
    /// small grid gets exactly block AMD's permutation.
    #[test]
    fn auto_is_block_amd_below_the_size_and_in_3d() {
        use super::METIS_MIN_UNKNOWNS as M;
        let metis = if cfg!(feature = "metis") {
            FillOrdering::Metis
        } else {
            FillOrdering::BlockAmd
        };
        assert_eq!(FillOrdering::auto_choice(M, M / 2), metis);
        assert_eq!(
            FillOrdering::auto_choice(M - 2, M / 2 - 1),
            FillOrdering::BlockAmd
        );
        assert_eq!(FillOrdering::auto_choice(3 * M, M), FillOrdering::BlockAmd);
        assert_eq!(FillOrdering::default(), FillOrdering::Auto);
        assert_eq!(FillOrdering::from_name("auto"), Some(FillOrdering::Auto));
        let p = grid(7, 5, 2);
        let (auto, used) = permutation(&p, FillOrdering::Auto, None).unwrap();
        assert_eq!(used, FillOrdering::BlockAmd);
        assert_eq!(
            auto,
            permutation(&p, FillOrdering::BlockAmd, None).unwrap().0
        );
    }

    #[test]
    fn every_available_ordering_is_a_permutation_keeping_blocks() {
        let p = grid(7, 5, 2);
        let coords: Coordinates = grid_coords(7, 5, 2).into();
        for o in FillOrdering::ALL.into_iter().filter(|o| o.is_available()) {
            let (perm, used) = permutation(&p, o, Some(&coords)).unwrap();
            assert_eq!(used, o);
            let Some(perm) = perm else {
                assert_eq!(o, FillOrdering::Amd);
                continue;
            };
            assert!(is_permutation(&perm, p.n()), "{o:?}");
            for pair in perm.chunks_exact(2) {
                assert_eq!(pair[0] % 2, 0, "{o:?}: a vertex's unknowns stay together");
                assert_eq!(pair[1], pair[0] + 1, "{o:?}");
            }
        }
    }

    /// METIS from many threads at once (each call reseeds and draws from
    /// METIS's process-wide random state) gives every thread the ordering
    /// of a call on its own: the calls are serialised.
    #[cfg(feature = "metis")]
    #[test]
    fn concurrent_metis_orderings_are_those_of_one_at_a_time() {
        let p = grid(30, 30, 2);
        let alone = permutation(&p, FillOrdering::Metis, None).unwrap().0;
        std::thread::scope(|s| {
            let runs: Vec<_> = (0..8)
                .map(|_| {
                    s.spawn(|| {
                        (0..4)
                            .map(|_| permutation(&p, FillOrdering::Metis, None).unwrap().0)
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            for r in runs {
                for perm in r.join().unwrap() {
                    assert_eq!(perm, alone);
                }
            }
        });
    }

    /// Σ c² of the factor of a path graph in its natural order: every
    /// column but the last has two entries (itself and its successor).
    #[test]
    fn group_flops_counts_the_factor_columns() {
        let n: usize = 9;
        let lists: Vec<Vec<usize>> = (0..n)
            .map(|v| {
                [v.wrapping_sub(1), v + 1]
                    .into_iter()
                    .filter(|&u| u < n)
                    .collect()
            })
            .collect();
        let mut adj_ptr = vec![0];
        lists
            .iter()
            .for_each(|l| adj_ptr.push(adj_ptr.last().unwrap() + l.len()));
        let sv = Supervariables {
            start: (0..=n).collect(),
            adj_ptr,
            adj: lists.concat(),
        };
        let natural: Vec<usize> = (0..n).collect();
        assert_eq!(
            group_flops(&sv, &natural).unwrap(),
            (4 * (n - 1) + 1) as f64
        );
        // the middle vertex first: its two neighbours fill in, one column of 3
        let mut mid_first = natural.clone();
        mid_first.swap(0, n / 2);
        assert!(group_flops(&sv, &mid_first).unwrap() > (4 * (n - 1) + 1) as f64);
    }

    /// The grid's vertices rolled three times round the z axis (a spiral
    /// sheet): the same graph as [`grid_coords`]'s flat one, curved in 3D.
    fn rolled_coords(nx: usize, ny: usize, dim: usize) -> Vec<[f64; 3]> {
        grid_coords(nx, ny, dim)
            .into_iter()
            .map(|[x, y, _]| {
                let t = 3.0 * std::f64::consts::TAU * x / nx as f64;
                let r = 5.0 + x / 12.0;
                [r * t.cos(), r * t.sin(), y]
            })
            .collect()
    }

    /// The geometric dissection is taken when its vertex-graph factor costs
    /// little enough per g^1.5: the flat grid (c ≈ 17.1 at this size)
    /// passes [`GEOMETRIC_MAX_CONSTANT`] and not a bound of 16, the rolled
    /// one (≈ 43) does not pass; without positions there is nothing to
    /// dissect.
    #[test]
    fn the_geometric_ordering_is_taken_only_where_flat() {
        let (nx, dim) = (120, 2);
        let p = grid(nx, nx, dim);
        let sv = Supervariables::of(&p);
        let n = p.n();
        let flat: Coordinates = grid_coords(nx, nx, dim).into();
        let max = GEOMETRIC_MAX_CONSTANT;
        let (got, elimination) = flat_geometric(&sv, n, Some(&flat), max).unwrap().unwrap();
        assert_eq!(got, geometric_groups(&sv, &flat));
        assert_eq!(elimination, group_elimination(&sv, &got).unwrap());
        let c = per_nd_scale(group_flops(&sv, &got).unwrap(), sv.len());
        assert!((16.5..18.0).contains(&c), "{c}");
        assert!(flat_geometric(&sv, n, Some(&flat), 16.0).unwrap().is_none());
        let rolled: Coordinates = rolled_coords(nx, nx, dim).into();
        assert!(
            flat_geometric(&sv, n, Some(&rolled), max)
                .unwrap()
                .is_none()
        );
        let (rolled_perm, _) = flat_geometric(&sv, n, Some(&rolled), 50.0)
            .unwrap()
            .unwrap();
        let c = per_nd_scale(group_flops(&sv, &rolled_perm).unwrap(), sv.len());
        assert!((40.0..46.0).contains(&c), "{c}");
        assert!(
            flat_geometric(&sv, n, None, f64::INFINITY)
                .unwrap()
                .is_none()
        );
    }

    /// A dissection given with the coordinates is the geometric ordering's
    /// group order when it names every group once by its first unknown
    /// (here: the computed one reversed, which no dissection gives); one
    /// that names a group twice, misses one or names an unknown that does
    /// not start a group is not used (the groups are dissected).
    #[test]
    fn a_given_dissection_is_used_only_when_it_is_one_of_the_groups() {
        let (nx, dim) = (20, 2);
        let p = grid(nx, nx, dim);
        let sv = Supervariables::of(&p);
        let mut coords: Coordinates = grid_coords(nx, nx, dim).into();
        let own = geometric_groups(&sv, &coords);
        let firsts: Vec<usize> = own.iter().rev().map(|&g| sv.start[g]).collect();
        coords.dissection = Some(firsts.clone().into());
        let want: Vec<usize> = own.iter().rev().copied().collect();
        assert_eq!(geometric_groups(&sv, &coords), want);
        let (perm, used) = permutation(&p, FillOrdering::Geometric, Some(&coords)).unwrap();
        assert_eq!(
            (perm.unwrap(), used),
            (sv.expand(&want), FillOrdering::Geometric)
        );
        let mut twice = firsts.clone();
        twice[1] = twice[0];
        let mut inside = firsts.clone();
        inside[3] += 1;
        for bad in [twice, firsts[1..].to_vec(), inside] {
            coords.dissection = Some(bad.into());
            assert_eq!(geometric_groups(&sv, &coords), own);
        }
    }

    #[cfg(not(feature = "metis"))]
    #[test]
    fn metis_without_the_feature_is_a_clear_error() {
        let e = permutation(&grid(2, 2, 2), FillOrdering::Metis, None).unwrap_err();
        assert!(format!("{e}").contains("`metis` feature"), "{e}");
    }

    #[test]
    fn geometric_without_positions_is_a_clear_error() {
        let p = grid(2, 2, 2);
        let short: Coordinates = grid_coords(2, 1, 2).into();
        for coords in [None, Some(&short)] {
            let e = permutation(&p, FillOrdering::Geometric, coords).unwrap_err();
            assert!(format!("{e}").contains("vertex positions"), "{e}");
        }
    }

    /// On a 40×40 grid (large enough for several levels of dissection) the
    /// geometric ordering's factor is within 1.3× of METIS's (when compiled
    /// in) and block AMD's fill.
    #[test]
    fn geometric_fill_is_close_to_the_others() {
        use faer::sparse::linalg::cholesky::{SymmetricOrdering, factorize_symbolic_cholesky};
        let (nx, ny) = (40, 40);
        let p = grid(nx, ny, 2);
        let coords: Coordinates = grid_coords(nx, ny, 2).into();
        let fill = |o: FillOrdering| {
            let perm = permutation(&p, o, Some(&coords)).unwrap().0.unwrap();
            let inv = ecc_mesh::dissection::inverse_permutation(&perm);
            let a =
                SymbolicSparseColMatRef::new_checked(p.n(), p.n(), p.col_ptr(), None, p.row_idx());
            let ord =
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(&perm, &inv, p.n()));
            factorize_symbolic_cholesky(a, faer::Side::Upper, ord, Default::default())
                .unwrap()
                .len_val() as f64
        };
        let geo = fill(FillOrdering::Geometric);
        for o in [FillOrdering::BlockAmd, FillOrdering::Metis] {
            if o.is_available() {
                let other = fill(o);
                assert!(geo <= 1.3 * other, "geometric {geo} vs {o:?} {other}");
            }
        }
    }
}
