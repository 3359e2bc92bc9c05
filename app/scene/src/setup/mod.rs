//! Building blocks of a scene that need files or geometry: the mesh and
//! the second rest shape of an interpolation.

pub mod mesh;
pub mod shape;
