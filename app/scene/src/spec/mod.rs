//! The scene file: data model, reading with located errors, validation.

mod fibre;
mod load;
mod model;
mod spans;
pub mod validate;

pub(crate) use load::suggest as suggest_name;
pub use fibre::{AroundSpec, FibreSpec};
pub use load::{SceneFile, data_dir};
pub use model::*;
