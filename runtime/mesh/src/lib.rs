//! ecc-mesh: triangle and tetrahedral meshes for ecc.
//!
//! (Readers, writers, validation, generators and the Tutte embedding are
//! being added; the types in [`types`] and [`error`] are the stable contract.)

pub mod error;
pub mod types;

pub use error::{MeshError, ParseError, TutteError, ValidationError};
pub use types::{AnyMesh, TetMesh, TriMesh, TutteWeights, Validated, ValidationOptions};
