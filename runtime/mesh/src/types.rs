//! The stable mesh types shared by readers, writers, validation, generators
//! and the FEM solver.

/// A triangle mesh: planar (every `z = 0`) or a surface in 3D.
///
/// Triangles index into `positions` (0-based). `uvs`, when present, holds one
/// texture coordinate per vertex (`uvs.len() == positions.len()`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions; planar meshes have `z = 0`.
    pub positions: Vec<[f64; 3]>,
    /// Triangles as vertex index triples, counter-clockwise for positive area
    /// in the plane.
    pub triangles: Vec<[usize; 3]>,
    /// Per-vertex texture coordinates (a parameterisation), if any.
    pub uvs: Option<Vec<[f64; 2]>>,
}

/// A tetrahedral mesh.
///
/// A tet `[a, b, c, d]` is positively oriented when
/// `vol = ((b − a) × (c − a)) · (d − a) / 6 > 0`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TetMesh {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Tetrahedra as vertex index quadruples (0-based).
    pub tets: Vec<[usize; 4]>,
}

/// A mesh of either kind, as returned by [`crate::read_mesh`].
#[derive(Clone, Debug, PartialEq)]
pub enum AnyMesh {
    /// A triangle mesh (planar or surface).
    Tri(TriMesh),
    /// A tetrahedral mesh.
    Tet(TetMesh),
}

impl AnyMesh {
    /// `"triangle"` or `"tetrahedral"` (for messages).
    pub fn kind(&self) -> &'static str {
        match self {
            AnyMesh::Tri(_) => "triangle",
            AnyMesh::Tet(_) => "tetrahedral",
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        match self {
            AnyMesh::Tri(m) => m.positions.len(),
            AnyMesh::Tet(m) => m.positions.len(),
        }
    }

    /// Number of elements (triangles or tets).
    pub fn element_count(&self) -> usize {
        match self {
            AnyMesh::Tri(m) => m.triangles.len(),
            AnyMesh::Tet(m) => m.tets.len(),
        }
    }
}

/// A rest element is degenerate when `|det Dm| ≤ DEGENERATE_REL_TOL · L^d`
/// (`L` its longest edge): the same rule and value as the element library's
/// `ecc_runtime::element::DEGENERATE_REL_TOL` (a test in ecc-fem keeps them
/// equal), so a mesh that validates is one the library accepts.
pub const DEGENERATE_REL_TOL: f64 = 1e-12;

/// What [`crate::validate_tri`] / [`crate::validate_tet`] require beyond the
/// always-on checks (indices in range, no repeated vertex in an element, no
/// duplicate element, finite coordinates, no degenerate or inverted element).
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationOptions {
    /// Reject non-manifold edges (triangles: an edge with more than two
    /// faces, a pinched vertex, a boundary vertex with more than two boundary
    /// edges; tets: a face shared by more than two tets).
    pub require_manifold: bool,
    /// Reject inconsistently oriented triangle surfaces (an interior edge
    /// used twice in the same direction). Planar meshes and tet meshes are
    /// checked by the sign of their measure instead.
    pub require_oriented: bool,
    /// Reject meshes with more than one connected component.
    pub require_single_component: bool,
    /// Refuse elements whose quality `q = |m| / L^d` (rest measure over its
    /// longest edge to the power `d`, 2 for triangles, 3 for tets; √3/4 for
    /// an equilateral triangle, 1/(6√2) for a regular tet) is below this,
    /// naming them ([`crate::ValidationError::LowQualityElements`]). The
    /// default `0` refuses only degenerate elements (`|det Dm| ≤ 1e-12·L^d`,
    /// [`DEGENERATE_REL_TOL`]), exactly what the element library refuses.
    /// Must be finite and ≥ 0 (NaN refuses nothing).
    pub min_quality: f64,
    /// Elements with quality below this (and at least `min_quality`) are
    /// kept with a warning naming them. Default `1e-5`: a triangle whose
    /// height is below `2e-5` of its longest edge; the shipped meshes' worst
    /// elements sit above it (hand.mesh: `5.5e-5`).
    pub sliver_quality: f64,
    /// Drop vertices that no element uses (with a warning, renumbering the
    /// rest; [`Validated::vertex_map`] keeps old → new ids) instead of
    /// rejecting the mesh with [`crate::ValidationError::UnreferencedVertices`].
    /// Off by default: a stray vertex usually means a broken export, and a
    /// silently renumbered mesh breaks vertex ids a user refers to.
    pub drop_unreferenced: bool,
}

impl Default for ValidationOptions {
    fn default() -> Self {
        ValidationOptions {
            require_manifold: false,
            require_oriented: false,
            require_single_component: false,
            min_quality: 0.0,
            sliver_quality: 1e-5,
            drop_unreferenced: false,
        }
    }
}

/// A mesh that passed validation.
#[derive(Clone, Debug, PartialEq)]
pub struct Validated<M> {
    /// The mesh, with unreferenced vertices removed and indices renumbered
    /// (only with [`ValidationOptions::drop_unreferenced`]; otherwise they
    /// are an error and the mesh is unchanged).
    pub mesh: M,
    /// `vertex_map[old] = Some(new)`, or `None` for a dropped
    /// (unreferenced) vertex. Its length is the input vertex count.
    pub vertex_map: Vec<Option<usize>>,
    /// Human-readable notes about what was changed (e.g. dropped vertices).
    pub warnings: Vec<String>,
}

/// Edge weights of the Tutte / Floater embedding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TutteWeights {
    /// `w_ij = 1` (Tutte's barycentric embedding). Bijective.
    Uniform,
    /// Floater's mean-value weights
    /// `w_ij = (tan(α/2) + tan(β/2)) / |x_i − x_j|`. Positive, so bijective.
    MeanValue,
    /// Cotangent weights `w_ij = (cot α_ij + cot β_ij) / 2`. Can be negative
    /// on obtuse triangles, so the map may fold.
    Cotangent,
}

impl TutteWeights {
    /// Whether the interior system is symmetric (uniform and cotangent
    /// weights): solved by Cholesky in a nested-dissection order, where
    /// mean-value weights take a sparse LU.
    pub fn is_symmetric(self) -> bool {
        matches!(self, TutteWeights::Uniform | TutteWeights::Cotangent)
    }
}
