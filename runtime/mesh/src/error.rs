//! Error types: reading/writing ([`MeshError`]), text parsing
//! ([`ParseError`]), validation ([`ValidationError`]) and the Tutte
//! embedding ([`TutteError`]).

use std::path::PathBuf;

/// A problem found by a text parser (`parse_obj`, `parse_off`, …), before a
/// path is attached.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseError {
    /// Something is wrong on a given (1-based) line.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file as a whole is wrong (missing section, wrong kind, …).
    #[error("{message}")]
    Format {
        /// What is wrong.
        message: String,
    },
}

impl ParseError {
    /// Shorthand for [`ParseError::Line`].
    pub fn line(line: usize, message: impl Into<String>) -> Self {
        ParseError::Line {
            line,
            message: message.into(),
        }
    }

    /// Shorthand for [`ParseError::Format`].
    pub fn format(message: impl Into<String>) -> Self {
        ParseError::Format {
            message: message.into(),
        }
    }

    /// Attach the file path.
    pub fn at(self, path: impl Into<PathBuf>) -> MeshError {
        let path = path.into();
        match self {
            ParseError::Line { line, message } => MeshError::Parse {
                path,
                line,
                message,
            },
            ParseError::Format { message } => MeshError::Format { path, message },
        }
    }
}

/// Reading or writing a mesh file failed.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The operating system refused (missing file, permissions, full disk, …).
    #[error("{}: {source}", path.display())]
    Io {
        /// The file involved.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A line of the file could not be understood.
    #[error("{}:{line}: {message}", path.display())]
    Parse {
        /// The file involved.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file as a whole is malformed or unsupported.
    #[error("{}: {message}", path.display())]
    Format {
        /// The file involved.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The file extension is not one of `.obj .off .mesh .msh .vtk`.
    #[error(
        "{}: unsupported mesh file extension {extension:?} (expected .obj, .off, .mesh, .msh or .vtk)",
        path.display()
    )]
    UnsupportedExtension {
        /// The file involved.
        path: PathBuf,
        /// The extension found (empty if none).
        extension: String,
    },
    /// The file holds the other kind of mesh.
    #[error("{}: expected a {expected} mesh but the file holds a {found} mesh", path.display())]
    WrongKind {
        /// The file involved.
        path: PathBuf,
        /// `"triangle"` or `"tetrahedral"`.
        expected: &'static str,
        /// `"triangle"` or `"tetrahedral"`.
        found: &'static str,
    },
    /// Data handed to a writer is inconsistent (bad point-data length, bad
    /// name, non-finite value, …). Nothing was written.
    #[error("{}: {message}", path.display())]
    Data {
        /// The file that was to be written.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The mesh failed validation.
    #[error("invalid mesh: {0}")]
    Invalid(#[from] ValidationError),
}

/// Why a mesh failed validation. Element and vertex ids are 0-based indices
/// into the mesh given to the validator.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ValidationError {
    /// The mesh has no elements.
    #[error("the mesh has no elements")]
    NoElements,
    /// An element refers to a vertex that does not exist.
    #[error(
        "element {element} refers to vertex {index}, but there are only {vertex_count} vertices (valid ids 0..{vertex_count})"
    )]
    IndexOutOfRange {
        /// Element id.
        element: usize,
        /// The offending vertex index.
        index: usize,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// An element uses the same vertex twice.
    #[error("element {element} uses a vertex more than once: {vertices:?}")]
    RepeatedVertexInElement {
        /// Element id.
        element: usize,
        /// The element's vertex ids.
        vertices: Vec<usize>,
    },
    /// Two elements have the same vertex set.
    #[error("element {element} duplicates element {first} (same vertices)")]
    DuplicateElement {
        /// The later element id.
        element: usize,
        /// The earlier element with the same vertices.
        first: usize,
    },
    /// A referenced vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate {position:?}")]
    NonFiniteCoordinate {
        /// Vertex id.
        vertex: usize,
        /// Its position.
        position: [f64; 3],
    },
    /// A planar mesh has a vertex off the plane `z = 0`.
    #[error("vertex {vertex} of a planar mesh has z = {z} (planar meshes need z = 0)")]
    NotPlanar {
        /// Vertex id.
        vertex: usize,
        /// Its z coordinate.
        z: f64,
    },
    /// The per-vertex texture coordinates do not match the vertices.
    #[error("the mesh has {uvs} texture coordinates for {vertices} vertices")]
    UvCountMismatch {
        /// Number of uvs.
        uvs: usize,
        /// Number of vertices.
        vertices: usize,
    },
    /// A texture coordinate is NaN or infinite.
    #[error("texture coordinate of vertex {vertex} is not finite: {uv:?}")]
    NonFiniteUv {
        /// Vertex id.
        vertex: usize,
        /// Its uv.
        uv: [f64; 2],
    },
    /// The rest element has (nearly) zero area/volume.
    #[error(
        "element {element} is degenerate: {}",
        degenerate_detail(*measure, *tolerance, *dimension)
    )]
    DegenerateElement {
        /// Element id.
        element: usize,
        /// Its signed area (planar) / unsigned area (surface) / signed volume.
        measure: f64,
        /// The absolute tolerance used (`DEGENERATE_REL_TOL · L^d / den`,
        /// `L` the element's longest edge, `den` = 2 or 6).
        tolerance: f64,
        /// 2 for triangles, 3 for tets.
        dimension: usize,
    },
    /// The rest element has negative signed area (planar) or volume (tets).
    #[error(
        "element {element} is inverted: signed rest {} {measure:e} < 0 ({count} of {total} elements are inverted{})",
        if *dimension == 2 { "area" } else { "volume" },
        if count == total { "; the whole mesh has the opposite orientation: swap two vertices of every element" } else { "" }
    )]
    InvertedElement {
        /// The first inverted element id.
        element: usize,
        /// Its signed measure.
        measure: f64,
        /// How many elements are inverted.
        count: usize,
        /// Number of elements.
        total: usize,
        /// 2 for triangles, 3 for tets.
        dimension: usize,
    },
    /// Elements whose quality (rest measure ÷ longest edge^d) is below
    /// `ValidationOptions::min_quality`.
    #[error(
        "{count} of {total} elements have a quality (rest {} ÷ longest edge{}) below the minimum {min_quality:e}: elements {}; the worst is element {worst} ({quality:e})",
        if *dimension == 2 { "area" } else { "volume" },
        if *dimension == 2 { "²" } else { "³" },
        id_list(*count, first)
    )]
    LowQualityElements {
        /// How many.
        count: usize,
        /// Number of elements.
        total: usize,
        /// The first few ids (at most 10).
        first: Vec<usize>,
        /// The element of lowest quality.
        worst: usize,
        /// Its quality.
        quality: f64,
        /// The minimum asked for.
        min_quality: f64,
        /// 2 for triangles, 3 for tets.
        dimension: usize,
    },
    /// An edge is shared by more than two triangles.
    #[error("edge {edge:?} is non-manifold: it is shared by triangles {faces:?}")]
    NonManifoldEdge {
        /// The edge (sorted vertex ids).
        edge: [usize; 2],
        /// The triangles using it.
        faces: Vec<usize>,
    },
    /// A triangular face is shared by more than two tets.
    #[error("face {face:?} is non-manifold: it is shared by tets {tets:?}")]
    NonManifoldFace {
        /// The face (sorted vertex ids).
        face: [usize; 3],
        /// The tets using it.
        tets: Vec<usize>,
    },
    /// The triangles around a vertex do not form a single fan (pinched
    /// vertex), or a boundary vertex has more than two boundary edges.
    #[error("vertex {vertex} is non-manifold: {reason}")]
    NonManifoldVertex {
        /// Vertex id.
        vertex: usize,
        /// What is wrong around it.
        reason: String,
    },
    /// Two triangles traverse their shared edge in the same direction.
    #[error(
        "triangles {faces:?} are inconsistently oriented: both traverse edge {edge:?} in the same direction"
    )]
    InconsistentOrientation {
        /// The directed edge.
        edge: [usize; 2],
        /// The two triangles.
        faces: [usize; 2],
    },
    /// The mesh is not connected.
    #[error("the mesh has {count} connected components (one is required)")]
    MultipleComponents {
        /// Number of components.
        count: usize,
    },
    /// Vertices that no element uses (allowed with
    /// `ValidationOptions::drop_unreferenced`, which drops them).
    #[error("{}", unreferenced(*count, first))]
    UnreferencedVertices {
        /// How many.
        count: usize,
        /// The first few ids (at most 10).
        first: Vec<usize>,
    },
}

fn id_list(count: usize, first: &[usize]) -> String {
    let ids: Vec<String> = first.iter().map(|v| v.to_string()).collect();
    let more = if count > first.len() { ", …" } else { "" };
    format!("{}{more}", ids.join(", "))
}

fn unreferenced(count: usize, first: &[usize]) -> String {
    let ids: Vec<String> = first.iter().map(|v| v.to_string()).collect();
    let more = if count > first.len() { ", …" } else { "" };
    let ids = ids.join(", ");
    if count == 1 {
        format!(
            "1 vertex is used by no element (id {ids}); remove it from the file or let it be dropped"
        )
    } else {
        format!(
            "{count} vertices are used by no element (ids {ids}{more}); remove them from the file or let them be dropped"
        )
    }
}

/// Why a Tutte embedding could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TutteError {
    /// The mesh is not a valid manifold triangle mesh.
    #[error("invalid mesh: {0}")]
    Invalid(#[from] ValidationError),
    /// The mesh does not have exactly one boundary loop.
    #[error(
        "a Tutte embedding needs a disk (exactly one boundary loop), but the mesh has {loops} boundary loops"
    )]
    NotADisk {
        /// Number of boundary loops found.
        loops: usize,
    },
    /// A vertex is used by no triangle (validate the mesh first to drop it).
    #[error(
        "vertex {vertex} is not used by any triangle (validate_tri with drop_unreferenced drops it)"
    )]
    UnreferencedVertex {
        /// Vertex id.
        vertex: usize,
    },
    /// Some vertices are not connected to the boundary.
    #[error("the mesh has {count} connected components (a disk has one)")]
    Disconnected {
        /// Number of components.
        count: usize,
    },
    /// The boundary loop has zero length.
    #[error("the boundary loop has zero length")]
    DegenerateBoundary,
    /// A weight is NaN or infinite (a degenerate triangle).
    #[error("the {weights:?} weight of edge {edge:?} is not finite (degenerate triangle nearby)")]
    BadWeight {
        /// Which weights were used.
        weights: crate::TutteWeights,
        /// The edge.
        edge: [usize; 2],
    },
    /// The sparse solver failed (singular system).
    #[error("the sparse linear solve failed: {message}")]
    Solve {
        /// Solver message.
        message: String,
    },
    /// The embedding has triangles with non-positive signed area.
    /// `uv` keeps the computed map so nothing is lost.
    #[error(
        "the embedding is not bijective: {count} triangles have non-positive signed area (first: {first})"
    )]
    Flipped {
        /// Number of flipped triangles.
        count: usize,
        /// The first flipped triangle id.
        first: usize,
        /// The computed map, one uv per vertex.
        uv: Vec<[f64; 2]>,
    },
}

/// Why an element counts as degenerate, in words. A measure or tolerance
/// that overflowed (coordinates around 1e100 and beyond) is not "below"
/// anything: say that the coordinates are out of range instead.
fn degenerate_detail(measure: f64, tolerance: f64, dimension: usize) -> String {
    let what = if dimension == 2 { "area" } else { "volume" };
    if !measure.is_finite() || !tolerance.is_finite() {
        format!(
            "its rest {what} ({measure:e}) or the size of the mesh overflows f64: \
             the coordinates are too large (scale the mesh down)"
        )
    } else {
        format!("rest {what} {measure:e} is below the tolerance {tolerance:e}")
    }
}
