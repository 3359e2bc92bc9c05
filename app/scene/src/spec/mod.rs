//! The scene file: data model, reading with located errors, validation.

mod fibre;
mod load;
mod model;
mod spans;
pub mod validate;

pub use fibre::{AroundSpec, FibreSpec};
pub(crate) use load::suggest as suggest_name;
pub use load::{SceneFile, data_dir};
pub use model::*;
