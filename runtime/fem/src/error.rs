//! Set-up errors: everything that can be wrong with a problem *before* the
//! solver runs. Failures *during* a solve are not errors but a
//! [`crate::NewtonStatus`] on the result.

use thiserror::Error;

/// What is wrong with a problem description, and where.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum FemError {
    /// A term's flat stencil list is not a whole number of stencils.
    #[error(
        "term `{term}`: stencil list has {len} vertex indices, not a multiple of the arity {arity}"
    )]
    BadStencilList {
        term: String,
        len: usize,
        arity: usize,
    },
    /// A term declared arity 0.
    #[error("term `{term}`: stencil arity must be at least 1")]
    ZeroArity { term: String },
    /// A stencil couples more DOFs than the assembler's local buffers hold.
    #[error("term `{term}`: {dofs} DOFs per stencil, at most {max} are supported")]
    StencilTooLarge {
        term: String,
        dofs: usize,
        max: usize,
    },
    /// A stencil names a vertex that does not exist.
    #[error(
        "term `{term}`, stencil {stencil}: vertex {vertex} out of range ({n_vertices} vertices)"
    )]
    VertexOutOfRange {
        term: String,
        stencil: usize,
        vertex: usize,
        n_vertices: usize,
    },
    /// A stencil names the same vertex twice.
    #[error("term `{term}`, stencil {stencil}: vertex {vertex} appears twice")]
    RepeatedVertex {
        term: String,
        stencil: usize,
        vertex: usize,
    },
    /// A fixed vertex index does not exist.
    #[error("fixed vertex {vertex} out of range ({n_vertices} vertices)")]
    FixedOutOfRange { vertex: usize, n_vertices: usize },
    /// A per-DOF mask or a position array has the wrong length.
    #[error("{what}: expected length {expected}, got {got}")]
    LengthMismatch {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("{what}: vertex {vertex} has a non-finite coordinate")]
    NonFinitePosition { what: &'static str, vertex: usize },
    /// The problem is too large for the 32-bit index maps.
    #[error("{what} count {count} exceeds the supported maximum {max}")]
    TooLarge {
        what: &'static str,
        count: usize,
        max: usize,
    },
    /// An element's rest shape is degenerate (zero or negative measure).
    #[error("element {element}: degenerate rest shape ({reason})")]
    DegenerateRest { element: usize, reason: String },
    /// An element's fibre direction is unusable (zero or non-finite).
    #[error("element {element}: fibre direction {direction:?} is {reason}")]
    BadFibre {
        element: usize,
        direction: Vec<f64>,
        reason: &'static str,
    },
    /// The mesh has no elements.
    #[error("the mesh has no elements")]
    EmptyMesh,
    /// A mesh needed for a helper has the wrong topology.
    #[error("mesh topology: {0}")]
    Topology(String),
    /// No Tutte embedding of the surface (not a disk, not manifold, …).
    #[error("mesh topology: {0}")]
    Tutte(#[from] ecc_mesh::TutteError),
    /// The Tutte start is not a bijection (total signed uv area not positive).
    #[error("mesh topology: Tutte start has total signed area {0}")]
    TutteArea(f64),
    /// The sparse Cholesky symbolic analysis failed (out of memory, index overflow).
    #[error("sparse Cholesky symbolic analysis failed: {0}")]
    Symbolic(String),
}

impl FemError {
    /// `Ok` when `got == expected`, else [`FemError::LengthMismatch`].
    pub(crate) fn check_len(what: &'static str, expected: usize, got: usize) -> Result<(), Self> {
        if got == expected {
            Ok(())
        } else {
            Err(FemError::LengthMismatch {
                what,
                expected,
                got,
            })
        }
    }
}
