//! The effect terms, each an [`ecc_fem::Term`]: gravity, inertia and mass
//! damping (a quadratic mass form), stiffness damping, the ground, and the
//! interpolation blend. Each counts its passes in [`crate::Counters`].

pub mod blend;
pub mod damping;
pub mod fibre;
pub mod gravity;
pub mod ground;
pub mod mass;

pub use blend::Blend;
pub use damping::StiffnessDamping;
pub use gravity::Gravity;
pub use ground::Ground;
pub use mass::{MassMatrix, MassQuadratic, vertex_masses};
